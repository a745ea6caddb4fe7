#pragma once
// Seed 002's adaptive cutting-force controller (Kim & Kim 1996, §3 and Fig. 7): an ARMA model of feed drive
// and cutting process (arma_model.hpp), its parameters estimated on line by RLS with covariance resetting
// and a dead zone (arma_estimator.hpp), and a robust servo controller whose gains are re-assigned from the
// estimate every sample so that the closed-loop poles stay where asked (pole_assignment.hpp). One sample
// per spindle revolution: the measured force is the revolution's peak, the output the feed override held
// over the next revolution.
//
// Each sample t, with the force f(t) measured:
//   the estimator learns from f(t) with the regressor (−f(t−1), −f(t−2), v(t−1), v(t−2)) of the feeds the
//     machine applied (from the third sample on, when two past samples exist);
//   the gains are assigned from the estimate; when the estimate admits no assignment (kNotCoprime) the
//     previous gains stay (counted);
//   the feed v(t) of Eqs. 22–24 is applied as an override of the programmed feed, within the override range
//     (seed 002: 0–255 %, sent as 8 bits).
//
// Realisation. Eqs. 22–24 are run in their input–output form: eliminating η and ε,
//   v(t) = (1 + γ0) v(t−1) − γ0 v(t−2) + n2 f(t) + n1 f(t−1) + n0 f(t−2) − N(1) f*,
// with n2 = γ3, n1 = γ4γ1 + Tk − γ3(1 + γ0), n0 = γ3γ0 − γ4γ1 − Tkγ0 + Tγ4γ2 and
// N(1) = n2 + n1 + n0 = T (k (1 − γ0) + γ4 γ2) (pole_assignment.hpp). With constant gains it is the same
// controller; run on the feeds the machine actually applied (after the override range), it cannot wind up
// when the range cuts the command, and the gains can change every sample without a bump in the feed (seed
// 002 does not say how it handled either). Before the first sample the feed is the programmed feed and
// the past forces equal the first one measured, so the first command is the programmed feed corrected
// by N(1) (f(0) − f*).
//
// The force may come from the feed drive's servo currents (seed 002 §2: I_q = a + b·|F|, within 8 % and up
// to 62 Hz); learning::fit_current_calibration fits that map, and the controller takes the force it gives.

#include <array>
#include <string>
#include <vector>

#include "feedplan/control/arma_estimator.hpp"
#include "feedplan/control/arma_model.hpp"
#include "feedplan/control/override_range.hpp"
#include "feedplan/control/pole_assignment.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Settings of the adaptive robust servo.
struct AdaptiveRobustServoParameters {
  double reference_force_n = 500.0;  //!< f*, N (finite, > 0); seed 002's experiment: 500 N
  //! Closed-loop poles in the z-plane, real, in (−1, 1); seed 002: 0.3, 0.35, 0.7, 0.75.
  std::array<double, 4> closed_loop_poles = kKimKimPoles;
  //! The estimator's start: seed 002's feed drive (feed_drive.hpp) sampled every 0.1 s with the gain of its
  //! first cut (500 N at 360 mm/min: 1.389 N per mm/min) — arma_equivalent({14, 0.08}, 0.1, 500/360).
  ArmaModel initial_model{-0.246597, 0.0, 0.339189, 0.707204};
  ArmaEstimatorParameters estimator;  //!< RLS settings
  double programmed_feed_mm_per_min = 300.0;  //!< the feed an override ratio of 1 means, mm/min (finite, > 0)
  //! What the override can express: seed 002 sends 0–255 % in 1 % steps.
  OverrideRange override_range{2.55, 0.01};
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("robust_servo.closed_loop_poles[3] = 1.1: must be finite and inside the unit circle, in (−1, 1)").
//! Empty when usable.
std::vector<InputProblem> validate(const AdaptiveRobustServoParameters& parameters,
                                   const std::string& field_prefix = "robust_servo.");

//! The controller's state, stepped once per spindle revolution.
class AdaptiveRobustServo {
 public:
  //! Assigns the starting gains from initial_model. Throws InputError with validate()'s problems, and
  //! "robust_servo.initial_model" when its gains cannot be assigned (kNotCoprime).
  explicit AdaptiveRobustServo(const AdaptiveRobustServoParameters& parameters);

  //! Takes the revolution's force (finite) and the sample period T (finite, > 0; both asserted) and
  //! returns the override ratio to hold over the next revolution, as the file comment says.
  double step(double measured_force_n, double dt_s);

  const ArmaModel& model() const { return estimator_.model(); }     //!< the estimate now
  const RobustServoGains& gains() const { return gains_; }           //!< the gains in use
  const ArmaEstimator& estimator() const { return estimator_; }      //!< the RLS state
  int failed_assignments() const { return failed_assignments_; }     //!< samples whose estimate was not coprime
  double commanded_feed_mm_per_min() const { return applied_feed_[0]; }  //!< v(t) applied, mm/min
  //! The override ratio last returned (1 before the first step).
  double override_ratio() const { return applied_feed_[0] / parameters_.programmed_feed_mm_per_min; }

 private:
  void learn(double measured_force_n);
  void reassign_gains(double dt_s);
  double command(double measured_force_n, double dt_s) const;

  AdaptiveRobustServoParameters parameters_;
  ArmaEstimator estimator_;
  RobustServoGains gains_;
  std::array<double, 2> force_{0.0, 0.0};         // f(t−1), f(t−2)
  std::array<double, 2> applied_feed_{0.0, 0.0};  // v(t−1), v(t−2); after a step [0] is the latest v(t)
  int samples_ = 0;
  int failed_assignments_ = 0;
};

}  // namespace feedplan::control
