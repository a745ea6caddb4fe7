#include "feedplan/control/held_system_simulator.hpp"

#include <cassert>
#include <cmath>

namespace feedplan::control {

HeldSystemSimulator::HeldSystemSimulator(const ContinuousSystem& system, double period_s, int substeps_per_period)
    : system_(system), period_s_(period_s), substeps_(substeps_per_period) {
  assert(std::isfinite(period_s) && period_s > 0.0 && substeps_per_period >= 1);
  substep_ = linear_input_transition(system_, period_s_ / substeps_);
  period_outputs_ = {output()};
}

void HeldSystemSimulator::set_system(const ContinuousSystem& system) {
  system_ = system;
  substep_ = linear_input_transition(system_, period_s_ / substeps_);
}

double HeldSystemSimulator::output() const { return system_.c[0] * x_[0] + system_.c[1] * x_[1]; }

void HeldSystemSimulator::set_state(const std::array<double, 2>& x) {
  assert(std::isfinite(x[0]) && std::isfinite(x[1]));
  x_ = x;
}

double HeldSystemSimulator::step(double command, double previous_command, double beta) {
  assert(std::isfinite(command) && std::isfinite(previous_command) && beta >= -1.0 && beta <= 1.0);
  const double rise_per_substep = beta * (command - previous_command) / substeps_;
  period_outputs_.assign(1, output());
  for (int j = 0; j < substeps_; ++j) {
    const double start = fractional_hold_output(command, previous_command, beta, static_cast<double>(j) / substeps_);
    std::array<double, 2> next{};
    for (std::size_t i = 0; i < 2; ++i) {
      next[i] = substep_.phi[i][0] * x_[0] + substep_.phi[i][1] * x_[1] + substep_.gamma0[i] * start +
                substep_.gamma1[i] * rise_per_substep;
    }
    x_ = next;
    period_outputs_.push_back(output());
  }
  return output();
}

}  // namespace feedplan::control
