#pragma once
// Seed 004's model-reference milling force controller (Rubio & De la Sen 2007; control/
// froh_model_reference_controller.hpp) set up for the virtual machine's feed override: the basic ZOH
// controller (`model-reference`, the bank {0}), scheme 1 with seed 004's fixed bank of β (`multi-model-1`)
// and scheme 2's neighbour search (`multi-model-2`).
//
// Units. As for the other controllers (feedback_controller.hpp) the feed is counted in percent of the
// program's feed: seed 004's controller works in mm/s, so its programmed feed is set to 6000 "mm/min" —
// 100 of its mm/s — and a command of 100 is the program's feed. Its plant gain K_p is then in N per percent.
//
// The known plant (seed 004 Eq. 3, control/milling_plant.hpp), K_p/((τ_m s + 1)(τ_c s + 1)):
//   K_p: K_p0 = target / 100 N per percent, the premise every controller here starts from (the program's
//     feed cuts at the target). Seed 004 writes K_p = K_c a b / (N n); the controller cannot know the
//     cutting pressure, the immersion or the depth, only their product, so N and n are the machine's
//     (flutes, spindle speed), a = 1 and b = 1 mm (nominal_depth_mm) are placeholders, and K_c is the
//     "cutting pressure" that makes the product K_p0: K_c = K_p0 N n / (a b). The depth is never told to
//     the controller here (set_depth_of_cut_mm is not called): on the virtual machine, as on a real one,
//     the controller does not know where the depth changes. Seed 004 does ("varied in a known way"); here a
//     new depth is a plant-gain error the law has to live with, and with no integrator in its R (the
//     model-following design of Eq. 9 has none) a gain error leaves a steady error — the price of the
//     paper's assumption not holding.
//   τ_m = 1/14 s: the virtual machine's feed drive, seed 002's 14 e^(−0.08 s)/(s + 14) (sim::
//     FeedOverrideOptions); seed 004's 0.1 ms is its own machine's. The 0.08 s dead time has no place in
//     seed 004's plant (second order, no delay) and is left out of the model: the period below is chosen so
//     that the loop stays stable with it.
//   τ_c = one tooth period, 60 / (N n): milling_plant.hpp's choice (seed 004 gives none).
//
// Period. Seed 004 samples once per spindle revolution. Here that is kept when a revolution lasts at least
// kModelReferenceMinPeriodS = 0.1 s, else the controller is stepped every n-th revolution, n the fewest
// spanning it (as the robust servo is), with the largest force of the n. Why: the loop the law does not
// know — the 0.08 s dead time, and the sensor, which reports a revolution's peak only at its end — must fit
// in about one period. Checked by simulating the plant with the dead time and the per-revolution peak
// (tests/trial/model_reference_law_test.cpp): one revolution at 3000 rev/min (0.02 s) oscillates by
// ±250 N and more after a 10 % gain step; 0.1 s settles without oscillation. 0.1 s is also seeds 000/001's
// period and the robust servo's.
//
// Reference model (seed 004 Eq. 6, ξ = 0.75, ω_n T_r = 2.5): a rise time of one period, not seed 004's four.
// With the plant's zero cancelled, the law's steady state on a plant of g times the known gain is
//   F / F_r = g ρ / (1 + g (ρ − 1)),   ρ = A_m(1) / A(1),
// A and A_m the denominators of the sampled plant and reference model (A(1) = (1 − e^(−T/τ_m))(1 − e^(−T/τ_c))).
// A reference model slower than the plant (ρ < 1) makes the feedback positive at low frequency: with four
// periods, ρ ≈ 0.38 at 0.1 s and any g above 1/(1 − ρ) ≈ 1.6 runs the override to its bound. One period
// gives ρ ≈ 1.6 (1.4 with a short tooth period): a plant 40 % stiffer than known is held at +22 %, twice as
// stiff at +45 % — seed 004's controller has no integrator, and relies on the plant being known.

// Start. The controller is first stepped in a cut under way, at the override's 100 %: it starts there in a
// steady state (FrohModelReferenceController::start_in_steady_state), the reference model at the target,
// instead of from rest as in seed 004, whose loop starts the cut.
//
// Override. The controller's range is the adapter's bounds (min_ratio … max_ratio), so its own record of
// the commands is what the machine is asked for. Between two steps the β-FROH's ramp
// f(kT + τ) = f_k + β (f_k − f_k−1) τ/T is applied through ControlLaw::hold (ZOH for β = 0); a ramp that
// leaves the bounds is clamped by the adapter.

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/trial/feedback_controller.hpp"

namespace feedplan::trial {

//! The shortest period the model-reference controllers are stepped at, s (see the file comment).
inline constexpr double kModelReferenceMinPeriodS = 0.1;

//! Seed 004's controller variants on the virtual machine.
enum class ModelReferenceVariant {
  kZeroOrderHold,    //!< model-reference: the basic ZOH controller, bank {0}
  kFixedBank,        //!< multi-model-1: scheme 1 on seed 004's bank 1, 0.9, …, −0.4
  kNeighbourSearch,  //!< multi-model-2: scheme 2, β from 1 in steps of 0.2 halving
};

//! What the controller is set up from.
struct ModelReferenceLawSettings {
  ModelReferenceVariant variant = ModelReferenceVariant::kFixedBank;  //!< which of the three
  double target_force_n = 0.0;   //!< the force to hold, N (finite, > 0); K_p0 = target / 100 N per percent
  double spindle_rpm = 0.0;      //!< the machine's spindle speed, rev/min (finite, > 0): n and τ_c
  int flutes = 0;                //!< the tool's flutes (≥ 1): N and τ_c
  double min_ratio = 0.0;        //!< the lowest override, (finite, in [0, max_ratio])
  double max_ratio = 1.5;        //!< the highest override (finite, > 0)
  //! The shortest period, s (finite, > 0; default kModelReferenceMinPeriodS, see the file comment).
  double min_period_s = kModelReferenceMinPeriodS;
  //! The reference model's rise time in periods (finite, > 0); seed 004: 4, here 1 (see the file comment).
  double rise_time_periods = 1.0;
};

//! Every problem with the settings, each named "<field_prefix><field>" with its value and the rule. Empty
//! when usable.
std::vector<InputProblem> validate(const ModelReferenceLawSettings& settings,
                                   const std::string& field_prefix = "model_reference.");

//! The nominal depth of the placeholder plant, mm (see the file comment: only K_c a b matters).
inline constexpr double kModelReferenceNominalDepthMm = 1.0;

//! The law of the file comment: stepped per revolution group of at least min_period_s, with the β-FROH's
//! ramp as its hold. Throws InputError with validate()'s problems, and the controller's own when it admits
//! no design.
ControlLaw model_reference_law(const ModelReferenceLawSettings& settings);

}  // namespace feedplan::trial
