// Helical boring generator: helix turns, depths and the clean-up circle in closed form.

#include "feedplan/cycles/helical_boring.hpp"

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

TEST(HelicalBoring, TurnsDescendOnePitchEachAndEndExactlyAtDepth) {
  const Cycle cycle = generate_helical_boring({{0, 0}, 16.0, 1.0, 10.0, Direction::kCcw}, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  EXPECT_TRUE(cycle.notes.empty());
  for (int k = 1; k <= 10; ++k) {
    const auto turn = moves_of(cycle.path, "helix turn " + std::to_string(k));
    ASSERT_EQ(turn.size(), 1u) << k;
    const auto& m = cycle.path.moves[turn[0]];
    EXPECT_EQ(m.kind, MoveKind::kArc);
    EXPECT_NEAR(geometry::arc_radius_mm(m), (16.0 - 10.0) / 2, kTol);  // ρ = (D_h − D) / 2
    EXPECT_NEAR(m.sweep_rad, kTwoPi, kTol);
    EXPECT_NEAR(m.start.z_mm, -(k - 1.0), kTol);
    EXPECT_NEAR(m.end.z_mm, -static_cast<double>(k), kTol);
    EXPECT_NEAR(m.end.x_mm, 3.0, kTol);
    EXPECT_NEAR(m.end.y_mm, 0.0, kTol);
    EXPECT_TRUE(m.cutting);
    EXPECT_EQ(m.axial_depth_mm, 1.0);
  }
  EXPECT_TRUE(moves_of(cycle.path, "helix turn 11").empty());
  const auto bottom = moves_of(cycle.path, "bottom circle");
  ASSERT_EQ(bottom.size(), 1u);
  const auto& circle = cycle.path.moves[bottom[0]];
  EXPECT_NEAR(circle.start.z_mm, -10.0, kTol);
  EXPECT_NEAR(circle.end.z_mm, -10.0, kTol);
  EXPECT_NEAR(circle.sweep_rad, kTwoPi, kTol);
  EXPECT_EQ(circle.axial_depth_mm, 1.0);
  EXPECT_TRUE(circle.cutting);
  // Entry feeds in air to the stock top; exit goes to the hole axis and up to the clearance.
  const auto entry = moves_of(cycle.path, "entry");
  EXPECT_NEAR(cycle.path.moves[entry.back()].end.z_mm, 0.0, kTol);
  EXPECT_FALSE(cycle.path.moves[entry.back()].cutting);
  const auto exit = moves_of(cycle.path, "exit");
  EXPECT_NEAR(cycle.path.moves[exit.front()].end.x_mm, 0.0, kTol);
  EXPECT_NEAR(cycle.path.moves.back().end.z_mm, 5.0, kTol);
  // Solid block, half-size D_h / 2 + 2·D, bottom 5 mm below the hole.
  EXPECT_TRUE(cycle.stock.regions.at(0).holes.empty());
  EXPECT_NEAR(cycle.stock.regions[0].outer.vertices[2].x_mm, 8.0 + 20.0, kTol);
  EXPECT_NEAR(cycle.stock.z_bottom_mm, -15.0, kTol);
}

TEST(HelicalBoring, LastTurnIsPartialWhenDepthIsNotAMultipleOfThePitch) {
  const Cycle cycle = generate_helical_boring({{2, 1}, 16.0, 1.0, 10.5, Direction::kCcw}, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const auto last = moves_of(cycle.path, "helix turn 11");
  ASSERT_EQ(last.size(), 1u);
  const auto& m = cycle.path.moves[last[0]];
  EXPECT_NEAR(m.sweep_rad, kPi, kTol);  // half a turn for the last 0.5 mm
  EXPECT_NEAR(m.end.z_mm, -10.5, kTol);
  EXPECT_NEAR(m.end.x_mm, 2.0 - 3.0, kTol);  // O + ρ·(cos π, sin π)
  EXPECT_NEAR(m.end.y_mm, 1.0, kTol);
  const auto& bottom = cycle.path.moves[moves_of(cycle.path, "bottom circle").at(0)];
  EXPECT_NEAR(bottom.start.x_mm, -1.0, kTol);
  EXPECT_NEAR(bottom.start.z_mm, -10.5, kTol);
  ASSERT_EQ(cycle.notes.size(), 1u);
  EXPECT_NE(cycle.notes[0].find("partial (0.5 turn)"), std::string::npos) << cycle.notes[0];
}

TEST(HelicalBoring, ClockwiseTurnsTheOtherWay) {
  const Cycle cycle = generate_helical_boring({{0, 0}, 20.0, 2.0, 4.0, Direction::kCw}, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const auto& turn = cycle.path.moves[moves_of(cycle.path, "helix turn 1").at(0)];
  EXPECT_FALSE(turn.ccw);
  EXPECT_NEAR(geometry::arc_radius_mm(turn), 5.0, kTol);
  EXPECT_NEAR(geometry::point_at(turn, 0.25).y_mm, -5.0, kTol);  // clockwise from +X goes to −Y
}

TEST(HelicalBoring, ValidateNamesTheCoreLeftByALargeHole) {
  const auto problems = validate(HelicalBoringSpec{{0, 0}, 20.5, 1.0, 10.0, Direction::kCcw}, kTool);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "helical_boring.hole_diameter_mm");
  EXPECT_NE(problems[0].message.find("= 20.5: must be in (10, 20] — a hole larger than twice the tool diameter "
                                     "leaves an uncut core"),
            std::string::npos)
      << problems[0].message;
  EXPECT_EQ(validate(HelicalBoringSpec{{0, 0}, 10.0, 1.0, 10.0, Direction::kCcw}, kTool).at(0).message,
            "= 10: must be in (10, 20] — the hole must be larger than the tool");
}

}  // namespace
}  // namespace feedplan::cycles
