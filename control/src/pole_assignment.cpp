#include "feedplan/control/pole_assignment.hpp"

#include <Eigen/Dense>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {
namespace {

//! Coefficients p3, p2, p1, p0 of Π (z − p_i) = z⁴ + p3 z³ + p2 z² + p1 z + p0.
Eigen::Vector4d desired_polynomial(const std::array<double, 4>& poles) {
  std::array<double, 5> c{1.0, 0.0, 0.0, 0.0, 0.0};  // c[j]: coefficient of z^(degree − j)
  int degree = 0;
  for (double p : poles) {
    ++degree;
    for (int j = degree; j >= 1; --j) c[j] -= p * c[j - 1];
  }
  return {c[1], c[2], c[3], c[4]};
}

//! Solves the Sylvester system for (γ0, n2, n1, n0) with A(z)(z − 1) = z³ + a2 z² + a1 z + a0.
struct ControllerPolynomials {
  double gamma0 = 0.0, n2 = 0.0, n1 = 0.0, n0 = 0.0;
  bool solvable = false;
};

ControllerPolynomials solve_diophantine(const ArmaModel& model, const Eigen::Vector4d& desired) {
  const double a2 = model.phi1 - 1.0, a1 = model.phi2 - model.phi1, a0 = -model.phi2;
  const double t0 = model.theta0, t1 = model.theta1;
  // Coefficients of z³, z², z¹, z⁰ of A(z)(z − 1)(z − γ0) − B(z) N(z) − z⁴, linear in (γ0, n2, n1, n0).
  Eigen::Matrix4d m;
  m << -1.0, -t0, 0.0, 0.0,  //
      -a2, -t1, -t0, 0.0,    //
      -a1, 0.0, -t1, -t0,    //
      -a0, 0.0, 0.0, -t1;
  const Eigen::Vector4d rhs = desired - Eigen::Vector4d(a2, a1, a0, 0.0);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector4d s = svd.singularValues();
  ControllerPolynomials result;
  if (!(s(3) > 1e-9 * s(0))) return result;
  const Eigen::Vector4d x = svd.solve(rhs);
  result = {x(0), x(1), x(2), x(3), true};
  return result;
}

RobustServoGains gains_of(const ControllerPolynomials& c, double period_s) {
  RobustServoGains g;
  g.gamma0 = c.gamma0;
  g.gamma3 = c.n2;
  g.gamma4 = 1.0;
  const double m1 = c.n1 + g.gamma3 * (1.0 + g.gamma0);
  const double m0 = c.n0 - g.gamma3 * g.gamma0;
  if (std::abs(1.0 - g.gamma0) > 1e-9) {
    g.k = (m1 + m0) / (period_s * (1.0 - g.gamma0));
    g.gamma1 = m1 - period_s * g.k;
    g.gamma2 = 0.0;
  } else {
    g.k = 0.0;
    g.gamma1 = m1;
    g.gamma2 = (m0 + m1) / period_s;
  }
  return g;
}

}  // namespace

std::vector<InputProblem> validate_poles(const std::array<double, 4>& poles, const std::string& field_prefix) {
  ProblemList problems;
  for (std::size_t i = 0; i < poles.size(); ++i) {
    if (!(std::isfinite(poles[i]) && std::abs(poles[i]) < 1.0)) {
      problems.add(field_prefix + "[" + std::to_string(i) + "]",
                   "= " + shortest_number_text(poles[i]) + ": must be finite and inside the unit circle, in (−1, 1)");
    }
  }
  return problems.take();
}

PoleAssignment assign_poles(const ArmaModel& model, const std::array<double, 4>& poles, double period_s) {
  assert(std::isfinite(model.phi1) && std::isfinite(model.phi2) && std::isfinite(model.theta0) &&
         std::isfinite(model.theta1));
  assert(validate_poles(poles).empty());
  assert(std::isfinite(period_s) && period_s > 0.0);
  const ControllerPolynomials c = solve_diophantine(model, desired_polynomial(poles));
  PoleAssignment result;
  if (!c.solvable) {
    result.message = "the plant's zero z = −θ1/θ0 (nearly) cancels a root of A(z)(z − 1) (θ0 = " +
                     shortest_number_text(model.theta0) + ", θ1 = " + shortest_number_text(model.theta1) +
                     "): no gains place every pole";
    return result;
  }
  result.status = PoleAssignmentStatus::kAssigned;
  result.gains = gains_of(c, period_s);
  return result;
}

}  // namespace feedplan::control
