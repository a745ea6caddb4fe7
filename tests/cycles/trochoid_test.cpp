// Trochoid generator against the closed-form geometry of seed 003 Table 2 and Fig. 7.

#include "feedplan/cycles/trochoid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "path_checks.hpp"

namespace feedplan::cycles {
namespace {

using geometry::MoveKind;
using testing::moves_of;

const geometry::Tool kTool{"D10", 10.0, 4, 30.0};
constexpr double kTol = 1e-9;

std::vector<const geometry::Move*> circles(const Cycle& cycle) {
  std::vector<const geometry::Move*> result;
  for (const auto& m : cycle.path.moves) {
    if (m.kind == MoveKind::kArc && std::abs(m.sweep_rad - kTwoPi) < 1e-12) result.push_back(&m);
  }
  return result;
}

// Table 2: R_t = 5, p = 1, A_d = 10; centres 0..9 mm along X.
TEST(Trochoid, Table2HasTenLoopsOfTheLoopRadiusOnePitchApart) {
  const Cycle cycle = generate_trochoid({{0, 0}, {9, 0}, 5.0, 1.0, Direction::kCcw}, kTool, 10.0);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  EXPECT_TRUE(cycle.notes.empty());
  const auto loops = circles(cycle);
  ASSERT_EQ(loops.size(), 10u);
  for (std::size_t k = 0; k < loops.size(); ++k) {
    const auto& m = *loops[k];
    EXPECT_NEAR(m.center.x_mm, static_cast<double>(k), kTol);
    EXPECT_NEAR(m.center.y_mm, 0.0, kTol);
    EXPECT_NEAR(geometry::arc_radius_mm(m), 5.0, kTol);
    // Counter-clockwise, starting at the bottom point b_k = c_k − R_t·v.
    EXPECT_TRUE(m.ccw);
    EXPECT_NEAR(m.start.x_mm, static_cast<double>(k), kTol);
    EXPECT_NEAR(m.start.y_mm, -5.0, kTol);
    EXPECT_TRUE(m.cutting);
    EXPECT_EQ(m.axial_depth_mm, 10.0);
    EXPECT_NEAR(m.start.z_mm, -10.0, kTol);
    EXPECT_EQ(cycle.path.part_names[m.part], "loop " + std::to_string(k + 1));
  }
  // Steps are tangent to the circles: the whole cutting path has no corner.
  EXPECT_LT(testing::max_kink_between_cutting_moves_rad(cycle.path), 1e-9);
}

TEST(Trochoid, ToolEdgeReachesLoopRadiusPlusToolRadiusFromTheAxis) {
  const Cycle cycle = generate_trochoid({{0, 0}, {9, 0}, 5.0, 1.0, Direction::kCcw}, kTool, 10.0);
  double reach = 0;
  for (const auto& m : cycle.path.moves) {
    if (!m.cutting) continue;
    for (int i = 0; i <= 720; ++i) reach = std::max(reach, std::abs(geometry::point_at(m, i / 720.0).y_mm) + 5.0);
  }
  EXPECT_NEAR(reach, 5.0 + 5.0, 1e-9);  // slot width 2(R + r) = 20 mm (Table 2)
}

TEST(Trochoid, EntersInAirOutsideTheStockAndLeavesFromTheLastCentre) {
  const Cycle cycle = generate_trochoid({{0, 0}, {9, 0}, 5.0, 1.0, Direction::kCcw}, kTool, 10.0);
  const auto& first = cycle.path.moves.front();
  EXPECT_EQ(first.kind, MoveKind::kRapid);
  EXPECT_NEAR(first.start.z_mm, 5.0, kTol);  // default clearance above the top (z 0)
  EXPECT_NEAR(first.start.x_mm, 0.0, kTol);
  EXPECT_NEAR(first.start.y_mm, -5.0, kTol);
  for (std::size_t i : moves_of(cycle.path, "entry")) EXPECT_FALSE(cycle.path.moves[i].cutting);
  // Stock entry face at R_t + r − p = 9 along the axis; the tool at b_0 spans x in [−5, 5].
  double min_x = 1e9, max_x = -1e9, max_y = 0;
  for (const auto& v : cycle.stock.regions.at(0).outer.vertices) {
    min_x = std::min(min_x, v.x_mm);
    max_x = std::max(max_x, v.x_mm);
    max_y = std::max(max_y, std::abs(v.y_mm));
  }
  EXPECT_NEAR(min_x, 9.0, kTol);
  EXPECT_NEAR(max_x, 9.0 + 5.0 + 3 * 5.0, kTol);
  EXPECT_NEAR(max_y, 5.0 + 3 * 5.0, kTol);
  EXPECT_NEAR(cycle.stock.z_bottom_mm, -15.0, kTol);
  const auto exit = moves_of(cycle.path, "exit");
  ASSERT_EQ(exit.size(), 2u);
  EXPECT_FALSE(cycle.path.moves[exit[0]].cutting);
  EXPECT_NEAR(cycle.path.moves[exit[0]].end.x_mm, 9.0, kTol);
  EXPECT_NEAR(cycle.path.moves[exit[0]].end.y_mm, 0.0, kTol);
  EXPECT_EQ(cycle.path.moves.back().kind, MoveKind::kRapid);
  EXPECT_NEAR(cycle.path.moves.back().end.z_mm, 5.0, kTol);
}

TEST(Trochoid, PitchIsReducedToEndOnTheLastCentreAndNoted) {
  const Cycle cycle = generate_trochoid({{0, 0}, {9.5, 0}, 5.0, 1.0, Direction::kCcw}, kTool, 10.0);
  const auto loops = circles(cycle);
  ASSERT_EQ(loops.size(), 11u);  // ceil(9.5 / 1) = 10 steps
  for (std::size_t k = 0; k < loops.size(); ++k) EXPECT_NEAR(loops[k]->center.x_mm, 0.95 * k, kTol);
  ASSERT_EQ(cycle.notes.size(), 1u);
  EXPECT_NE(cycle.notes[0].find("from 1 to 0.95 mm"), std::string::npos) << cycle.notes[0];
}

TEST(Trochoid, ObliqueSlotKeepsLoopCentresOnTheAxis) {
  const double heading = deg_to_rad(30.0);
  const geometry::Point2 start{1, 2};
  const geometry::Point2 end{1 + 6 * std::cos(heading), 2 + 6 * std::sin(heading)};
  const Cycle cycle = generate_trochoid({start, end, 4.0, 1.0, Direction::kCcw}, kTool, 5.0);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const auto loops = circles(cycle);
  ASSERT_EQ(loops.size(), 7u);
  for (std::size_t k = 0; k < loops.size(); ++k) {
    EXPECT_NEAR(loops[k]->center.x_mm, start.x_mm + k * std::cos(heading), 1e-9);
    EXPECT_NEAR(loops[k]->center.y_mm, start.y_mm + k * std::sin(heading), 1e-9);
    // b_k = c_k − R_t·v with v = (−sin, cos).
    EXPECT_NEAR(loops[k]->start.x_mm, loops[k]->center.x_mm + 4 * std::sin(heading), 1e-9);
    EXPECT_NEAR(loops[k]->start.y_mm, loops[k]->center.y_mm - 4 * std::cos(heading), 1e-9);
    EXPECT_NEAR(loops[k]->start.z_mm, -5.0, 1e-12);
  }
}

TEST(Trochoid, ClockwiseIsTheMirrorImageAboutTheSlotAxis) {
  const Cycle ccw = generate_trochoid({{0, 0}, {9, 0}, 5.0, 1.0, Direction::kCcw}, kTool, 10.0);
  const Cycle cw = generate_trochoid({{0, 0}, {9, 0}, 5.0, 1.0, Direction::kCw}, kTool, 10.0);
  EXPECT_TRUE(geometry::consistency_defects(cw.path).empty());
  ASSERT_EQ(ccw.path.moves.size(), cw.path.moves.size());
  for (std::size_t i = 0; i < cw.path.moves.size(); ++i) {
    const auto& a = ccw.path.moves[i];
    const auto& b = cw.path.moves[i];
    EXPECT_NEAR(b.start.x_mm, a.start.x_mm, kTol);
    EXPECT_NEAR(b.start.y_mm, -a.start.y_mm, kTol);
    EXPECT_NEAR(b.end.y_mm, -a.end.y_mm, kTol);
    if (a.kind == MoveKind::kArc) {
      EXPECT_NE(a.ccw, b.ccw);
    }
  }
  EXPECT_NEAR(circles(cw).front()->start.y_mm, 5.0, kTol);  // loops start at c_k + R_t·v
}

TEST(Trochoid, ValidateRejectsEqualEndsAndReportsEveryProblem) {
  const auto problems = validate(TrochoidSpec{{3, 3}, {3, 3}, 0.0, 10.0, Direction::kCcw}, kTool, 0.0);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0].field, "axial_depth_mm");
  EXPECT_EQ(problems[1].field, "trochoid.end");
  EXPECT_EQ(problems[2].field, "trochoid.pitch_mm");
  EXPECT_EQ(problems[3].field, "trochoid.loop_radius_mm");
  EXPECT_THROW(generate_trochoid({{3, 3}, {3, 3}, 5.0, 1.0, Direction::kCcw}, kTool, 10.0), InputError);
}

}  // namespace
}  // namespace feedplan::cycles
