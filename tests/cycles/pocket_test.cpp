// Pocket generator: the sub-cycles of seed 003 Fig. 3 in order, and the wall pass exactly one tool
// radius inside the finished walls (checked with the rounded rectangle's own distance function).

#include "feedplan/cycles/pocket.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

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

PocketSpec pocket(double width_mm, double height_mm, double corner_radius_mm, Direction direction = Direction::kCcw) {
  PocketSpec spec;
  spec.center = {5, -3};
  spec.width_mm = width_mm;
  spec.height_mm = height_mm;
  spec.depth_mm = 10;
  spec.corner_radius_mm = corner_radius_mm;
  spec.direction = direction;
  return spec;
}

// Distance of p inside the pocket from its finished walls (signed distance of a rounded rectangle).
double distance_from_walls(const PocketSpec& spec, const geometry::Point3& p) {
  const double qx = std::abs(p.x_mm - spec.center.x_mm) - (0.5 * spec.width_mm - spec.corner_radius_mm);
  const double qy = std::abs(p.y_mm - spec.center.y_mm) - (0.5 * spec.height_mm - spec.corner_radius_mm);
  const double sdf = std::hypot(std::max(qx, 0.0), std::max(qy, 0.0)) + std::min(std::max(qx, qy), 0.0) -
                     spec.corner_radius_mm;
  return -sdf;
}

std::string sub_cycle(const std::string& part) { return part.substr(0, part.find(':')); }

std::vector<std::string> sub_cycle_order(const geometry::ToolPath& path) {
  std::vector<std::string> order;
  for (const auto& name : testing::part_order(path)) {
    if (order.empty() || order.back() != sub_cycle(name)) order.push_back(sub_cycle(name));
  }
  return order;
}

bool is_wall_pass(const std::string& part) {
  return part.rfind("walls: wall", 0) == 0 || part.rfind("walls: corner", 0) == 0;
}

void expect_wall_pass_one_radius_inside(const PocketSpec& spec, const Cycle& cycle) {
  int checked = 0;
  for (const auto& m : cycle.path.moves) {
    if (!is_wall_pass(cycle.path.part_names[m.part])) continue;
    EXPECT_TRUE(m.cutting);
    for (int i = 0; i <= 50; ++i) {
      EXPECT_NEAR(distance_from_walls(spec, geometry::point_at(m, i / 50.0)), 5.0, 1e-9)
          << cycle.path.part_names[m.part];
      ++checked;
    }
  }
  EXPECT_GT(checked, 8 * 51 - 1);
}

