#include "feedplan/control/arma_model.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const ArmaModel& model, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.finite("phi1", model.phi1);
  problems.finite("phi2", model.phi2);
  problems.finite("theta0", model.theta0);
  problems.finite("theta1", model.theta1);
  if (model.theta0 == 0.0 && model.theta1 == 0.0) {
    problems.add_value("theta0", "0", "θ0 and θ1 must not both be 0 (the feed would not reach the force)");
  }
  return problems.take();
}

double steady_gain_n_per_mm_per_min(const ArmaModel& model) {
  const double a1 = 1.0 + model.phi1 + model.phi2;
  if (a1 == 0.0) return std::numeric_limits<double>::infinity();
  return (model.theta0 + model.theta1) / a1;
}

ArmaPlant::ArmaPlant(const ArmaModel& model, double initial_feed_mm_per_min) : model_(model) {
  ProblemList problems;
  problems.add_all(validate(model));
  ProblemList start("arma.");
  start.finite("initial_feed_mm_per_min", initial_feed_mm_per_min);
  problems.add_all(start.take());
  if (problems.empty() && !std::isfinite(steady_gain_n_per_mm_per_min(model))) {
    problems.add("arma.steady_gain", "= inf: 1 + φ1 + φ2 = 0, the model integrates and has no steady state to start in");
  }
  problems.throw_if_any();
  feed_1_mm_per_min_ = initial_feed_mm_per_min;
  force_1_n_ = force_2_n_ = steady_gain_n_per_mm_per_min(model) * initial_feed_mm_per_min;
}

double ArmaPlant::step(double feed_mm_per_min, double disturbance_n) {
  assert(std::isfinite(feed_mm_per_min));
  const double next = -model_.phi1 * force_1_n_ - model_.phi2 * force_2_n_ + model_.theta0 * feed_mm_per_min +
                      model_.theta1 * feed_1_mm_per_min_ + disturbance_n;
  force_2_n_ = force_1_n_;
  force_1_n_ = next;
  feed_1_mm_per_min_ = feed_mm_per_min;
  return next;
}

void ArmaPlant::set_model(const ArmaModel& model) {
  assert(validate(model).empty());
  model_ = model;
}

}  // namespace feedplan::control
