#include "feedplan/control/milling_plant.hpp"

#include <cassert>

#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const MillingPlantParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("cutting_pressure_n_per_mm2", parameters.cutting_pressure_n_per_mm2);
  problems.positive("immersion_function", parameters.immersion_function);
  if (parameters.teeth < 1) problems.add_value("teeth", std::to_string(parameters.teeth), "must be ≥ 1");
  problems.positive("spindle_speed_rpm", parameters.spindle_speed_rpm);
  problems.positive("feed_drive_time_constant_s", parameters.feed_drive_time_constant_s);
  problems.positive("cutting_time_constant_s", parameters.cutting_time_constant_s);
  return problems.take();
}

double process_gain_n_s_per_mm(const MillingPlantParameters& parameters, double depth_mm) {
  const double spindle_rev_per_s = parameters.spindle_speed_rpm / 60.0;
  return parameters.cutting_pressure_n_per_mm2 * parameters.immersion_function * depth_mm /
         (parameters.teeth * spindle_rev_per_s);
}

double spindle_period_s(const MillingPlantParameters& parameters) { return 60.0 / parameters.spindle_speed_rpm; }

ContinuousSystem milling_system(const MillingPlantParameters& parameters, double depth_mm) {
  assert(validate(parameters).empty());
  const double tau_m = parameters.feed_drive_time_constant_s;
  const double tau_c = parameters.cutting_time_constant_s;
  ContinuousSystem s;
  s.a = {{{-1.0 / tau_m, 0.0}, {process_gain_n_s_per_mm(parameters, depth_mm) / tau_c, -1.0 / tau_c}}};
  s.b = {1.0 / tau_m, 0.0};
  s.c = {0.0, 1.0};
  return s;
}

}  // namespace feedplan::control
