// One step of the best-achievable-plan search (trial/correction_step.hpp) on force laws whose root is known in
// closed form: the planner holds c · F̂ at the target, so the feed falls as 1 / c, and a place whose force is
// F₀ + k · feed has F(c) = F₀ + k / c; the c that meets the target T is k / (T − F₀).

#include <gtest/gtest.h>

#include <cmath>

#include "feedplan/trial/correction_step.hpp"

namespace feedplan::trial {
namespace {

// Steps from c = 1 until the force is within `tolerance` of the target; the steps taken (max_steps + 1: never).
int steps_to_target(double floor_n, double k_n, double target_n, double tolerance, int max_steps, double* c_out) {
  double c = 1.0;
  CorrectionTry previous;
  for (int step = 0; step <= max_steps; ++step) {
    const double r = (floor_n + k_n / c) / target_n;
    if (std::abs(r - 1.0) <= tolerance) {
      *c_out = c;
      return step;
    }
    const double next = next_force_correction(c, r, previous);
    previous = {c, r};
    c = next;
  }
  *c_out = c;
  return max_steps + 1;
}

TEST(CorrectionStep, AForceProportionalToTheFeedTakesTheProportionalStep) {
  // F = k / c: r falls exactly as c rises, sensitivity 1, and c · r is the root in one step.
  EXPECT_DOUBLE_EQ(next_force_correction(1.0, 1.3, CorrectionTry{}), 1.3);
  EXPECT_DOUBLE_EQ(next_force_correction(1.3, 1.0 / 1.3 * 1.3 * 1.01, CorrectionTry{1.0, 1.3}), 1.3 * 1.01);
}

TEST(CorrectionStep, NearTheForceFloorTheSecantFindsTheFeedTheProportionalStepCrawlsTo) {
  // The floor 95 % of the target (target 1.05 × floor, as the family benchmark sets it); at c = 1 the force
  // is twice the target. Root c* = k / (T − F₀).
  const double floor_n = 380.0, target_n = 400.0, k_n = 2.0 * target_n - floor_n;
  const double root = k_n / (target_n - floor_n);
  double c = 0.0;
  const int steps = steps_to_target(floor_n, k_n, target_n, 0.02, 40, &c);
  EXPECT_LE(steps, 8);
  EXPECT_NEAR(c, root, 0.4 * root);  // within 2 % of the target in force is ±40 % in c this close to the floor
  // The proportional step alone: each removes k / (c F) of the excess, a few per cent of it near the floor.
  double c_proportional = 1.0;
  int proportional_steps = 0;
  for (; proportional_steps < 40; ++proportional_steps) {
    const double r = (floor_n + k_n / c_proportional) / target_n;
    if (std::abs(r - 1.0) <= 0.02) break;
    c_proportional *= r;
  }
  EXPECT_GT(proportional_steps, 20);
}

TEST(CorrectionStep, SameRatioTwiceOrAForceRisingWithCKeepsTheProportionalStep) {
  // A change of r under kMinLogRatioChange says nothing about the force law (revolution boundaries moved).
  EXPECT_DOUBLE_EQ(next_force_correction(2.0, 1.1, CorrectionTry{1.0, 1.1 * 1.005}), 2.0 * 1.1);
  // r rising as c rises: no law the planner's correction obeys; the proportional step.
  EXPECT_DOUBLE_EQ(next_force_correction(2.0, 1.2, CorrectionTry{1.0, 1.1}), 2.0 * 1.2);
}

TEST(CorrectionStep, AFlatMeasuredLawStepsAtMostOneOverTheSmallestSensitivity) {
  // Sensitivity 0.029 measured: the step is ln r / kMinSensitivity, not ln r / 0.029.
  const double c = 2.0, r = 1.2;
  const double step = next_force_correction(c, r, CorrectionTry{1.0, r * std::exp(0.02)});
  EXPECT_NEAR(std::log(step / c), std::log(r) / kMinSensitivity, 1e-12);
}

}  // namespace
}  // namespace feedplan::trial
