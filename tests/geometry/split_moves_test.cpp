// A move written as many blocks (as a plan splits a move wherever its feed changes) has the engagement
// of the move itself: the closed form in the steady part, and the unsplit move's value at every sample,
// entries and exits included.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/analytic_engagement.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "test_moves.hpp"

namespace feedplan::geometry {
namespace {

constexpr double kDs = 0.1;

Move line(Point3 a, Point3 b) {
  Move m;
  m.kind = MoveKind::kLine;
  m.start = a;
  m.end = b;
  m.cutting = true;
  m.axial_depth_mm = -a.z_mm;
  return m;
}

using testing::arc;

// The part of `move` between steps k0 and k1 of `steps` equal steps, as a planner writes a block.
Move block(const Move& move, int k0, int k1, int steps) {
  Move sub = move;
  sub.start = point_at(move, static_cast<double>(k0) / steps);
  sub.end = k1 == steps ? move.end : point_at(move, static_cast<double>(k1) / steps);
  if (move.kind == MoveKind::kArc) sub.sweep_rad = move.sweep_rad * (k1 - k0) / steps;
  return sub;
}

// The move cut into blocks of 1, 2, 3, … 7 steps in turn, on the whole move's sampling grid.
std::vector<Move> blocks(const Move& move, int steps) {
  std::vector<Move> out;
  int k = 0;
  for (int width = 1; k < steps; width = width % 7 + 1) {
    const int next = std::min(steps, k + width);
    out.push_back(block(move, k, next, steps));
    k = next;
  }
  return out;
}

// The engagement along `moves` as one move each and as blocks, compared sample by sample (each
// block's end is the next one's first sample, so the two grids are the same points).
void expect_same_as_whole(const std::vector<Move>& moves, const Stock& stock, double r) {
  ToolPath whole;
  ToolPath split;
  for (const Move& move : moves) {
    whole.moves.push_back(move);
    const int steps = static_cast<int>(std::ceil(length_mm(move) / kDs - 1e-9));
    for (const Move& b : blocks(move, steps)) split.moves.push_back(b);
  }
  const auto a = compute_engagement(whole, stock, r, {.ds_mm = kDs});
  const auto b = compute_engagement(split, stock, r, {.ds_mm = kDs});
  ASSERT_EQ(a.samples.size(), b.samples.size());
  int engaged = 0;
  for (std::size_t k = 0; k < a.samples.size(); ++k) {
    ASSERT_NEAR(a.samples[k].s_mm, b.samples[k].s_mm, 1e-9);
    ASSERT_NEAR(a.samples[k].engagement_rad, b.samples[k].engagement_rad, 1e-9) << "sample " << k << " s " << a.samples[k].s_mm;
    ASSERT_NEAR(a.samples[k].chip_factor, b.samples[k].chip_factor, 1e-9) << "sample " << k;
    engaged += a.samples[k].engagement_rad > 0.0;
  }
  EXPECT_GT(engaged, 100);
}

// A slot entered from outside the stock, then a straight cut at 3 mm radial depth: entry, full slot
// and steady cut, each block of the written program alike.
TEST(SplitMoves, AStraightCutWrittenAsBlocksHasTheMovesEngagement) {
  const double r = 5.0;
  Stock stock;
  stock.z_bottom_mm = -30;
  stock.regions.push_back({Contour::rectangle({0, -60}, {200, -r + 3.0}), {}});
  const Move cut = line({-10, 0, -10}, {80, 0, -10});
  expect_same_as_whole({cut}, stock, r);

  ToolPath split;
  for (const Move& b : blocks(cut, static_cast<int>(std::ceil(length_mm(cut) / kDs - 1e-9)))) split.moves.push_back(b);
  const auto profile = compute_engagement(split, stock, r, {.ds_mm = kDs});
  const double expected = straight_engagement_rad(r, 3.0);
  for (const auto& s : profile.samples) {
    if (s.position.x_mm < 10 || s.position.x_mm > 70) continue;
    ASSERT_NEAR(s.engagement_rad, expected, 1e-6) << "x " << s.position.x_mm;
  }
}

// A trochoid-like turn: a clockwise arc inside a bore, then a second turn on the same circle (the
// tool meets what the first turn left), then a line out: engagement changes along every block.
TEST(SplitMoves, ArcsWrittenAsBlocksHaveTheArcsEngagement) {
  const double r = 5.0;
  Stock stock;
  stock.z_bottom_mm = -30;
  stock.regions.push_back({Contour::rectangle({-60, -60}, {60, 60}), {Contour::circle({0, 0}, 9.0)}});
  const Move first = arc({0, 0}, 6.0, 0.0, 1.5 * kPi, false, -10);
  const Move second = arc({1.5, 0}, 6.0, 0.5 * kPi, 2.0 * kPi, false, -10);
  const Move link = line(first.end, second.start);  // over to the second turn
  expect_same_as_whole({first, link, second, line(second.end, {30, 6, -10})}, stock, r);

  // The steady part of the first turn is the internal-arc closed form (wall 11 mm, 2 mm deep).
  ToolPath split;
  for (const Move& b : blocks(first, static_cast<int>(std::ceil(length_mm(first) / kDs - 1e-9)))) split.moves.push_back(b);
  const auto profile = compute_engagement(split, stock, r, {.ds_mm = kDs});
  const double expected = internal_arc_engagement_rad(r, 11.0, 2.0);
  int checked = 0;
  for (const auto& s : profile.samples) {
    const double angle = std::atan2(s.position.y_mm, s.position.x_mm);
    if (angle > -0.5 || angle < -2.8) continue;
    ++checked;
    ASSERT_NEAR(s.engagement_rad, expected, 1e-6) << "at " << angle;
  }
  EXPECT_GT(checked, 100);
}

}  // namespace
}  // namespace feedplan::geometry
