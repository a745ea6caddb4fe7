#pragma once
// The variable-gain adaptive controller of seeds 000/001 (Ulsoy, Koren, Rasmussen 1982, Eqs. 3–5, after
// Masory & Koren 1980): the integral ACC of integral_force_controller.hpp whose gain follows an estimate of
// the process gain, so that the loop gain stays at a chosen value K whatever the depth of cut.
//
//   Eq. 3, controller:                 u   = K_c ∫ (F_R − F_c) dt
//   Eq. 4, process-gain estimation:    K_m = c1 ∫ (F_c − u K_m) dt
//   Eq. 5, controller-gain adaptation: K_c = c2 ∫ (K − K_c K_m) dt
//
// K_m estimates the gain from command to force (F_c / u in steady state, K_p for a unit servo gain) and
// K_c is driven towards K / K_m. Seed 000 prints Eq. 5 as "K − K_o K_m", seed 001 as "K − K_C K_m"; the
// latter is the loop gain the text describes ("a desired constant value of the open-loop gain is
// maintained"), and is what is implemented.
//
// Sampled every Δt (the seeds: 0.1 s) with the force F_k measured at sample k and the command u_{k−1} held
// over the period that produced it:
//   K_m,k = K_m,k−1 + c1 Δt (F_k − u_{k−1} K_m,k−1)
//   K_c,k = K_c,k−1 + c2 Δt (K − K_c,k−1 K_m,k)
//   u_k   = u_{k−1} + K_c,k Δt (F_R − F_k),  held over [kΔt, (k+1)Δt)
// The integrals start at K_m,0 (the initial estimate) and K_c,0 = K / K_m,0: with c1 = c2 = 0 this is the
// conventional ACC tuned for that estimate (seed 000 Fig. 5). As there, u is the applied override times the
// programmed feed, limited by an OverrideRange — seed 001's lathe variant is kLatheOverrideSteps (0–150 %
// in 15 % steps) — and the estimator uses the command the machine applied. The integrator u is clamped to
// the range (no windup); K_m and K_c are kept ≥ 0 (a negative gain would turn the loop's sign).
//
// Units. F in N, u in mm/min, so K_m is in N per mm/min, K_c in mm/min per N·s, K in 1/s, c1 in
// 1/(mm/min · s) and c2 in mm/min per N·s: the seeds' c1 = 0.001 and c2 = 0.5 are read in
// these units (the seeds keep F in sensor units and give none).

#include <string>
#include <vector>

#include "feedplan/control/override_range.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Settings of the variable-gain controller.
struct VariableGainParameters {
  double reference_force_n = 1000.0;  //!< F_R, N (finite, > 0)
  //! K of Eq. 5, the loop gain K_c · K_m to hold, 1/s (finite, > 0). The seeds give none; on the default
  //! TurningProcess at Δt = 0.1 s, 8 /s puts the dominant closed-loop poles at |z| = 0.79 (settling in about
  //! 2 s), and a fixed gain tuned so at 1 mm depth turns unstable above about 2.9 mm (loop gain ≈ 23 /s).
  double desired_loop_gain_per_s = 8.0;
  //! c1 of Eq. 4, 1/(mm/min · s) (finite, ≥ 0; 0: K_m stays at its start). Seeds 000/001: 0.001 and 0.015.
  double estimation_rate_c1 = 0.001;
  //! c2 of Eq. 5, mm/min per N·s (finite, ≥ 0; 0: K_c stays at its start). Seeds 000/001: 0.5 and 0.1.
  double adaptation_rate_c2 = 0.5;
  //! K_m,0, N per mm/min (finite, > 0): the process gain the controller starts from.
  double initial_model_gain_n_per_mm_per_min = 4.0;
  double programmed_feed_mm_per_min = 200.0;  //!< the feed an override ratio of 1 means, mm/min (finite, > 0)
  //! u before the first sample, mm/min (finite, within [0, max_ratio · programmed feed]).
  double initial_feed_mm_per_min = 200.0;
  OverrideRange override_range;  //!< continuous 0–150 % by default; kLatheOverrideSteps for seed 001's lathe
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("variable_gain.estimation_rate_c1 = -0.1: must be finite and ≥ 0"). Empty when usable.
std::vector<InputProblem> validate(const VariableGainParameters& parameters,
                                   const std::string& field_prefix = "variable_gain.");

//! The controller's state, stepped once per sample.
class VariableGainController {
 public:
  //! Throws InputError with validate()'s problems when the parameters are not usable.
  explicit VariableGainController(const VariableGainParameters& parameters);

  //! Takes the force measured now (finite) and the time since the previous sample (finite, > 0; both
  //! asserted), updates K_m, K_c and u as the file comment says and returns the override ratio to hold
  //! until the next sample.
  double step(double measured_force_n, double dt_s);

  double model_gain_n_per_mm_per_min() const { return model_gain_; }                 //!< K_m now
  double controller_gain_mm_per_min_per_n_s() const { return controller_gain_; }     //!< K_c now
  double commanded_feed_mm_per_min() const { return applied_feed_mm_per_min_; }      //!< applied u, mm/min
  //! The override ratio last returned (the initial feed's before the first step).
  double override_ratio() const { return applied_feed_mm_per_min_ / parameters_.programmed_feed_mm_per_min; }

 private:
  VariableGainParameters parameters_;
  double model_gain_ = 0.0;
  double controller_gain_ = 0.0;
  double integrator_mm_per_min_ = 0.0;
  double applied_feed_mm_per_min_ = 0.0;
};

}  // namespace feedplan::control
