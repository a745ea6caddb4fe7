#pragma once
// Seed 002's plant for its force controller (Kim & Kim 1996): the CNC feed drive, identified on a FANUC
// 15-M x axis as (Eq. 3, the 0–10 Hz approximation of Eq. 2)
//
//   v_a(s) / v_c(s) = 14.0 e^{−0.08 s} / (s + 14.0),
//
// followed by the cutting process, here a static gain: the force peak of a spindle revolution is
// K_f · v_a, K_f in N per mm/min, set by the depth of cut and the material (seed 002's experiment held
// 500 N at 360 mm/min in steel at 1 mm depth, 120 mm/min at 2 mm, 320 mm/min in aluminium at 2 mm:
// K_f = 1.39, 4.17 and 1.56 N per mm/min).
//
// Sampling once per revolution with the command held over each period T (zero-order hold), the lag
// τ = 1/14 s and the dead time T_d = N T + δ (0 ≤ δ < T) discretise exactly (modified z-transform): with
// α = e^{−T/τ},
//   v_a(k+1) = α v_a(k) + e^{−(T−δ)/τ} (1 − e^{−δ/τ}) v_c(k−N−1) + (1 − e^{−(T−δ)/τ}) v_c(k−N).
// For T_d < T (N = 0: seed 002's 0.08 s dead time at one sample per revolution above 600 rev/min) the
// force follows the ARMA form of Eq. 17 exactly, with φ1 = −α, φ2 = 0, θ0 = K_f (1 − e^{−(T−δ)/τ}) and
// θ1 = K_f e^{−(T−δ)/τ} (1 − e^{−δ/τ}) — arma_equivalent(). The virtual machine's override channel
// (sim::FeedOverride) discretises the same drive at its own step; this copy runs at the controller's
// period, so that the control module needs no simulator.

#include <optional>
#include <string>
#include <vector>

#include "feedplan/control/arma_model.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Eq. 3's feed drive.
struct FeedDriveParameters {
  double bandwidth_rad_per_s = 14.0;  //!< 1/τ of the lag, rad/s (finite, > 0); seed 002 Eq. 3: 14.0
  double dead_time_s = 0.08;          //!< T_d, s (finite, ≥ 0); seed 002 Eq. 3: 0.08 s, the PMC's delay
};

//! Every problem with the parameters and the sample period, each named "<field_prefix><field>"
//! ("feed_drive.period_s = 0: must be finite and > 0"). Empty when usable.
std::vector<InputProblem> validate(const FeedDriveParameters& parameters, double period_s,
                                   const std::string& field_prefix = "feed_drive.");

//! The exact ARMA form (Eq. 17) of the drive with the force gain `force_gain_n_per_mm_per_min` sampled
//! every `period_s`, when the dead time is shorter than the period; std::nullopt otherwise (the model
//! would need more than two past commands). Needs parameters that pass validate() (asserted).
std::optional<ArmaModel> arma_equivalent(const FeedDriveParameters& parameters, double period_s,
                                         double force_gain_n_per_mm_per_min);

//! Feed drive and cutting gain stepped once per revolution.
class FeedDriveProcess {
 public:
  //! Starts in steady state at the feed `initial_feed_mm_per_min` (commanded and actual; force =
  //! K_f × feed). Throws InputError with validate()'s problems, and "feed_drive.force_gain_n_per_mm_per_min"
  //! / "feed_drive.initial_feed_mm_per_min" when those are not finite and ≥ 0.
  FeedDriveProcess(const FeedDriveParameters& parameters, double period_s, double force_gain_n_per_mm_per_min,
                   double initial_feed_mm_per_min);

  //! Changes K_f from the next step on (finite and ≥ 0, asserted): a new depth of cut or material.
  void set_force_gain(double force_gain_n_per_mm_per_min);

  //! Holds the feed command (finite, asserted) over one period and returns the force peak of the
  //! revolution that ends the period, K_f × v_a, N.
  double step(double command_mm_per_min);

  double actual_feed_mm_per_min() const { return actual_mm_per_min_; }  //!< v_a now, mm/min
  double force_n() const { return force_gain_ * actual_mm_per_min_; }  //!< K_f v_a now, N

 private:
  double alpha_ = 0.0;
  double gain_older_ = 0.0;  // weight of v_c(k−N−1)
  double gain_newer_ = 0.0;  // weight of v_c(k−N)
  std::vector<double> commands_;  // v_c(k−N−1) … v_c(k), oldest first
  double force_gain_ = 0.0;
  double actual_mm_per_min_ = 0.0;
};

}  // namespace feedplan::control
