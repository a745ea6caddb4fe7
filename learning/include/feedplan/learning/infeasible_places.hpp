#pragma once
// Where the logs show a target the machine cannot hold: revolutions cut while every engaged place of the plan
// inside them ran at the machine's minimum feed, and still above the target. There the force does not fall
// below the target at any feed the machine can run (rubbing and the smallest chips, edge forces, runout), so
// learning cannot help: the place stays at the minimum feed, and a target at or above the largest such peak
// is the lowest the logs say can be held everywhere.

#include <string>
#include <vector>

#include "feedplan/learning/measured_revolutions.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning {

//! A measured peak counts as above the target when it exceeds it by more than this share (noise).
inline constexpr double kInfeasibleMargin = 0.02;

//! What the logs show.
struct InfeasiblePlaces {
  int revolutions = 0;             //!< revolutions at the minimum feed above the target
  double first_s_mm = 0.0;         //!< where the first of them starts on the path, mm
  double largest_peak_n = 0.0;     //!< their largest measured peak, N: the lowest target the logs allow there
};

//! The revolutions of `measured` (logs of cycles cut with `plan`) that lie wholly where `plan` ran at the
//! minimum feed (every engaged sample in their span limited by FeedLimitReason::kMinFeed) with a peak above
//! `target_force_n` × (1 + kInfeasibleMargin).
InfeasiblePlaces infeasible_places(const planner::PlanResult& plan, const std::vector<MeasuredRevolutions>& measured,
                                   double target_force_n);

//! One sentence for people ("3 revolutions at the machine's minimum feed still above the target …"), or ""
//! when there are none.
std::string describe(const InfeasiblePlaces& places, double target_force_n);

}  // namespace feedplan::learning
