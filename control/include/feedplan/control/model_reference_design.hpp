#pragma once
// Seed 004's model-following controller (Rubio & De la Sen 2007, §III.D, Eqs. 7–9, in the pole-placement
// form of Åström & Wittenmark): for a discrete plant B(z)/A(z) (A monic of degree n, B of degree n − 1:
// n = 2 under a zero-order hold, 3 under a β-FROH with β ≠ 0) and a discrete reference model Bm(z)/Am(z)
// (the same continuous model behind the same hold, Am of degree n), the control law (Eq. 9)
//
//   R(q) f_c,k = T(q) F_r,k − S(q) F_p,k
//
// puts the closed loop at B T / (A R + B S). The design:
//   B = B⁺ B⁻: B⁺ monic with the zeros strictly inside the cancellation radius (seed 004: the stable ones),
//     cancelled by the controller; B⁻ the rest with B's leading coefficient (seed 004: the unstable zeros,
//     which the closed loop must keep);
//   the Diophantine equation (Eq. 8), A R1 + B⁻ S = A_d with A_d = z^{d⁻} Am and d⁻ = deg B⁻, solved for R1
//     monic of degree d⁻ and S of degree n − 1 (a Sylvester system, unique when A and B⁻ are coprime —
//     always so when A is stable and B⁻ holds only zeros outside it);
//   R = B⁺ R1 (degree n − 1), T = Bm / B⁻(1).
// The closed loop is then A R + B S = B⁺ A_d and
//
//   F_p / F_r = B⁻(z) Bm(z) / (B⁻(1) z^{d⁻} Am(z)):
//
// the reference model exactly when every zero is cancelled (B⁻ a constant), and otherwise the model times
// B⁻(z) / (B⁻(1) z^{d⁻}), unit gain at z = 1. The extra poles at the origin keep T/R proper. Seed 004 writes
// the target as B⁻ B'm Ao / (Am Ao) and gives deg R = n, deg Am Ao = 2n − 1; with Ao = 1 the minimal
// degrees above already close the count (deg B⁺ A_d = 2n − 1), so no observer polynomial is added — a reading
// of the printed degrees, which do not add up as printed (A R would be of degree 2n).

#include <span>
#include <string>

#include "feedplan/control/froh_discretisation.hpp"
#include "feedplan/control/polynomial.hpp"

namespace feedplan::control {

//! R, S, T of Eq. 9.
struct ModelReferenceController {
  Polynomial r;  //!< R(z), monic, degree n − 1 (feed, mm/s, per feed)
  Polynomial s;  //!< S(z), degree n − 1 (feed per force, mm/s per N)
  Polynomial t;  //!< T(z), degree ≤ n − 1 (feed per force, mm/s per N)
};

//! Whether the design succeeded.
enum class ModelReferenceStatus {
  kDesigned,           //!< R, S, T as the file comment says
  kDegenerateZeros,    //!< B's leading coefficient is (nearly) 0: the plant's relative degree is above one
  kZeroAtOne,          //!< a kept zero sits at z = 1: no T gives the closed loop unit gain
  kUnstableReference,  //!< a pole of the reference model is not strictly inside the unit circle
  kNotCoprime,         //!< A and B⁻ (nearly) share a root: the Diophantine equation has no unique solution
};

//! The result of design_model_reference().
struct ModelReferenceDesign {
  ModelReferenceStatus status = ModelReferenceStatus::kNotCoprime;
  ModelReferenceController controller;  //!< valid when kDesigned
  Polynomial cancelled_zeros;  //!< B⁺, monic (the constant 1 when nothing is cancelled)
  Polynomial kept_zeros;       //!< B⁻, with B's leading coefficient
  //! B⁺ A_d: what A R + B S is asked to be, the closed loop's characteristic polynomial.
  Polynomial closed_loop_polynomial;
  std::string message;  //!< why not, when not designed
};

//! The design of the file comment for the plant `plant` and the reference model `reference` (denominators
//! monic of the same degree n ≥ 1, numerators of degree ≤ n − 1 and finite; asserted). Zeros of modulus
//! below `cancellation_radius` (in (0, 1], asserted; seed 004: 1, every stable zero) are cancelled.
ModelReferenceDesign design_model_reference(const DiscreteTransferFunction& plant, const DiscreteTransferFunction& reference,
                                            double cancellation_radius = 1.0);

//! f_c,k of Eq. 9 for the controller `c` with R of degree n − 1: the reference F_r,k, F_r,k−1, … and the
//! forces F_p,k, F_p,k−1, … newest first (at least n values each), the commands f_c,k−1, f_c,k−2, … newest
//! first (at least n − 1). Asserted.
double model_reference_command(const ModelReferenceController& c, std::span<const double> reference_n,
                               std::span<const double> force_n, std::span<const double> past_commands);

}  // namespace feedplan::control
