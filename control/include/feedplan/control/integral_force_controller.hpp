#pragma once
// The conventional ACC of seeds 000/001 (their Fig. 1 and Eq. 3): a fixed-gain integral controller that
// moves the feed to hold the measured force at a reference,
//
//   u = K_c ∫₀ᵗ (F_R − F_c) dt,
//
// sampled every Δt as u_k = u_{k−1} + K_c Δt (F_R − F_c,k) — the command u_k is computed from the force
// measured at the sample and held until the next one. u is a feed in mm/min; the machine applies it as a
// feed override, the ratio u / programmed feed, limited by an OverrideRange (seed 001: 0–150 %, on the lathe
// in 15 % steps). The integrator is kept within the range too (clamped to [0, max_ratio · programmed
// feed]), so that a force the override cannot reach does not wind it up.
//
// The loop gain is K_c · K_p (1/s) for a process gain K_p (N per mm/min): fixed K_c tuned at one depth of
// cut becomes unstable where K_p is a few times larger (seed 000, Fig. 5). That is what the variable-gain
// controller (variable_gain_controller.hpp) remedies; with c1 = c2 = 0 it is this controller.

#include <string>
#include <vector>

#include "feedplan/control/override_range.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Settings of the fixed-gain integral ACC.
struct IntegralControllerParameters {
  double reference_force_n = 1000.0;  //!< F_R, N (finite, > 0)
  //! K_c of Eq. 3, mm/min of feed per N·s of accumulated force error (finite, ≥ 0).
  double controller_gain_mm_per_min_per_n_s = 0.1;
  double programmed_feed_mm_per_min = 200.0;  //!< the feed an override ratio of 1 means, mm/min (finite, > 0)
  //! u before the first sample, mm/min (finite, within [0, max_ratio · programmed feed]).
  double initial_feed_mm_per_min = 200.0;
  OverrideRange override_range;  //!< what the override can express (continuous 0–150 % by default)
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("integral_acc.controller_gain_mm_per_min_per_n_s = -1: must be finite and ≥ 0"). Empty when usable.
std::vector<InputProblem> validate(const IntegralControllerParameters& parameters,
                                   const std::string& field_prefix = "integral_acc.");

//! The controller's state, stepped once per sample.
class IntegralForceController {
 public:
  //! Throws InputError with validate()'s problems when the parameters are not usable.
  explicit IntegralForceController(const IntegralControllerParameters& parameters);

  //! Takes the force measured now (finite) and the time since the previous sample (finite, > 0; both
  //! asserted), integrates the error and returns the override ratio to hold until the next sample.
  double step(double measured_force_n, double dt_s);

  //! The feed the applied override commands, mm/min (override × programmed feed).
  double commanded_feed_mm_per_min() const { return applied_feed_mm_per_min_; }
  //! The override ratio last returned (the initial feed's before the first step).
  double override_ratio() const { return applied_feed_mm_per_min_ / parameters_.programmed_feed_mm_per_min; }

 private:
  IntegralControllerParameters parameters_;
  double integrator_mm_per_min_ = 0.0;
  double applied_feed_mm_per_min_ = 0.0;
};

}  // namespace feedplan::control
