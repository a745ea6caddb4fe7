#include "feedplan/control/turning_process.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const TurningProcessParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("specific_cutting_force_n_per_mm2", parameters.specific_cutting_force_n_per_mm2);
  problems.positive("spindle_rpm", parameters.spindle_rpm);
  problems.non_negative("process_time_constant_s", parameters.process_time_constant_s);
  problems.positive("servo_natural_frequency_rad_per_s", parameters.servo_natural_frequency_rad_per_s);
  problems.positive("servo_damping_ratio", parameters.servo_damping_ratio);
  problems.positive("servo_dc_gain", parameters.servo_dc_gain);
  return problems.take();
}

double process_gain_n_per_mm_per_min(const TurningProcessParameters& parameters, double depth_mm) {
  return parameters.specific_cutting_force_n_per_mm2 * depth_mm / parameters.spindle_rpm;
}

TurningProcess::TurningProcess(const TurningProcessParameters& parameters, double period_s, double depth_mm,
                               double initial_command_mm_per_min)
    : parameters_(parameters), period_s_(period_s), depth_mm_(depth_mm) {
  ProblemList problems("turning.");
  problems.add_all(validate(parameters));
  problems.positive("period_s", period_s);
  problems.non_negative("depth_mm", depth_mm);
  problems.non_negative("initial_command_mm_per_min", initial_command_mm_per_min);
  problems.throw_if_any();
  x_[0] = parameters.servo_dc_gain * initial_command_mm_per_min;
  x_[2] = process_gain_n_per_mm_per_min(parameters, depth_mm) * x_[0];
  discretise();
}

void TurningProcess::set_depth_mm(double depth_mm) {
  assert(std::isfinite(depth_mm) && depth_mm >= 0.0);
  if (depth_mm == depth_mm_) return;
  depth_mm_ = depth_mm;
  discretise();
}

double TurningProcess::step(double command_mm_per_min) {
  assert(std::isfinite(command_mm_per_min));
  double next[3];
  for (int i = 0; i < 3; ++i) {
    next[i] = gamma_[i] * command_mm_per_min;
    for (int j = 0; j < 3; ++j) next[i] += phi_[i][j] * x_[j];
  }
  for (int i = 0; i < 3; ++i) x_[i] = next[i];
  ++steps_;
  return x_[2];
}

// The zero-order-hold discretisation of the file comment. With τ = 0 the force is K_p f at every instant:
// F_c is then read off the feed rather than integrated.
void TurningProcess::discretise() {
  const double wn = parameters_.servo_natural_frequency_rad_per_s;
  const double zeta = parameters_.servo_damping_ratio;
  const double kp = process_gain_n_per_mm_per_min(parameters_, depth_mm_);
  const double tau = parameters_.process_time_constant_s;
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 1) = 1.0;
  m(1, 0) = -wn * wn;
  m(1, 1) = -2.0 * zeta * wn;
  m(1, 3) = parameters_.servo_dc_gain * wn * wn;
  if (tau > 0.0) {
    m(2, 0) = kp / tau;
    m(2, 2) = -1.0 / tau;
  }
  const Eigen::Matrix4d e = (m * period_s_).exp();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) phi_[i][j] = e(i, j);
    gamma_[i] = e(i, 3);
  }
  if (tau == 0.0) {
    for (int j = 0; j < 3; ++j) phi_[2][j] = kp * phi_[0][j];
    gamma_[2] = kp * gamma_[0];
  }
}

}  // namespace feedplan::control
