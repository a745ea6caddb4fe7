// Bad parameters are refused, each problem naming the field, the value and the allowed range (STYLE.md,
// "Errors"): validate() lists them all, the constructors throw them as one InputError.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "feedplan/control/adaptive_robust_servo.hpp"
#include "feedplan/control/arma_estimator.hpp"
#include "feedplan/control/feed_drive.hpp"
#include "feedplan/control/integral_force_controller.hpp"
#include "feedplan/control/pole_assignment.hpp"
#include "feedplan/control/turning_process.hpp"
#include "feedplan/control/variable_gain_controller.hpp"
#include "has_problem.hpp"

namespace feedplan::control {
namespace {

using test_support::has_problem;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

TEST(ParameterValidation, VariableGainNamesEveryBadField) {
  VariableGainParameters p;
  p.estimation_rate_c1 = -0.001;
  p.adaptation_rate_c2 = kNan;
  p.desired_loop_gain_per_s = 0.0;
  p.initial_feed_mm_per_min = 1000.0;  // above 150 % of 200 mm/min
  p.override_range.step_ratio = 2.0;   // above max_ratio 1.5
  const auto problems = validate(p);
  EXPECT_TRUE(has_problem(problems, "variable_gain.estimation_rate_c1", "= -0.001: must be finite and ≥ 0"));
  EXPECT_TRUE(has_problem(problems, "variable_gain.adaptation_rate_c2", "= nan: must be finite and ≥ 0"));
  EXPECT_TRUE(has_problem(problems, "variable_gain.desired_loop_gain_per_s", "= 0: must be finite and > 0"));
  EXPECT_TRUE(has_problem(problems, "variable_gain.override_range.step_ratio", "= 2: must be ≤ max_ratio = 1.5"));
  EXPECT_EQ(problems.size(), 4u) << "the feed is not judged against a broken range";
  p.override_range.step_ratio = 0.15;
  EXPECT_TRUE(has_problem(validate(p), "variable_gain.initial_feed_mm_per_min", "= 1000: must be ≤ override_range.max_ratio"));
  try {
    VariableGainController controller(p);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(has_problem(e.problems(), "variable_gain.estimation_rate_c1", "must be finite and ≥ 0"));
  }
}

TEST(ParameterValidation, IntegralControllerRefusesANegativeGain) {
  IntegralControllerParameters p;
  p.controller_gain_mm_per_min_per_n_s = -1.0;
  p.programmed_feed_mm_per_min = 0.0;
  const auto problems = validate(p);
  EXPECT_TRUE(has_problem(problems, "integral_acc.controller_gain_mm_per_min_per_n_s", "= -1: must be finite and ≥ 0"));
  EXPECT_TRUE(has_problem(problems, "integral_acc.programmed_feed_mm_per_min", "= 0: must be finite and > 0"));
  EXPECT_THROW(IntegralForceController{p}, InputError);
}

TEST(ParameterValidation, PlantsRefuseANonPositivePeriod) {
  TurningProcessParameters turning;
  turning.servo_damping_ratio = -0.7;
  EXPECT_TRUE(has_problem(validate(turning), "turning.servo_damping_ratio", "= -0.7: must be finite and > 0"));
  try {
    TurningProcess plant(TurningProcessParameters{}, 0.0, 1.0, 100.0);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_TRUE(has_problem(e.problems(), "turning.period_s", "= 0: must be finite and > 0"));
  }
  EXPECT_TRUE(has_problem(validate(FeedDriveParameters{}, -0.1), "feed_drive.period_s", "= -0.1: must be finite and > 0"));
  FeedDriveParameters drive;
  drive.dead_time_s = kNan;
  EXPECT_TRUE(has_problem(validate(drive, 0.1), "feed_drive.dead_time_s", "= nan: must be finite and ≥ 0"));
}

TEST(ParameterValidation, RobustServoRefusesPolesOutsideTheUnitCircleAndABrokenEstimator) {
  AdaptiveRobustServoParameters p;
  p.closed_loop_poles = {0.3, 1.2, -1.0, kNan};
  p.estimator.reset_trace = 1.0;  // above trace P₀ = 4e-5
  p.initial_model.theta0 = 0.0;
  p.initial_model.theta1 = 0.0;
  const auto problems = validate(p);
  EXPECT_TRUE(has_problem(problems, "robust_servo.closed_loop_poles[1]", "= 1.2: must be finite and inside the unit circle"));
  EXPECT_TRUE(has_problem(problems, "robust_servo.closed_loop_poles[2]", "= -1: must be finite and inside the unit circle"));
  EXPECT_TRUE(has_problem(problems, "robust_servo.closed_loop_poles[3]", "= nan"));
  EXPECT_FALSE(has_problem(problems, "robust_servo.closed_loop_poles[0]", ""));
  EXPECT_TRUE(has_problem(problems, "robust_servo.estimator.reset_trace", "= 1: must be < 4 × initial_variance"));
  EXPECT_TRUE(has_problem(problems, "robust_servo.initial_model.theta0", "must not both be 0"));
  EXPECT_THROW(AdaptiveRobustServo{p}, InputError);
}

TEST(ParameterValidation, ValidDefaultsHaveNoProblems) {
  EXPECT_TRUE(validate(VariableGainParameters{}).empty());
  EXPECT_TRUE(validate(IntegralControllerParameters{}).empty());
  EXPECT_TRUE(validate(TurningProcessParameters{}).empty());
  EXPECT_TRUE(validate(FeedDriveParameters{}, 0.1).empty());
  EXPECT_TRUE(validate(AdaptiveRobustServoParameters{}).empty());
  EXPECT_TRUE(validate(ArmaEstimatorParameters{}).empty());
  EXPECT_TRUE(validate(kLatheOverrideSteps).empty());
}

}  // namespace
}  // namespace feedplan::control
