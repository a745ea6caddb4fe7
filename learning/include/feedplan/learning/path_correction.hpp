#pragma once
// Iterative learning along one path (the repeated parts of seed 003's title): where the measured peak
// force of a revolution differs from what the refitted model predicts there — mostly where the tool
// enters the material, a geometry the straight-cut response surface cannot represent — the next plan
// of the same program scales the model by the measured ratio at that place: c(s) = F_measured / F̂(s).
// The model carries what generalises; c(s) carries what belongs to this path.

#include <vector>

#include "feedplan/learning/measured_revolutions.hpp"
#include "feedplan/model_db/response_surface_model.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning {

//! Smallest and largest correction applied (a ratio outside is more likely a bad revolution than physics).
inline constexpr double kMinPathCorrection = 0.5;
inline constexpr double kMaxPathCorrection = 2.0;  //!< see kMinPathCorrection

//! The per-sample correction for the next plan of `plan`'s path (one value per plan sample, for
//! PlanSettings::force_correction): every engaged plan sample inside the path span of a measured
//! revolution gets r = F_measured / F̂_model (F̂ of `model` at the revolution's inputs) clamped to
//! [kMinPathCorrection, kMaxPathCorrection] — r itself the first time (`previous` empty), after that
//! √(previous · r): damped, because a revolution's peak comes from one place in its span and the next
//! plan changes the feed there (undamped throughout, the trochoid entries oscillated: +22 %, +29 %,
//! +32 % over cycles 2–4; damped from the first step, cycle 3 of the corner still overshot +10 % at the
//! wall entry, +4.9 % with the first step whole). Samples no revolution covers keep `previous` (1 when
//! it is empty). `measured` holds the revolutions of one or more logs of this plan (their samples and s
//! spans). Tried and left: an affine secant through two cycles' measurements at each place (worse on
//! the trochoid: the places of two cycles' revolution peaks differ by up to a revolution's travel).
std::vector<double> path_correction(const planner::PlanResult& plan, const model_db::ResponseSurfaceModel& model,
                                    const std::vector<MeasuredRevolutions>& measured, const std::vector<double>& previous);

}  // namespace feedplan::learning
