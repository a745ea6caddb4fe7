#include "feedplan/control/arma_estimator.hpp"

#include <Eigen/Dense>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {
namespace {

using Matrix4 = Eigen::Matrix<double, 4, 4, Eigen::RowMajor>;

void set_initial(std::array<double, 16>& covariance, double initial_variance) {
  Eigen::Map<Matrix4>(covariance.data()) = Matrix4::Identity() * initial_variance;
}

}  // namespace

std::vector<InputProblem> validate(const ArmaEstimatorParameters& parameters, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("initial_variance", parameters.initial_variance);
  problems.non_negative("dead_zone_n", parameters.dead_zone_n);
  problems.non_negative("reset_trace", parameters.reset_trace);
  const double start_trace = 4.0 * parameters.initial_variance;
  if (std::isfinite(parameters.reset_trace) && std::isfinite(start_trace) && parameters.initial_variance > 0.0 &&
      parameters.reset_trace >= start_trace) {
    problems.add_value("reset_trace", shortest_number_text(parameters.reset_trace),
                       "must be < 4 × initial_variance = " + shortest_number_text(start_trace) +
                           " (the trace of P₀), or P would be reset after every update");
  }
  return problems.take();
}

ArmaEstimator::ArmaEstimator(const ArmaModel& start, const ArmaEstimatorParameters& parameters)
    : model_(start), parameters_(parameters) {
  ProblemList problems;
  problems.add_all(validate(parameters));
  ProblemList coefficients("arma_estimator.start.");
  coefficients.finite("phi1", start.phi1);
  coefficients.finite("phi2", start.phi2);
  coefficients.finite("theta0", start.theta0);
  coefficients.finite("theta1", start.theta1);
  problems.add_all(coefficients.take());
  problems.throw_if_any();
  set_initial(covariance_, parameters.initial_variance);
}

double ArmaEstimator::covariance_trace() const {
  return Eigen::Map<const Matrix4>(covariance_.data()).trace();
}

ArmaEstimatorStep ArmaEstimator::update(double force_n, const std::array<double, 4>& regressor) {
  assert(std::isfinite(force_n));
  const Eigen::Map<const Eigen::Vector4d> phi(regressor.data());
  assert(phi.allFinite());
  std::array<double, 4> theta_values = parameter_vector(model_);
  Eigen::Map<Eigen::Vector4d> theta(theta_values.data());
  ArmaEstimatorStep step;
  step.error_n = force_n - phi.dot(theta);
  if (std::abs(step.error_n) <= parameters_.dead_zone_n) {
    ++skipped_;
    return step;
  }
  Eigen::Map<Matrix4> p(covariance_.data());
  const Eigen::Vector4d p_phi = p * phi;
  const double denominator = 1.0 + phi.dot(p_phi);
  theta += p_phi * (step.error_n / denominator);
  p -= p_phi * p_phi.transpose() / denominator;
  p = (0.5 * (p + p.transpose())).eval();
  model_ = ArmaModel{theta(0), theta(1), theta(2), theta(3)};
  step.updated = true;
  ++updates_;
  if (p.trace() < parameters_.reset_trace) {
    set_initial(covariance_, parameters_.initial_variance);
    step.reset = true;
    ++resets_;
  }
  return step;
}

}  // namespace feedplan::control
