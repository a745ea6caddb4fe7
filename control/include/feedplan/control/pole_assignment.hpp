#pragma once
// The gains of seed 002's robust servo controller (Kim & Kim 1996, Eqs. 22–30) that place the closed-loop
// poles where asked, for a plant in the ARMA form of Eq. 17.
//
// The controller. With e(t) = f(t) − f*(t) and the sample period T:
//   Eq. 22, servo compensator:      η(t+1) = η(t) + T e(t)
//   Eq. 23, stabilising compensator: ε(t+1) = γ0 ε(t) + γ1 f(t) + γ2 η(t)
//   Eq. 24, feedback:                v(t)   = k η(t) + γ3 f(t) + γ4 ε(t)
// Closed on the plant's observable canonical form (Eqs. 19–20), the state X = (x1, x2, η, ε) evolves by the
// 4×4 matrix Φ(K) of Eq. 28, K = (k, γ0, γ1, γ2, γ3, γ4) (Eq. 30).
//
// The assignment. Seed 002 places the eigenvalues of Φ(K) by parametric eigenstructure assignment (Fahmy &
// O'Reilly 1988), which also spends K's two spare degrees of freedom on the eigenvectors. Here the
// eigenvalues alone are placed, by the characteristic polynomial: as a transfer function the controller is
// v = N(z)/D(z) f (reference aside) with D(z) = (z − 1)(z − γ0) and N(z) = n2 z² + n1 z + n0, and
//   det(zI − Φ(K)) = A(z) (z − 1)(z − γ0) − B(z) N(z),
// A(z) = z² + φ1 z + φ2, B(z) = θ0 z + θ1. Setting this equal to the desired P(z) = Π (z − p_i) is four
// linear equations in (γ0, n2, n1, n0) — a Sylvester system, solvable exactly when A(z)(z − 1) and B(z) have
// no common root (seed 002's robustness condition 4: the plant's zero must not sit at the command's mode
// z = 1, nor cancel a plant pole). The gains then follow with the free choices γ4 = 1 (ε's scale) and
// γ2 = 0 (ε driven by the force alone):
//   γ3 = n2,  m1 = n1 + γ3 (1 + γ0),  m0 = n0 − γ3 γ0,  k = (m1 + m0) / (T (1 − γ0)),  γ1 = m1 − T k;
// when γ0 = 1 (then k cannot carry the integral path) k = 0, γ1 = m1 and γ2 = (m0 + m1) / T instead.
//
// Seed 002's poles, z = 0.3, 0.35, 0.7, 0.75 at one sample per revolution (100 ms), are "a damping
// coefficient of 1.0 and a dominant natural frequency of 2.8 rad/s".

#include <array>
#include <string>
#include <vector>

#include "feedplan/control/arma_model.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! K of Eq. 30.
struct RobustServoGains {
  double k = 0.0;       //!< gain on the servo compensator's state η, mm/min per N·s
  double gamma0 = 0.0;  //!< γ0: the stabilising compensator's own pole
  double gamma1 = 0.0;  //!< γ1: force into ε, per N … in ε's units (γ4 = 1 makes ε a feed, mm/min per N)
  double gamma2 = 0.0;  //!< γ2: η into ε, per N·s
  double gamma3 = 0.0;  //!< γ3: force fed straight to the feed, mm/min per N
  double gamma4 = 1.0;  //!< γ4: ε into the feed (1: ε is in mm/min)
};

//! Seed 002's closed-loop poles in the z-plane.
inline constexpr std::array<double, 4> kKimKimPoles{0.3, 0.35, 0.7, 0.75};

//! Every problem with the poles, each named "<field_prefix>[i]" ("poles[2] = 1.2: must be finite and
//! inside the unit circle, in (−1, 1)"). The poles are real (seed 002's are); empty when usable.
std::vector<InputProblem> validate_poles(const std::array<double, 4>& poles, const std::string& field_prefix = "poles");

//! Whether the gains were found.
enum class PoleAssignmentStatus {
  kAssigned,    //!< Φ(K) has the requested eigenvalues
  kNotCoprime,  //!< A(z)(z − 1) and B(z) (nearly) share a root: no K places every pole; gains left at zero
};

//! The result of assign_poles().
struct PoleAssignment {
  PoleAssignmentStatus status = PoleAssignmentStatus::kNotCoprime;
  RobustServoGains gains;  //!< valid when status is kAssigned
  std::string message;     //!< why not, when not assigned
};

//! The gains of the file comment for the model `model` (finite coefficients, asserted), the poles
//! `poles` (passing validate_poles(), asserted) and the sample period `period_s` (finite, > 0, asserted).
//! kNotCoprime when the Sylvester system's smallest singular value is below 1e-9 of its largest.
PoleAssignment assign_poles(const ArmaModel& model, const std::array<double, 4>& poles, double period_s);

}  // namespace feedplan::control
