#pragma once
// The 1-D search for the feed at one place of a repeated path (learn_along_path): the force at a place
// rises with the chip thickness t_m run there, so the t_m at which it meets the target is a root to
// bracket and close in on from one part to the next — a safeguarded secant, the model's shape giving
// the first step. The planner is steered to that t_m through the correction c it puts on the model.

#include "feedplan/learning/path_correction.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::learning::detail {

//! The model as the planner holds it at one place: F̂(t_m) = transfer_factor · F̂(t_m, L).
struct PlaceModel {
  const model::ResponseSurfaceModel* model = nullptr;
  double contact_length_mm = 0.0;  //!< L the model is evaluated at, mm
  double transfer_factor = 1.0;    //!< the plan sample's chip-load or depth transfer (> 0)

  double force_n(double chip_mm) const;  //!< the planner's F̂ at t_m = chip_mm, N
  //! d ln F̂ / d ln t_m at chip_mm (over the next 10 %); 0 where F̂ ≤ 0.
  double force_exponent(double chip_mm) const;
  //! The c with which the planner runs t_m = chip_mm here (c · F̂(t_m) = target), 0 when F̂ ≤ 0.
  double correction_at(double chip_mm, double target_force_n) const;
};

//! `bracket` with the measurement `now` added (a force at or under the target raises the lower end,
//! one over it lowers the upper end; an end the new measurement contradicts — more force at a thinner
//! chip, or less at a thicker one — is dropped: the latest is believed).
PlaceBracket bracket_with(const PlaceBracket& bracket, const PathMeasurement& now, double target_force_n);

//! The next c at a place measured `now` (the measurement before: `before`, force 0 when none), with
//! `bracket` already holding `now`; `previous` when the model predicts no force there. `noise_n`: the
//! sensor's noise per row in the log of `now`, N (0: not known). See learn_along_path for the rule.
double next_place_correction(const PlaceModel& place, double target_force_n, const PathMeasurement& now,
                             const PathMeasurement& before, const PlaceBracket& bracket, double previous,
                             double noise_n = 0.0);

//! The largest c that does not run the place slower than its bracket's lower end (the thickest chip
//! measured at or under the target); kMaxPathCorrection when there is none.
double largest_correction_not_slower(const PlaceModel& place, double target_force_n, const PlaceBracket& bracket);

//! The t_m in [lo_mm, hi_mm] the planner runs here with correction c (c · F̂(t_m) = target), the nearer end
//! when c lies beyond it; 0 when the model does not rise over the range (no chip to aim at).
double chip_at_correction_mm(const PlaceModel& place, double target_force_n, double c, double lo_mm, double hi_mm);

//! The smallest c that runs the place no thicker a chip than t_b · target / F_b, (t_b, F_b) the bracket's
//! lower end (kMinPathCorrection when there is none): the chip at which a force proportional to the chip
//! would reach the target. A cutting force is concave in the chip with F(0) ≥ 0 (edge forces, a size
//! effect), so F(t) / t does not rise with t and F(t) ≤ F_b · t / t_b above t_b: a step to that chip
//! stays at or under the target whatever the force's shape.
double smallest_correction_not_past_proportional(const PlaceModel& place, double target_force_n,
                                                 const PlaceBracket& bracket);

}  // namespace feedplan::learning::detail
