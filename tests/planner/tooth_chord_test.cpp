// The chord of the path over the last tooth period (planner/tooth_chord.hpp) against its closed form on a
// circle: over a path length L on a circle of radius ρ the chord is 2ρ·sin(L / 2ρ) long and lags the tangent
// by L / 2ρ (behind it on a counter-clockwise circle, ahead on a clockwise one).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "feedplan/planner/tooth_chord.hpp"

namespace feedplan::planner {
namespace {

//! Samples every ds along a circle of radius ρ about the origin, counter-clockwise (or clockwise).
geometry::EngagementProfile circle_profile(double radius_mm, double ds_mm, int count, bool ccw) {
  geometry::EngagementProfile profile;
  profile.ds_mm = ds_mm;
  for (int i = 0; i < count; ++i) {
    const double s = i * ds_mm, angle = (ccw ? 1.0 : -1.0) * s / radius_mm;
    geometry::EngagementSample e;
    e.s_mm = s;
    e.position = {radius_mm * std::cos(angle), radius_mm * std::sin(angle), 0.0};
    e.feed_direction_rad = angle + (ccw ? 0.5 : -0.5) * std::numbers::pi;
    profile.samples.push_back(e);
  }
  return profile;
}

TEST(ToothChord, OnACircleItIsTheClosedFormChord) {
  for (const bool ccw : {true, false}) {
    const double radius_mm = 5.0, per_tooth_mm = 0.13;
    const geometry::EngagementProfile profile = circle_profile(radius_mm, 0.05, 200, ccw);
    const auto& sample = profile.samples[100];
    const ToothChord chord = tooth_chord(profile, sample, per_tooth_mm);
    const double half_turn = per_tooth_mm / (2.0 * radius_mm);
    // The samples' positions are joined by straight lines: the point one tooth back lies inside the circle
    // by at most the sagitta of a 0.05 mm chord, 6e-5 mm, which turns the chord by 5e-4 rad at most.
    EXPECT_NEAR(chord.length_mm, 2.0 * radius_mm * std::sin(half_turn), 1e-4);
    EXPECT_NEAR(chord.angle_rad, ccw ? -half_turn : half_turn, 5e-4);
  }
}

TEST(ToothChord, AStraightPathAndThePathsStartGiveTheFeedPerTooth) {
  geometry::EngagementProfile profile;
  for (int i = 0; i < 20; ++i) {
    geometry::EngagementSample e;
    e.s_mm = 0.1 * i;
    e.position = {0.1 * i * std::cos(0.3), 0.1 * i * std::sin(0.3), 0.0};
    e.feed_direction_rad = 0.3;
    e.xy_speed_ratio = 1.0;
    profile.samples.push_back(e);
  }
  const ToothChord straight = tooth_chord(profile, profile.samples[10], 0.25);
  EXPECT_NEAR(straight.length_mm, 0.25, 1e-12);
  EXPECT_NEAR(straight.angle_rad, 0.0, 1e-12);
  const ToothChord start = tooth_chord(profile, profile.samples[1], 0.25);  // reaches before the path
  EXPECT_EQ(start.length_mm, 0.25);
  EXPECT_EQ(start.angle_rad, 0.0);
}

}  // namespace
}  // namespace feedplan::planner
