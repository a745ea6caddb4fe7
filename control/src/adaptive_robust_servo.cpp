#include "feedplan/control/adaptive_robust_servo.hpp"

#include <cassert>
#include <cmath>

#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const AdaptiveRobustServoParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("reference_force_n", parameters.reference_force_n);
  problems.add_all(validate_poles(parameters.closed_loop_poles, field_prefix + "closed_loop_poles"));
  problems.add_all(validate(parameters.initial_model, field_prefix + "initial_model."));
  problems.add_all(validate(parameters.estimator, field_prefix + "estimator."));
  problems.positive("programmed_feed_mm_per_min", parameters.programmed_feed_mm_per_min);
  problems.add_all(validate(parameters.override_range, field_prefix + "override_range."));
  return problems.take();
}

namespace {

ArmaEstimator checked_estimator(const AdaptiveRobustServoParameters& parameters) {
  ProblemList problems;
  problems.add_all(validate(parameters));
  problems.throw_if_any();
  return ArmaEstimator(parameters.initial_model, parameters.estimator);
}

}  // namespace

AdaptiveRobustServo::AdaptiveRobustServo(const AdaptiveRobustServoParameters& parameters)
    : parameters_(parameters), estimator_(checked_estimator(parameters)) {
  // The starting gains need a period; the assignment's poles do not depend on it, only k's scale, which
  // step() re-derives with the actual T on the first sample.
  const PoleAssignment start = assign_poles(parameters.initial_model, parameters.closed_loop_poles, 1.0);
  if (start.status != PoleAssignmentStatus::kAssigned) {
    throw InputError("robust_servo.initial_model", start.message);
  }
  gains_ = start.gains;
  applied_feed_ = {parameters.programmed_feed_mm_per_min, parameters.programmed_feed_mm_per_min};
}

double AdaptiveRobustServo::step(double measured_force_n, double dt_s) {
  assert(std::isfinite(measured_force_n) && std::isfinite(dt_s) && dt_s > 0.0);
  if (samples_ == 0) force_ = {measured_force_n, measured_force_n};
  learn(measured_force_n);
  reassign_gains(dt_s);
  const double programmed = parameters_.programmed_feed_mm_per_min;
  const double ratio = applied_override(parameters_.override_range, command(measured_force_n, dt_s) / programmed);
  force_ = {measured_force_n, force_[0]};
  applied_feed_ = {ratio * programmed, applied_feed_[0]};
  ++samples_;
  return ratio;
}

void AdaptiveRobustServo::learn(double measured_force_n) {
  if (samples_ < 2) return;
  estimator_.update(measured_force_n, arma_regressor(force_[0], force_[1], applied_feed_[0], applied_feed_[1]));
}

void AdaptiveRobustServo::reassign_gains(double dt_s) {
  const PoleAssignment assignment = assign_poles(estimator_.model(), parameters_.closed_loop_poles, dt_s);
  if (assignment.status == PoleAssignmentStatus::kAssigned) {
    gains_ = assignment.gains;
  } else {
    ++failed_assignments_;
  }
}

double AdaptiveRobustServo::command(double measured_force_n, double dt_s) const {
  const RobustServoGains& g = gains_;
  const double t = dt_s;
  const double n2 = g.gamma3;
  const double n1 = g.gamma4 * g.gamma1 + t * g.k - g.gamma3 * (1.0 + g.gamma0);
  const double n0 = g.gamma3 * g.gamma0 - g.gamma4 * g.gamma1 - t * g.k * g.gamma0 + t * g.gamma4 * g.gamma2;
  return (1.0 + g.gamma0) * applied_feed_[0] - g.gamma0 * applied_feed_[1] + n2 * measured_force_n +
         n1 * force_[0] + n0 * force_[1] - (n2 + n1 + n0) * parameters_.reference_force_n;
}

}  // namespace feedplan::control
