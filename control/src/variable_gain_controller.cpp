#include "feedplan/control/variable_gain_controller.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const VariableGainParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("reference_force_n", parameters.reference_force_n);
  problems.positive("desired_loop_gain_per_s", parameters.desired_loop_gain_per_s);
  problems.non_negative("estimation_rate_c1", parameters.estimation_rate_c1);
  problems.non_negative("adaptation_rate_c2", parameters.adaptation_rate_c2);
  problems.positive("initial_model_gain_n_per_mm_per_min", parameters.initial_model_gain_n_per_mm_per_min);
  problems.positive("programmed_feed_mm_per_min", parameters.programmed_feed_mm_per_min);
  problems.add_all(validate_override_start(parameters.override_range, parameters.programmed_feed_mm_per_min,
                                           parameters.initial_feed_mm_per_min, field_prefix));
  return problems.take();
}

VariableGainController::VariableGainController(const VariableGainParameters& parameters) : parameters_(parameters) {
  ProblemList problems;
  problems.add_all(validate(parameters));
  problems.throw_if_any();
  model_gain_ = parameters.initial_model_gain_n_per_mm_per_min;
  controller_gain_ = parameters.desired_loop_gain_per_s / model_gain_;
  integrator_mm_per_min_ = parameters.initial_feed_mm_per_min;
  applied_feed_mm_per_min_ =
      parameters.programmed_feed_mm_per_min *
      applied_override(parameters.override_range, integrator_mm_per_min_ / parameters.programmed_feed_mm_per_min);
}

double VariableGainController::step(double measured_force_n, double dt_s) {
  assert(std::isfinite(measured_force_n) && std::isfinite(dt_s) && dt_s > 0.0);
  const VariableGainParameters& p = parameters_;
  model_gain_ = std::max(
      0.0, model_gain_ + p.estimation_rate_c1 * dt_s * (measured_force_n - applied_feed_mm_per_min_ * model_gain_));
  controller_gain_ = std::max(
      0.0, controller_gain_ + p.adaptation_rate_c2 * dt_s * (p.desired_loop_gain_per_s - controller_gain_ * model_gain_));
  integrator_mm_per_min_ =
      std::clamp(integrator_mm_per_min_ + controller_gain_ * dt_s * (p.reference_force_n - measured_force_n),
                 p.override_range.min_ratio * p.programmed_feed_mm_per_min,
                 p.override_range.max_ratio * p.programmed_feed_mm_per_min);
  const double ratio = applied_override(p.override_range, integrator_mm_per_min_ / p.programmed_feed_mm_per_min);
  applied_feed_mm_per_min_ = ratio * p.programmed_feed_mm_per_min;
  return ratio;
}

}  // namespace feedplan::control
