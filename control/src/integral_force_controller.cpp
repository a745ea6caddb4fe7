#include "feedplan/control/integral_force_controller.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const IntegralControllerParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("reference_force_n", parameters.reference_force_n);
  problems.non_negative("controller_gain_mm_per_min_per_n_s", parameters.controller_gain_mm_per_min_per_n_s);
  problems.positive("programmed_feed_mm_per_min", parameters.programmed_feed_mm_per_min);
  problems.add_all(validate_override_start(parameters.override_range, parameters.programmed_feed_mm_per_min,
                                           parameters.initial_feed_mm_per_min, field_prefix));
  return problems.take();
}

IntegralForceController::IntegralForceController(const IntegralControllerParameters& parameters)
    : parameters_(parameters) {
  ProblemList problems;
  problems.add_all(validate(parameters));
  problems.throw_if_any();
  integrator_mm_per_min_ = parameters.initial_feed_mm_per_min;
  applied_feed_mm_per_min_ =
      parameters.programmed_feed_mm_per_min *
      applied_override(parameters.override_range, integrator_mm_per_min_ / parameters.programmed_feed_mm_per_min);
}

double IntegralForceController::step(double measured_force_n, double dt_s) {
  assert(std::isfinite(measured_force_n) && std::isfinite(dt_s) && dt_s > 0.0);
  const double programmed = parameters_.programmed_feed_mm_per_min;
  const double error_n = parameters_.reference_force_n - measured_force_n;
  integrator_mm_per_min_ = std::clamp(
      integrator_mm_per_min_ + parameters_.controller_gain_mm_per_min_per_n_s * dt_s * error_n,
      parameters_.override_range.min_ratio * programmed, parameters_.override_range.max_ratio * programmed);
  const double ratio = applied_override(parameters_.override_range, integrator_mm_per_min_ / programmed);
  applied_feed_mm_per_min_ = ratio * programmed;
  return ratio;
}

}  // namespace feedplan::control
