// Corner rounding generator: the tool-centre path against the closed-form offsets of the finished
// walls, and the engagement in its steady parts against the analytic oracle of docs/method.md §5.1
// (which needs the implied stock to be concentric with the finished corner).

#include "feedplan/cycles/corner.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "path_checks.hpp"

namespace feedplan::cycles {
namespace {

using geometry::MoveKind;
using testing::moves_of;

const geometry::Tool kTool{"D10", 10.0, 4, 30.0};
constexpr double kTol = 1e-9;

// Seed 003 Fig. 5: 90° corner at the origin, finished radius 10, R_d 1.5, walls 30 mm, r = 5.
const CornerSpec kFig5{{0, 0}, 0.0, 90.0, 10.0, 1.5, 30.0, std::nullopt, Direction::kCcw};

const geometry::Move& only(const Cycle& cycle, const std::string& part) {
  const auto moves = moves_of(cycle.path, part);
  EXPECT_EQ(moves.size(), 1u) << part;
  return cycle.path.moves.at(moves.at(0));
}

TEST(Corner, Fig5PathIsTheWallsOffsetByTheToolRadius) {
  const Cycle cycle = generate_corner(kFig5, kTool, 10.0);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  // Finished walls: y = 0 (wall 1, material below) and x = 0 (wall 2, material right); the corner arc
  // of radius 10 about (−10, 10) touches them at (−10, 0) and (0, 10).
  const auto& wall1 = only(cycle, "wall 1");
  const auto& corner = only(cycle, "corner");
  const auto& wall2 = only(cycle, "wall 2");
  EXPECT_EQ(wall1.kind, MoveKind::kLine);
  EXPECT_NEAR(wall1.start.y_mm, 5.0, kTol);  // r from wall 1
  EXPECT_NEAR(wall1.end.y_mm, 5.0, kTol);
  EXPECT_NEAR(wall1.start.x_mm, -10.0 - 30.0 - 5.0, kTol);  // enters the stock at s1 = T1 − 30
  EXPECT_NEAR(wall1.end.x_mm, -10.0, kTol);
  EXPECT_EQ(corner.kind, MoveKind::kArc);
  EXPECT_TRUE(corner.ccw);
  EXPECT_NEAR(corner.center.x_mm, -10.0, kTol);
  EXPECT_NEAR(corner.center.y_mm, 10.0, kTol);
  EXPECT_NEAR(geometry::arc_radius_mm(corner), 10.0 - 5.0, kTol);  // R − r
  EXPECT_NEAR(corner.sweep_rad, 0.5 * kPi, kTol);
  EXPECT_NEAR(wall2.start.x_mm, -5.0, kTol);  // r from wall 2
  EXPECT_NEAR(wall2.end.x_mm, -5.0, kTol);
  EXPECT_NEAR(wall2.start.y_mm, 10.0, kTol);
  EXPECT_NEAR(wall2.end.y_mm, 10.0 + 30.0 + 5.0, kTol);
  for (const auto* m : {&wall1, &corner, &wall2}) {
    EXPECT_TRUE(m->cutting);
    EXPECT_EQ(m->axial_depth_mm, 10.0);
    EXPECT_NEAR(m->start.z_mm, -10.0, kTol);
  }
  // Tangent at both joints.
  EXPECT_NEAR(testing::angle_difference_rad(geometry::tangent_angle_rad(wall1, 1), geometry::tangent_angle_rad(corner, 0)), 0, 1e-12);
  EXPECT_NEAR(testing::angle_difference_rad(geometry::tangent_angle_rad(corner, 1), geometry::tangent_angle_rad(wall2, 0)), 0, 1e-12);
  // Approach and departure are air, a lead (default: the tool diameter) beyond the stock.
  for (auto i : moves_of(cycle.path, "approach")) EXPECT_FALSE(cycle.path.moves[i].cutting);
  for (auto i : moves_of(cycle.path, "departure")) EXPECT_FALSE(cycle.path.moves[i].cutting);
  EXPECT_NEAR(cycle.path.moves.front().start.x_mm, -40.0 - 10.0, kTol);
  EXPECT_NEAR(cycle.path.moves.back().end.y_mm, 40.0 + 10.0, kTol);
}

TEST(Corner, ImpliedStockHoldsTheEarlierPassRadialDepthFurtherOut) {
  const Cycle cycle = generate_corner(kFig5, kTool, 10.0);
  EXPECT_TRUE(geometry::validate(cycle.stock).empty());
  ASSERT_EQ(cycle.stock.removed.size(), 3u);
  const auto& line1 = cycle.stock.removed[0].move;
  const auto& arc = cycle.stock.removed[1].move;
  const auto& line2 = cycle.stock.removed[2].move;
  EXPECT_EQ(cycle.stock.removed[0].tool_radius_mm, 5.0);
  EXPECT_NEAR(line1.start.y_mm, 5.0 + 1.5, kTol);
  EXPECT_NEAR(geometry::arc_radius_mm(arc), 10.0 - 5.0 - 1.5, kTol);  // concentric with the finished arc
  EXPECT_NEAR(arc.center.x_mm, -10.0, kTol);
  EXPECT_NEAR(arc.center.y_mm, 10.0, kTol);
  EXPECT_NEAR(line2.end.x_mm, -5.0 - 1.5, kTol);
}

TEST(Corner, SteadyEngagementMatchesTheAnalyticOracle) {
  const Cycle cycle = generate_corner(kFig5, kTool, 10.0);
  const auto profile = geometry::compute_engagement(cycle.path, cycle.stock, 5.0, {.ds_mm = 0.05});
  EXPECT_TRUE(profile.warnings.empty());
  const auto wall1 = moves_of(cycle.path, "wall 1").at(0);
  const auto corner = moves_of(cycle.path, "corner").at(0);
  double wall_middle = -1, corner_max = 0;
  for (const auto& s : profile.samples) {
    if (s.move_index == static_cast<int>(wall1) && std::abs(s.position.x_mm + 25.0) < 0.03) wall_middle = s.engagement_rad;
    if (s.move_index == static_cast<int>(corner)) corner_max = std::max(corner_max, s.engagement_rad);
  }
  // docs/method.md §5.1: straight R_d 1.5, r 5 → acos(1 − 0.3) = 45.57°; internal R 10 / R_d 1.5 → 63.58°.
  EXPECT_NEAR(rad_to_deg(wall_middle), 45.573, 0.01);
  EXPECT_NEAR(rad_to_deg(corner_max), 63.58, 0.01);
}

TEST(Corner, ObliqueClockwiseCornerKeepsTheToolRadiusFromBothWalls) {
  const geometry::Point2 k{3, -2};
  const double heading = deg_to_rad(30.0);
  const double angle = deg_to_rad(120.0);
  const CornerSpec spec{k, 30.0, 120.0, 8.0, 2.0, 20.0, 7.0, Direction::kCw};
  const Cycle cycle = generate_corner(spec, kTool, 6.0);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  EXPECT_TRUE(geometry::validate(cycle.stock).empty());
  // Clockwise: the walls are on the tool's left and the travel turns right by 180° − 120°.
  const geometry::Point2 d1{std::cos(heading), std::sin(heading)};
  const double heading2 = heading - (kPi - angle);
  const geometry::Point2 d2{std::cos(heading2), std::sin(heading2)};
  auto left_of = [&](const geometry::Point2& d, const geometry::Point3& p) {  // signed distance, left positive
    return d.x_mm * (p.y_mm - k.y_mm) - d.y_mm * (p.x_mm - k.x_mm);
  };
  const auto& wall1 = only(cycle, "wall 1");
  const auto& corner = only(cycle, "corner");
  const auto& wall2 = only(cycle, "wall 2");
  EXPECT_NEAR(left_of(d1, wall1.start), -5.0, kTol);
  EXPECT_NEAR(left_of(d1, wall1.end), -5.0, kTol);
  EXPECT_NEAR(left_of(d2, wall2.start), -5.0, kTol);
  EXPECT_NEAR(left_of(d2, wall2.end), -5.0, kTol);
  EXPECT_NEAR(geometry::tangent_angle_rad(wall1, 0), heading, kTol);
  EXPECT_NEAR(testing::angle_difference_rad(geometry::tangent_angle_rad(wall2, 0), heading2), 0, kTol);
  EXPECT_FALSE(corner.ccw);
  EXPECT_NEAR(corner.sweep_rad, kPi - angle, kTol);
  EXPECT_NEAR(geometry::arc_radius_mm(corner), 8.0 - 5.0, kTol);
  // The arc centre lies on the bisector, R / sin(γ/2) from the corner point.
  EXPECT_NEAR(std::hypot(corner.center.x_mm - k.x_mm, corner.center.y_mm - k.y_mm), 8.0 / std::sin(0.5 * angle), kTol);
  EXPECT_LT(testing::max_kink_between_cutting_moves_rad(cycle.path), 1e-9);
  EXPECT_NEAR(wall1.start.z_mm, -6.0, kTol);
}

TEST(Corner, SharpEarlierPassIsNoted) {
  // R − r − R_d = 6 − 5 − 2 < 0: the earlier pass turned the corner sharply.
  const CornerSpec spec{{0, 0}, 0.0, 90.0, 6.0, 2.0, 30.0, std::nullopt, Direction::kCcw};
  const Cycle cycle = generate_corner(spec, kTool, 10.0);
  EXPECT_TRUE(geometry::validate(cycle.stock).empty());
  ASSERT_EQ(cycle.stock.removed.size(), 2u);
  EXPECT_NEAR(cycle.stock.removed[0].move.end.x_mm, -7.0, kTol);  // the offset lines meet at (−7, 7)
  EXPECT_NEAR(cycle.stock.removed[0].move.end.y_mm, 7.0, kTol);
  ASSERT_EQ(cycle.notes.size(), 1u);
  EXPECT_NE(cycle.notes[0].find("not concentric"), std::string::npos);
}

TEST(Corner, ValidateRejectsAShortLeadAndAFoldedBlock) {
  CornerSpec spec = kFig5;
  spec.lead_mm = 5.0;
  auto problems = validate(spec, kTool, 10.0);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(to_string(problems[0]), "corner.lead_mm = 5: must be > 5 — the tool (radius 5) must plunge clear of the stock");
  spec = kFig5;
  spec.corner_angle_deg = 5.0;
  spec.radial_depth_mm = 9.0;
  spec.wall_length_mm = 1.0;
  problems = validate(spec, kTool, 10.0);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "corner.wall_length_mm");
  EXPECT_NE(problems[0].message.find("= 1: too short for corner_angle_deg = 5"), std::string::npos);
}

}  // namespace
}  // namespace feedplan::cycles