TEST(Pocket, SubCyclesFollowFig3) {
  const PocketSpec spec = pocket(60, 40, 8);
  const Cycle cycle = generate_pocket(spec, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const std::vector<std::string> expected = {"boring",   "spiral",   "slot +x",  "slot -x",       "corner 1",
                                             "corner 2", "corner 3", "corner 4", "semi-finish 1", "walls"};
  EXPECT_EQ(sub_cycle_order(cycle.path), expected);
  const std::vector<std::string> walls = {"walls: entry",    "walls: lead-in", "walls: wall 1",  "walls: corner 1",
                                          "walls: wall 2",   "walls: corner 2", "walls: wall 3", "walls: corner 3",
                                          "walls: wall 4",   "walls: corner 4", "walls: wall 1 end", "walls: exit"};
  const auto order = testing::part_order(cycle.path);
  const std::vector<std::string> tail(order.end() - static_cast<long>(walls.size()), order.end());
  EXPECT_EQ(tail, walls);
}

TEST(Pocket, SubCycleSizesFollowFromThePocket) {
  const PocketSpec spec = pocket(60, 40, 8);
  const Cycle cycle = generate_pocket(spec, kTool);
  // (a) bore 1.6·D = 16 → helix radius 3 about the centre, 10 turns of 0.1·D down to −10.
  const auto& helix = cycle.path.moves[moves_of(cycle.path, "boring: helix turn 1").at(0)];
  EXPECT_NEAR(geometry::arc_radius_mm(helix), 3.0, kTol);
  EXPECT_NEAR(helix.center.x_mm, 5.0, kTol);
  EXPECT_NEAR(helix.end.z_mm, -1.0, kTol);
  EXPECT_EQ(moves_of(cycle.path, "boring: helix turn 10").size(), 1u);
  EXPECT_TRUE(moves_of(cycle.path, "boring: helix turn 11").empty());
  // (b) spiral to R_s = 40/2 − 1.5 = 18.5: finishing circle of tool-centre radius 13.5.
  const auto& finishing = cycle.path.moves[moves_of(cycle.path, "spiral: finishing circle").at(0)];
  EXPECT_NEAR(geometry::arc_radius_mm(finishing), 13.5, kTol);
  // (c) slots: loop radius R_s − r = 13.5, last loop centres at ±(60 − 40)/2 from the centre.
  double max_centre = -1e9, min_centre = 1e9;
  for (const auto& m : cycle.path.moves) {
    const std::string& part = cycle.path.part_names[m.part];
    if (part.rfind("slot", 0) != 0 || m.kind != MoveKind::kArc) continue;
    EXPECT_NEAR(geometry::arc_radius_mm(m), 13.5, kTol);
    EXPECT_NEAR(m.center.y_mm, -3.0, kTol);
    max_centre = std::max(max_centre, m.center.x_mm);
    min_centre = std::min(min_centre, m.center.x_mm);
  }
  EXPECT_NEAR(max_centre, 5.0 + 10.0, kTol);
  EXPECT_NEAR(min_centre, 5.0 - 10.0, kTol);
  // Everything cuts at the pocket depth except the helix; the bore's moves are planned for its pitch.
  for (const auto& m : cycle.path.moves) {
    const std::string& part = cycle.path.part_names[m.part];
    if (!m.cutting || part.rfind("boring: helix", 0) == 0) continue;
    EXPECT_NEAR(m.start.z_mm, -10.0, kTol);
    EXPECT_NEAR(m.end.z_mm, -10.0, kTol);
    EXPECT_EQ(m.axial_depth_mm, part.rfind("boring", 0) == 0 ? 1.0 : 10.0) << part;
  }
  // Between sub-cycles the tool is at the clearance height.
  for (std::size_t i = 1; i < cycle.path.moves.size(); ++i) {
    const auto& a = cycle.path.moves[i - 1];
    const auto& b = cycle.path.moves[i];
    if (sub_cycle(cycle.path.part_names[a.part]) != sub_cycle(cycle.path.part_names[b.part])) {
      EXPECT_NEAR(a.end.z_mm, 5.0, kTol);
    }
  }
  // Implied stock: the pocket rectangle grown by 2·D; bottom 5 mm below the pocket.
  const auto& outer = cycle.stock.regions.at(0).outer.vertices;
  EXPECT_NEAR(outer[0].x_mm, 5.0 - 30.0 - 20.0, kTol);
  EXPECT_NEAR(outer[0].y_mm, -3.0 - 20.0 - 20.0, kTol);
  EXPECT_NEAR(cycle.stock.z_bottom_mm, -15.0, kTol);
  EXPECT_TRUE(cycle.stock.removed.empty());
}

TEST(Pocket, WallPassStaysOneToolRadiusInsideTheFinishedWalls) {
  const PocketSpec spec = pocket(60, 40, 8);
  const Cycle cycle = generate_pocket(spec, kTool);
  expect_wall_pass_one_radius_inside(spec, cycle);
  // Counter-clockwise (climb): wall 1 runs along +X at the bottom wall; tangent-continuous from the
  // lead-in to the end of wall 1.
  const auto& wall1 = cycle.path.moves[moves_of(cycle.path, "walls: wall 1").at(0)];
  EXPECT_NEAR(geometry::tangent_angle_rad(wall1, 0), 0.0, kTol);
  EXPECT_NEAR(wall1.start.x_mm, 5.0, kTol);
  EXPECT_NEAR(wall1.start.y_mm, -3.0 - 15.0, kTol);
  EXPECT_LT(testing::max_kink_between_cutting_moves_rad(cycle.path), 1e-9);
  // The corner arcs have radius R_c − r.
  const auto& corner = cycle.path.moves[moves_of(cycle.path, "walls: corner 2").at(0)];
  EXPECT_NEAR(geometry::arc_radius_mm(corner), 8.0 - 5.0, kTol);
  EXPECT_TRUE(corner.ccw);
}

TEST(Pocket, TallPocketSlotsAlongYAndFinishesFromTheRightWall) {
  const PocketSpec spec = pocket(40, 60, 8);
  const Cycle cycle = generate_pocket(spec, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const std::vector<std::string> expected = {"boring",   "spiral",   "slot +y",  "slot -y",       "corner 1",
                                             "corner 2", "corner 3", "corner 4", "semi-finish 1", "walls"};
  EXPECT_EQ(sub_cycle_order(cycle.path), expected);
  expect_wall_pass_one_radius_inside(spec, cycle);
  const auto& wall1 = cycle.path.moves[moves_of(cycle.path, "walls: wall 1").at(0)];
  EXPECT_NEAR(wall1.start.x_mm, 5.0 + 15.0, kTol);
  EXPECT_NEAR(geometry::tangent_angle_rad(wall1, 0), 0.5 * kPi, kTol);
}

TEST(Pocket, SquarePocketNeedsNoSlots) {
  const PocketSpec spec = pocket(40, 40, 20);  // a circle: the wall pass has no straight walls
  const Cycle cycle = generate_pocket(spec, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const std::vector<std::string> expected = {"boring", "spiral", "walls"};
  EXPECT_EQ(sub_cycle_order(cycle.path), expected);
  EXPECT_TRUE(moves_of(cycle.path, "walls: wall 2").empty());
  EXPECT_EQ(moves_of(cycle.path, "walls: corner 2").size(), 1u);
}

TEST(Pocket, NarrowPocketBoresToWidthAndShrinksTheTrochoidPitch) {
  // Width 14 = D + 2a + 0.1·D: the bore is 14 − 2·1.5 = 11 mm, no spiral, loops of radius 0.5.
  const PocketSpec spec = pocket(14, 40, 6);
  const Cycle cycle = generate_pocket(spec, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  const std::vector<std::string> expected = {"boring",   "slot +y",  "slot -y",  "corner 1",
                                             "corner 2", "corner 3", "corner 4", "walls"};
  EXPECT_EQ(sub_cycle_order(cycle.path), expected);
  const auto& helix = cycle.path.moves[moves_of(cycle.path, "boring: helix turn 1").at(0)];
  EXPECT_NEAR(geometry::arc_radius_mm(helix), 0.5, kTol);
  const auto& loop = cycle.path.moves[moves_of(cycle.path, "slot +y: loop 2").back()];
  EXPECT_NEAR(geometry::arc_radius_mm(loop), 0.5, kTol);
  EXPECT_NEAR(loop.center.y_mm, -3.0 + 0.25, kTol);  // pitch R_t / 2
  expect_wall_pass_one_radius_inside(spec, cycle);
  const auto has_note = [&](const std::string& text) {
    return std::any_of(cycle.notes.begin(), cycle.notes.end(),
                       [&](const std::string& n) { return n.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has_note("hole diameter 11 mm instead of 16 mm"));
  EXPECT_TRUE(has_note("trochoid pitch reduced to 0.25 mm"));
}

TEST(Pocket, ClockwiseIsClimbMirroredAndNeverTouchesMaterialInAir) {
  const PocketSpec spec = pocket(36, 50, 6, Direction::kCw);
  const Cycle cycle = generate_pocket(spec, kTool);
  EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
  expect_wall_pass_one_radius_inside(spec, cycle);
  for (const auto& m : cycle.path.moves) {
    if (m.kind == MoveKind::kArc && m.cutting) {
      EXPECT_FALSE(m.ccw) << cycle.path.part_names[m.part];
    }
  }
  const auto profile = geometry::compute_engagement(cycle.path, cycle.stock, 5.0, {.ds_mm = 0.3});
  EXPECT_TRUE(profile.warnings.empty()) << profile.warnings.front();
}

TEST(Pocket, ValidateBoundsTheShortSideFromBothEnds) {
  auto problems = validate(pocket(13, 40, 6), kTool);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "pocket.width_mm");
  EXPECT_NE(problems[0].message.find("= 13: must be ≥ 14"), std::string::npos) << problems[0].message;
  // Largest short side: 2(√2·2r − a) / (√2 − 1) for R_c ≤ 2r.
  const double s_max = 2 * (std::sqrt(2.0) * 10 - 1.5) / (std::sqrt(2.0) - 1);
  EXPECT_TRUE(validate(pocket(100, s_max - 0.01, 8), kTool).empty());
  problems = validate(pocket(100, s_max + 0.01, 8), kTool);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "pocket.height_mm");
  PocketSpec spec = pocket(60, 40, 5);
  spec.finish_allowance_mm = 5.0;
  problems = validate(spec, kTool);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(to_string(problems[0]),
            "pocket.finish_allowance_mm = 5: must be in (0, 5) — the finishing pass takes less than the tool radius");
  EXPECT_EQ(problems[1].field, "pocket.corner_radius_mm");
}

}  // namespace
}  // namespace feedplan::cycles
