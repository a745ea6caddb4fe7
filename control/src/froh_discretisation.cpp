#include "feedplan/control/froh_discretisation.hpp"

#include <cassert>
#include <cmath>

#include "feedplan/control/fractional_order_hold.hpp"

namespace feedplan::control {
namespace {

//! N(g)(z) = C adj(zI − Φ) g, of degree 1.
Polynomial adjugate_numerator(const ContinuousSystem& system, const LinearInputTransition& t, const std::array<double, 2>& g) {
  const auto& phi = t.phi;
  const auto& c = system.c;
  return {{c[0] * g[0] + c[1] * g[1],
           c[0] * (phi[0][1] * g[1] - phi[1][1] * g[0]) + c[1] * (phi[1][0] * g[0] - phi[0][0] * g[1])}};
}

}  // namespace

DiscreteTransferFunction froh_transfer_function(const ContinuousSystem& system, double beta, double period_s) {
  assert(std::isfinite(beta) && beta >= -1.0 && beta <= 1.0);
  assert(std::isfinite(period_s) && period_s > 0.0);
  const LinearInputTransition t = linear_input_transition(system, period_s);
  const Polynomial a{{1.0, -(t.phi[0][0] + t.phi[1][1]), t.phi[0][0] * t.phi[1][1] - t.phi[0][1] * t.phi[1][0]}};
  if (beta == 0.0) return {adjugate_numerator(system, t, t.gamma0), a};
  const std::array<double, 2> leading{t.gamma0[0] + beta * t.gamma1[0], t.gamma0[1] + beta * t.gamma1[1]};
  const Polynomial n_leading = adjugate_numerator(system, t, leading);
  const Polynomial n_slope = adjugate_numerator(system, t, t.gamma1);
  const Polynomial b{{n_leading.coefficients[0], n_leading.coefficients[1] - beta * n_slope.coefficients[0],
                      -beta * n_slope.coefficients[1]}};
  return {b, multiply(Polynomial{{1.0, 0.0}}, a)};
}

}  // namespace feedplan::control
