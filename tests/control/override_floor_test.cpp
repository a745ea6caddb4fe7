// The override's floor (OverrideRange::min_ratio) known to the controllers: an integral controller held at
// the floor while the force stays above the target does not wind its integrator further down, so it moves
// up at the first sample the force falls below the target. The expected ratios are worked out by hand from
// Eq. 3 of seeds 000/001 (u_k = u_k−1 + K_c T (F_R − F_k)), not by the controller.

#include <gtest/gtest.h>

#include <algorithm>

#include "feedplan/control/integral_force_controller.hpp"
#include "feedplan/control/override_range.hpp"
#include "feedplan/control/variable_gain_controller.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {
namespace {

// F_R = 500 N, K_c = 0.03 (%)/(N·s), programmed 100 (%), T = 0.1 s, floor 10 %.
IntegralControllerParameters floored_integral(double min_ratio) {
  IntegralControllerParameters p;
  p.reference_force_n = 500.0;
  p.controller_gain_mm_per_min_per_n_s = 0.03;
  p.programmed_feed_mm_per_min = 100.0;
  p.initial_feed_mm_per_min = 100.0;
  p.override_range = {1.5, 0.0, min_ratio};
  return p;
}

TEST(OverrideFloor, IntegralHeldAtTheFloorRecoversAtTheFirstSampleBelowTheTarget) {
  IntegralForceController controller(floored_integral(0.1));
  // 2 s at 1500 N: each sample takes 0.03 · 0.1 · 1000 = 3 % off; from 100 % the floor is reached after
  // 30 samples, and the remaining 10 samples would take the integrator 30 % below it without the floor.
  double ratio = 1.0;
  for (int k = 0; k < 40; ++k) ratio = controller.step(1500.0, 0.1);
  EXPECT_DOUBLE_EQ(ratio, 0.1);
  // The force drops to 300 N: +0.03 · 0.1 · 200 = +0.6 % at once, from the floor.
  EXPECT_NEAR(controller.step(300.0, 0.1), 0.106, 1e-12);
  EXPECT_NEAR(controller.step(300.0, 0.1), 0.112, 1e-12);
}

TEST(OverrideFloor, WithoutTheFloorTheSameIntegratorWindsDownToZeroAndStaysThereLonger) {
  // The papers' 0 % floor, the adapter clamping at 10 % outside: the integrator sits at 0 after 40
  // samples at 1500 N (clamped at 0 from sample 34 on), and 300 N lifts it by 0.6 % a sample — 17 samples
  // (1.7 s) before it passes 10 % again. The test above is that delay removed.
  IntegralForceController controller(floored_integral(0.0));
  double ratio = 1.0;
  for (int k = 0; k < 40; ++k) ratio = controller.step(1500.0, 0.1);
  EXPECT_DOUBLE_EQ(ratio, 0.0);
  int samples_below_floor = 0;
  while (controller.step(300.0, 0.1) < 0.1 && samples_below_floor < 100) ++samples_below_floor;
  EXPECT_EQ(samples_below_floor, 16);  // the 17th is the first at or above 10 %
}

TEST(OverrideFloor, VariableGainControllerStaysAtTheFloorToo) {
  VariableGainParameters p;
  p.reference_force_n = 500.0;
  p.programmed_feed_mm_per_min = 100.0;
  p.initial_feed_mm_per_min = 100.0;
  p.initial_model_gain_n_per_mm_per_min = 5.0;
  p.override_range = {1.5, 0.0, 0.2};
  VariableGainController controller(p);
  double lowest = 1.0;
  for (int k = 0; k < 200; ++k) lowest = std::min(lowest, controller.step(5000.0, 0.1));
  EXPECT_DOUBLE_EQ(lowest, 0.2);
}

TEST(OverrideFloor, StepsStayWithinTheFloorAndTheCeiling) {
  // 15 % steps with a 20 % floor: the lowest step at or above it is 30 %.
  const OverrideRange range{1.5, 0.15, 0.2};
  EXPECT_NEAR(applied_override(range, 0.0), 0.30, 1e-12);
  EXPECT_NEAR(applied_override(range, 0.5), 0.45, 1e-12);
  EXPECT_NEAR(applied_override(range, 9.0), 1.50, 1e-12);
  EXPECT_DOUBLE_EQ(applied_override({1.5, 0.0, 0.1}, -1.0), 0.1);
}

TEST(OverrideFloor, AFloorAboveTheCeilingOrNegativeIsNamed) {
  const auto above = validate(OverrideRange{1.0, 0.0, 1.2});
  ASSERT_EQ(above.size(), 1u);
  EXPECT_EQ(above[0].field, "override.min_ratio");
  EXPECT_NE(above[0].message.find("1.2"), std::string::npos);
  EXPECT_NE(above[0].message.find("max_ratio = 1"), std::string::npos);
  const auto negative = validate(OverrideRange{1.0, 0.0, -0.1});
  ASSERT_EQ(negative.size(), 1u);
  EXPECT_EQ(negative[0].field, "override.min_ratio");
}

}  // namespace
}  // namespace feedplan::control
