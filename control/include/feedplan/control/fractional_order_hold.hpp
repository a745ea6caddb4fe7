#pragma once
// The fractional-order hold of correcting gain β (β-FROH) of seed 004 (Rubio & De la Sen 2007, §II.B,
// after Bárcena, De la Sen & Sagastabeitia 2000). Its transfer function (Eq. 4)
//
//   h_β(s) = (1 − β e^{−sT} + β (1 − e^{−sT}) / (T s)) (1 − e^{−sT}) / s
//
// has the impulse response 1 + β τ/T over the first period and −β τ/T over the second (τ: time since the
// period began), so from the samples u_k it puts out
//
//   u(kT + τ) = u_k + β (u_k − u_{k−1}) τ/T,   0 ≤ τ < T:
//
// the last step extrapolated by the fraction β. β = 0 is the zero-order hold, β = 1 the (predictive)
// first-order hold; seed 004 takes β in [−1, 1].
//
// Over any interval of length h on which the input is linear, u(σ) = a + s σ/h, a ContinuousSystem moves
// exactly as
//
//   x(h) = Φ x(0) + Γ0 a + Γ1 s,   Φ = e^{Ah},  Γ0 = ∫₀ʰ e^{A(h−σ)} B dσ,  Γ1 = ∫₀ʰ e^{A(h−σ)} B σ/h dσ,
//
// all three read off the exponential of the 4×4 matrix [[A h, B h, 0], [0, 0, 1], [0, 0, 0]] (the input
// and its slope carried as two more states). With h = T, a = u_k and s = β (u_k − u_{k−1}) this is the
// β-FROH sampled over one period.

#include <array>
#include <string>
#include <vector>

#include "feedplan/control/continuous_system.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Φ, Γ0, Γ1 of the file comment for one interval.
struct LinearInputTransition {
  std::array<std::array<double, 2>, 2> phi{};  //!< Φ = e^{Ah}, row by row
  std::array<double, 2> gamma0{};              //!< Γ0: the state's answer to the input's value at the start
  std::array<double, 2> gamma1{};              //!< Γ1: the state's answer to the input's rise over the interval
};

//! The transition of `system` over `interval_s` (finite, > 0; asserted) for an input linear on it.
LinearInputTransition linear_input_transition(const ContinuousSystem& system, double interval_s);

//! The β-FROH's output a fraction `fraction_of_period` (in [0, 1]) into the period that starts at the
//! sample `command` after the sample `previous_command`: command + β (command − previous_command) fraction.
double fractional_hold_output(double command, double previous_command, double beta, double fraction_of_period);

//! A problem named `field` unless β is finite and in [−1, 1] ("froh.beta = 1.5: must be finite and in
//! [−1, 1], the range of seed 004's fractional-order holds"). Empty when usable.
std::vector<InputProblem> validate_beta(double beta, const std::string& field);

}  // namespace feedplan::control
