#pragma once
// One step of the best-achievable-plan search at one place (best_achievable_plan.hpp): the next force
// correction c from the true peak over the target r that the plan with c gave there.
//
// The force taken as proportional to the feed (c · r; the planner holds c · F̂ at the target, so the feed
// falls as 1 / c) converges where the force falls with the feed, but crawls near the machine's force floor,
// where most of the force is rubbing and small chips: with F = F₀ + k / c each step removes only the share
// k / (c · F) of the excess. There — the place's last two plans measured a sensitivity −d ln r / d ln c under
// kFloorSensitivity — the step in ln c is ln r over that sensitivity: the secant in (ln c, ln r).

namespace feedplan::trial {

//! The smallest change of ln r between a place's two plans that its sensitivity is measured from: below it
//! the change is the shift of revolution boundaries between plans more than the feed's effect.
inline constexpr double kMinLogRatioChange = 0.01;

//! Below this sensitivity −d ln r / d ln c (1 where the force is proportional to the feed, 0.7–0.9 with a
//! size effect) the force is taken to hardly fall with the feed: the place is near the force floor.
inline constexpr double kFloorSensitivity = 0.5;

//! The smallest sensitivity a step is scaled by (a step at most 1 / this × the proportional one in ln c).
inline constexpr double kMinSensitivity = 0.15;

//! A place's previous plan: its correction and the peak ratio it gave (0: none).
struct CorrectionTry {
  double correction = 0.0;
  double ratio = 0.0;
};

//! The next correction after the plan with correction `c` gave the peak ratio `r` (> 0), `previous` being the
//! place's plan before it: c · r, or the secant above where the two measured a force near its floor.
double next_force_correction(double c, double r, const CorrectionTry& previous);

}  // namespace feedplan::trial
