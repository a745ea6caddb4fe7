#include "feedplan/control/reference_model.hpp"

#include <cassert>
#include <cmath>

#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const ReferenceModelParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("damping_ratio", parameters.damping_ratio);
  problems.positive("rise_time_periods", parameters.rise_time_periods);
  problems.positive("natural_frequency_times_rise_time", parameters.natural_frequency_times_rise_time);
  return problems.take();
}

double natural_frequency_rad_per_s(const ReferenceModelParameters& parameters, double period_s) {
  return parameters.natural_frequency_times_rise_time / (parameters.rise_time_periods * period_s);
}

ContinuousSystem reference_system(const ReferenceModelParameters& parameters, double period_s) {
  assert(validate(parameters).empty());
  assert(std::isfinite(period_s) && period_s > 0.0);
  const double wn = natural_frequency_rad_per_s(parameters, period_s);
  ContinuousSystem s;
  s.a = {{{0.0, wn}, {-wn, -2.0 * parameters.damping_ratio * wn}}};
  s.b = {0.0, wn};
  s.c = {1.0, 0.0};
  return s;
}

}  // namespace feedplan::control
