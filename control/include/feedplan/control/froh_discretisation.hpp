#pragma once
// Seed 004's discrete models (Rubio & De la Sen 2007, §II.B, Eqs. 4–5): a second-order ContinuousSystem
// G(s) sampled every T behind a β-FROH (fractional_order_hold.hpp),
//
//   H_β(z) = Z[h_β(s) G(s)] = (z − β)/z · Z[h_0 G] + β (z − 1)/(T z) · Z[h_0 G/s]
//          = B_β(z) / (z^δ A(z)),   A(z) = det(zI − Φ),   δ = 1 if β ≠ 0, δ = 0 if β = 0.
//
// Computed here from the sampled state equation of the hold, x_{k+1} = Φ x_k + (Γ0 + βΓ1) u_k − βΓ1 u_{k−1}
// (Φ, Γ0, Γ1 over one period as fractional_order_hold.hpp says), whose transfer function is
//
//   H_β(z) = C adj(zI − Φ) ((Γ0 + βΓ1) z − βΓ1) / (z A(z)),
//
// the same function as Eq. 5 (the tests compare the two): B_β(z) = z N(Γ0 + βΓ1) − β N(Γ1) with
// N(g) = C adj(zI − Φ) g, of degree 2. With β = 0 the factor z cancels (δ = 0) and B_0 = N(Γ0) is of
// degree 1. The numerator's roots — the sampled zeros — move with β; the poles do not, apart from the pole
// at the origin a β ≠ 0 adds. Eq. 5 as printed writes the poles e^{T/τ}: the sign of the exponent is lost,
// they are e^{−T/τ} (inside the unit circle for a stable plant).

#include "feedplan/control/continuous_system.hpp"
#include "feedplan/control/polynomial.hpp"

namespace feedplan::control {

//! numerator(z) / denominator(z), the denominator monic.
struct DiscreteTransferFunction {
  Polynomial numerator;    //!< B_β(z), output units per input unit
  Polynomial denominator;  //!< z^δ A(z), monic
};

//! H_β(z) of `system` sampled every `period_s` (finite, > 0) behind a β-FROH (β finite, in [−1, 1]; both
//! asserted, see validate_beta()).
DiscreteTransferFunction froh_transfer_function(const ContinuousSystem& system, double beta, double period_s);

}  // namespace feedplan::control
