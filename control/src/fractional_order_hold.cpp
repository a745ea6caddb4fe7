#include "feedplan/control/fractional_order_hold.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

LinearInputTransition linear_input_transition(const ContinuousSystem& system, double interval_s) {
  assert(std::isfinite(interval_s) && interval_s > 0.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) m(i, j) = system.a[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] * interval_s;
    m(i, 2) = system.b[static_cast<std::size_t>(i)] * interval_s;
  }
  m(2, 3) = 1.0;
  const Eigen::Matrix4d e = m.exp();
  LinearInputTransition t;
  for (std::size_t i = 0; i < 2; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    t.phi[i] = {e(row, 0), e(row, 1)};
    t.gamma0[i] = e(row, 2);
    t.gamma1[i] = e(row, 3);
  }
  return t;
}

double fractional_hold_output(double command, double previous_command, double beta, double fraction_of_period) {
  return command + beta * (command - previous_command) * fraction_of_period;
}

std::vector<InputProblem> validate_beta(double beta, const std::string& field) {
  ProblemList problems;
  if (!(std::isfinite(beta) && beta >= -1.0 && beta <= 1.0)) {
    problems.add(field, "= " + shortest_number_text(beta) +
                            ": must be finite and in [−1, 1], the range of seed 004's fractional-order holds");
  }
  return problems.take();
}

}  // namespace feedplan::control
