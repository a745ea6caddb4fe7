// Oracle test: the exact engagement kernel against the closed forms of docs/method.md §5.1 on steady
// straight cuts and steady internal and external arcs.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/analytic_engagement.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "test_moves.hpp"

namespace feedplan::geometry {
namespace {

constexpr double kToleranceRad = 1e-6;

Move line(Point3 a, Point3 b, double axial_depth_mm) {
  Move m;
  m.kind = MoveKind::kLine;
  m.start = a;
  m.end = b;
  m.cutting = true;
  m.axial_depth_mm = axial_depth_mm;
  return m;
}

using testing::arc;

// The docs/method.md §5.1 reference values, checked against the closed forms themselves.
TEST(AnalyticEngagement, DesignReferenceValues) {
  EXPECT_NEAR(rad_to_deg(internal_arc_engagement_rad(5, 20, 1.5)), 52.05, 0.005);
  EXPECT_NEAR(rad_to_deg(internal_arc_engagement_rad(5, 10, 1.5)), 63.58, 0.005);
  EXPECT_NEAR(rad_to_deg(external_arc_engagement_rad(5, 10, 1.5)), 38.28, 0.005);
  EXPECT_NEAR(rad_to_deg(external_arc_engagement_rad(5, 10, 4)), 68.90, 0.005);
  EXPECT_NEAR(rad_to_deg(straight_engagement_rad(5, 1.5)), std::acos(0.7) * 180 / kPi, 1e-12);
  EXPECT_DOUBLE_EQ(straight_engagement_rad(5, 12), kPi);
}

// Straight down-milling cut along +X with the material below: finished wall at y = −r, previous
// surface at y = −r + R_d.
TEST(ExactEngagement, StraightCutsMatchClosedForm) {
  const double r = 5.0;
  double worst_rad = 0.0;
  int total = 0;
  for (double rd = 0.5; rd <= 10.0 + 1e-9; rd += 0.5) {
    Stock stock;
    stock.z_top_mm = 0;
    stock.z_bottom_mm = -30;
    stock.regions.push_back({Contour::rectangle({-20, -60}, {200, -r + rd}), {}});
    ToolPath path;
    path.moves.push_back(line({-40, 0, -10}, {100, 0, -10}, 10));
    const auto profile = compute_engagement(path, stock, r, {.ds_mm = 0.25});
    const double expected = straight_engagement_rad(r, rd);
    int checked = 0;
    for (const auto& s : profile.samples) {
      if (s.position.x_mm < 10 || s.position.x_mm > 90) continue;
      ++checked;
      ++total;
      worst_rad = std::max(worst_rad, std::abs(s.engagement_rad - expected));
      ASSERT_NEAR(s.engagement_rad, expected, kToleranceRad) << "R_d " << rd << " at x " << s.position.x_mm;
      ASSERT_NEAR(s.exit_rad, rd >= 2 * r ? kPi : kPi, kToleranceRad);  // down milling exits at the right side
      ASSERT_NEAR(s.entry_rad, kPi - expected, kToleranceRad);
      ASSERT_NEAR(s.chip_factor, steady_chip_factor(expected), 1e-9);
      ASSERT_NEAR(s.contact_length_mm, r * s.engagement_rad, 1e-12);
      ASSERT_NEAR(s.chip_area_ratio, 1.0, 1e-9);  // a straight cut is what the model is fitted on
    }
    EXPECT_GT(checked, 300);
  }
  std::printf("%s: %d samples, largest |alpha_en - closed form| %.3g rad\n", "straight cuts R_d 0.5-10 mm", total, worst_rad);
}

// Internal arc: the tool runs counter-clockwise inside a bore whose previous wall has radius R − R_d;
// the finished wall has radius R, so the tool centre runs on R − r.
TEST(ExactEngagement, InternalArcsMatchClosedForm) {
  const double r = 5.0;
  double worst_rad = 0.0;
  int total = 0;
  const double cases[][2] = {{20, 1.5}, {10, 1.5}, {8, 1}, {8, 3}, {12, 2}, {16, 4}, {25, 0.5}, {40, 1.5}, {40, 6}};
  for (const auto& c : cases) {
    const double wall = c[0];
    const double rd = c[1];
    Stock stock;
    stock.z_bottom_mm = -30;
    stock.regions.push_back({Contour::rectangle({-100, -100}, {100, 100}), {Contour::circle({0, 0}, wall - rd)}});
    ToolPath path;
    path.moves.push_back(arc({0, 0}, wall - r, 0.0, 1.5 * kPi, true, -10));
    const auto profile = compute_engagement(path, stock, r, {.ds_mm = 0.05});
    const double expected = internal_arc_engagement_rad(r, wall, rd);
    int checked = 0;
    for (const auto& s : profile.samples) {
      const double angle = std::atan2(s.position.y_mm, s.position.x_mm);
      if (angle < 0.5 || angle > 2.8) continue;  // steady part, away from the start and end
      ++checked;
      ++total;
      worst_rad = std::max(worst_rad, std::abs(s.engagement_rad - expected));
      ASSERT_NEAR(s.engagement_rad, expected, kToleranceRad) << "R " << wall << " R_d " << rd << " at " << angle;
      ASSERT_NEAR(s.exit_rad, kPi, kToleranceRad);
    }
    EXPECT_GT(checked, 10) << "R " << wall;
  }
  std::printf("%s: %d samples, largest |alpha_en - closed form| %.3g rad\n", "internal arcs R 8-40 mm", total, worst_rad);
}

// External arc: the tool runs clockwise around a boss of radius R + R_d, finishing it to R.
TEST(ExactEngagement, ExternalArcsMatchClosedForm) {
  const double r = 5.0;
  double worst_rad = 0.0;
  int total = 0;
  const double cases[][2] = {{10, 1.5}, {10, 4}, {8, 1}, {20, 2}, {40, 3}, {5, 8}};
  for (const auto& c : cases) {
    const double wall = c[0];
    const double rd = c[1];
    Stock stock;
    stock.z_bottom_mm = -30;
    stock.regions.push_back({Contour::circle({0, 0}, wall + rd), {}});
    ToolPath path;
    path.moves.push_back(arc({0, 0}, wall + r, 0.0, 1.5 * kPi, false, -10));
    const auto profile = compute_engagement(path, stock, r, {.ds_mm = 0.05});
    const double expected = external_arc_engagement_rad(r, wall, rd);
    int checked = 0;
    for (const auto& s : profile.samples) {
      const double angle = std::atan2(s.position.y_mm, s.position.x_mm);
      if (angle > -0.5 || angle < -2.8) continue;
      ++checked;
      ++total;
      worst_rad = std::max(worst_rad, std::abs(s.engagement_rad - expected));
      ASSERT_NEAR(s.engagement_rad, expected, kToleranceRad) << "R " << wall << " R_d " << rd << " at " << angle;
      ASSERT_NEAR(s.exit_rad, kPi, kToleranceRad);
    }
    EXPECT_GT(checked, 10) << "R " << wall;
  }
  std::printf("%s: %d samples, largest |alpha_en - closed form| %.3g rad\n", "external arcs R 5-40 mm", total, worst_rad);
}

}  // namespace
}  // namespace feedplan::geometry
