#pragma once
// Iterative learning along one path (the repeated parts of seed 003's title): where the measured peak
// force differs from what the refitted model predicts there — mostly where the tool enters the
// material, a geometry the straight-cut response surface cannot represent — the next plan of the same
// program scales the model at that place: F = c(s) · F̂(s). The model carries what generalises; c(s)
// carries what belongs to this path.

#include <vector>

#include "feedplan/learning/measured_revolutions.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning {

//! Smallest and largest correction applied (a ratio outside is more likely a bad measurement than physics).
inline constexpr double kMinPathCorrection = 0.5;
inline constexpr double kMaxPathCorrection = 2.0;  //!< see kMinPathCorrection
//! Two measurements at a place whose t_m differ by less than this share of the larger give no slope.
inline constexpr double kMinSecantSpread = 0.15;
//! The secant's t_m at the target is kept within the measured t_m range widened by this factor either way.
inline constexpr double kSecantReach = 2.0;
//! Tooth periods whose runout factor exceeds this (their tooth cuts less than 1/1.25 of its turn's largest)
//! are not learned from; see learn_along_path.
inline constexpr double kMaxRunoutFactor = 1.25;

//! What was last measured at one plan sample.
struct PathMeasurement {
  double chip_mm = 0.0;            //!< t_m at the feed run, mm
  double contact_length_mm = 0.0;  //!< L as the model is evaluated, mm
  double force_n = 0.0;            //!< peak force (standing for a revolution's, on the model's axial depth), N; 0: none
  double window_mm = 0.0;          //!< longest tooth period measured here, as path length, mm
};

//! The state of learning along a path, one entry per plan sample (every plan of the path has the same samples).
struct PathLearning {
  std::vector<double> correction;            //!< c per plan sample, for PlanSettings::force_correction
  std::vector<double> place_correction;      //!< c per plan sample before the look-ahead (what the next step updates)
  std::vector<PathMeasurement> measurement;  //!< the latest measurement per plan sample
};

//! One learning step along `plan`'s path from the tooth periods of `measured` (one or more logs cut
//! with `plan`; MeasuredRevolutions::tooth_periods, each peak × its runout factor), with
//! `model` the refitted model the next plan uses and `previous` the state after the step before (empty
//! the first time; with only `correction` set, as read back from a plan report, that is the previous c).
//!
//! Place: inside a run of consecutive tooth periods, the force, t_m and L at a plan sample are
//! interpolated linearly between the peak places around it (the end values beyond the first and the
//! last peak) — up to Z places per revolution, so an entry where the force rises within one revolution is
//! resolved. Several logs are averaged. Plan samples no tooth period covers keep `previous`. A tooth period
//! whose runout factor exceeds kMaxRunoutFactor is left out: with a few µm of runout at thin chips a tooth
//! can cut a fraction of the largest one's chip, and its factor — the median over the steady turns nearest
//! to it, which may lie where the feed and engagement differ — multiplies its small peak into a revolution
//! peak that the place never had. Measured on the trochoid at 400 N with the sample model, 4 cycles on
//! machines of the family (data/machines/family): family-09 (5–6 µm runout) cycle 4 at 91.4 s and 17.8 % RMS
//! with those periods, 35.9 s and 2.8 % without; family-02 (4 µm) 35.5 s, 5.3 % → 25.5 s, 2.4 %.
//!
//! Correction at a measured place, with r = F / F̂(t_m, L):
//!  - the first measurement: c = r;
//!  - a second one at a t_m at least kMinSecantSpread apart, the force rising with t_m: the secant
//!    through both (F = α + β t_m at this place) gives the t* at which the force reaches
//!    `target_force_n` and c = (α + β t*) / F̂(t*, L) — the factor where the next plan will run (t* kept
//!    within the measured t_m range widened by kSecantReach);
//!  - otherwise: c = √(c_previous · r), damped.
//! Clamped to [kMinPathCorrection, kMaxPathCorrection]. Why the secant: at an entry the ratio to a
//! straight-cut model depends on the feed (trochoid entry, place s = 19.9 mm: 1.48 at t_m 0.076 mm,
//! 1.01 at 0.010 mm), so a ratio measured at one feed is wrong at the next plan's; taken whole it
//! oscillated (cycles 3–4: +24 %, +12 %), damped it converged too slowly (+14 %, +9 %). Why the
//! spread: closer measurements give a slope made of noise (spiral at 5 %: +8 %, +11 %).
//!
//! Look-ahead: the c handed to the planner (`correction`) is the largest c over the next window_mm of
//! path — a peak is placed only to within its tooth period, and where the force rises along the path
//! the plan must have slowed down before the place the rise was seen at (the trochoid's first entry:
//! +38 % in cycle 3 without; the window is the longest seen at the place, as the next plan may run as
//! fast as any earlier one).
PathLearning learn_along_path(const planner::PlanResult& plan, const model::ResponseSurfaceModel& model,
                              const std::vector<MeasuredRevolutions>& measured, double target_force_n,
                              const PathLearning& previous);

}  // namespace feedplan::learning
