// Spiral generator against the closed-form geometry of seed 003 Table 3 and Fig. 12.

#include "feedplan/cycles/spiral.hpp"

#include <gtest/gtest.h>

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

double distance_from(const geometry::Point3& p, const geometry::Point2& o) {
  return std::hypot(p.x_mm - o.x_mm, p.y_mm - o.y_mm);
}

// Table 3: R_init 8, R_fin 16, p 1, r 5: tool-centre radius from 3 to 11 mm in eight turns.
TEST(Spiral, Table3GrowsTheRadiusByOnePitchPerTurn) {
  const Cycle cycle = generate_spiral({{0, 0}, 8.0, 16.0, 1.0, Direction::kCcw}, kTool, 10.0);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  EXPECT_TRUE(cycle.notes.empty());
  for (int k = 1; k <= 8; ++k) {
    const auto turn = moves_of(cycle.path, "spiral turn " + std::to_string(k));
    ASSERT_EQ(turn.size(), 2u) << "turn " << k;
    const auto& first_half = cycle.path.moves[turn[0]];
    const auto& second_half = cycle.path.moves[turn[1]];
    // Half-turn about O at ρ0 + (k − 1)·p, then about O + (p/2, 0) at ρ0 + (k − 1)·p + p/2.
    EXPECT_NEAR(first_half.center.x_mm, 0.0, kTol);
    EXPECT_NEAR(geometry::arc_radius_mm(first_half), 3.0 + (k - 1), kTol);
    EXPECT_NEAR(first_half.sweep_rad, kPi, kTol);
    EXPECT_NEAR(second_half.center.x_mm, 0.5, kTol);
    EXPECT_NEAR(geometry::arc_radius_mm(second_half), 3.5 + (k - 1), kTol);
    EXPECT_NEAR(second_half.sweep_rad, kPi, kTol);
    // After the turn the tool centre is ρ0 + k·p from O, on +X.
    EXPECT_NEAR(distance_from(second_half.end, {0, 0}), 3.0 + k, kTol);
    EXPECT_NEAR(second_half.end.y_mm, 0.0, kTol);
    EXPECT_TRUE(first_half.ccw && second_half.ccw);
    EXPECT_TRUE(first_half.cutting && second_half.cutting);
    EXPECT_NEAR(first_half.start.z_mm, -10.0, kTol);
  }
  const auto finishing = moves_of(cycle.path, "finishing circle");
  ASSERT_EQ(finishing.size(), 1u);
  const auto& circle = cycle.path.moves[finishing[0]];
  EXPECT_NEAR(geometry::arc_radius_mm(circle), 16.0 - 5.0, kTol);  // R_fin − r
  EXPECT_NEAR(circle.sweep_rad, kTwoPi, kTol);
  EXPECT_NEAR(circle.center.x_mm, 0.0, kTol);
  // Exact semicircles joined tangentially: no corner anywhere on the cutting path.
  EXPECT_LT(testing::max_kink_between_cutting_moves_rad(cycle.path), 1e-9);
}

TEST(Spiral, StartsTouchingTheBoreWallAndStockIsTheBoredBlock) {
  const Cycle cycle = generate_spiral({{0, 0}, 8.0, 16.0, 1.0, Direction::kCcw}, kTool, 10.0);
  const auto entry = moves_of(cycle.path, "entry");
  ASSERT_FALSE(entry.empty());
  for (auto i : entry) EXPECT_FALSE(cycle.path.moves[i].cutting);
  // The air line ends with the tool edge on the bore wall: ρ0 + r = R_init.
  EXPECT_NEAR(distance_from(cycle.path.moves[entry.back()].end, {0, 0}) + 5.0, 8.0, kTol);
  ASSERT_EQ(cycle.stock.regions.size(), 1u);
  const auto& region = cycle.stock.regions[0];
  ASSERT_EQ(region.holes.size(), 1u);
  EXPECT_TRUE(region.holes[0].is_circle());
  EXPECT_EQ(region.holes[0].radius_mm, 8.0);
  EXPECT_NEAR(region.outer.vertices[2].x_mm, 16.0 + 20.0, kTol);  // half-size R_fin + 2·D
  EXPECT_NEAR(cycle.stock.z_bottom_mm, -15.0, kTol);
}

TEST(Spiral, PitchIsReducedToEndOnTheFinalRadiusAndNoted) {
  // ρ1 − ρ0 = 8.5 → 9 turns of 8.5 / 9 mm.
  const Cycle cycle = generate_spiral({{0, 0}, 8.0, 16.5, 1.0, Direction::kCcw}, kTool, 10.0);
  const auto last = moves_of(cycle.path, "spiral turn 9");
  ASSERT_EQ(last.size(), 2u);
  EXPECT_TRUE(moves_of(cycle.path, "spiral turn 10").empty());
  EXPECT_NEAR(distance_from(cycle.path.moves[last[1]].end, {0, 0}), 11.5, kTol);
  const auto third = moves_of(cycle.path, "spiral turn 3");
  EXPECT_NEAR(distance_from(cycle.path.moves[third[1]].end, {0, 0}), 3.0 + 3 * 8.5 / 9, kTol);
  ASSERT_EQ(cycle.notes.size(), 1u);
  EXPECT_NE(cycle.notes[0].find("reduced from 1 to 0.944444 mm"), std::string::npos) << cycle.notes[0];
}

TEST(Spiral, ClockwiseMirrorsAboutTheXAxisThroughTheCentre) {
  const geometry::Point2 o{10, -5};
  const Cycle cycle = generate_spiral({o, 8.0, 16.0, 1.0, Direction::kCw}, kTool, 4.0);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const auto half = moves_of(cycle.path, "spiral turn 2");
  ASSERT_EQ(half.size(), 2u);
  const auto& first = cycle.path.moves[half[0]];
  EXPECT_FALSE(first.ccw);
  // The first half-turn runs through the lower side (y < O_y) when mirrored.
  EXPECT_LT(geometry::point_at(first, 0.5).y_mm, o.y_mm - 3.9);
  EXPECT_NEAR(cycle.path.moves[half[1]].center.x_mm, o.x_mm + 0.5, kTol);
  EXPECT_NEAR(distance_from(cycle.path.moves[half[1]].end, o), 5.0, kTol);
  EXPECT_NEAR(first.start.z_mm, -4.0, kTol);
}

TEST(Spiral, ValidateExplainsATooSmallBore) {
  const auto problems = validate(SpiralSpec{{0, 0}, 4.0, 16.0, 1.0, Direction::kCcw}, kTool, 10.0);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(to_string(problems[0]),
            "spiral.initial_radius_mm = 4: must be > 5 — the tool (radius 5) does not fit in the bore");
}

}  // namespace
}  // namespace feedplan::cycles
