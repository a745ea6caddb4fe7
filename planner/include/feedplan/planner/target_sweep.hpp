#pragma once
// The time-versus-target curve of one cycle (`feedplan plan --target-sweep FROM:TO:STEP`): the same path,
// engagement and model planned at each target of a range, so a user can see what each newton of allowed
// force buys in cycle time, and where the target falls below what the model says the cut can do at any
// feed (the force floor: rubbing and small-chip forces at the thinnest chips).

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! The targets FROM, FROM + STEP, … up to TO (inclusive, within a millionth of STEP), N.
struct TargetRange {
  double from_n = 0.0;
  double to_n = 0.0;
  double step_n = 0.0;
};

//! Most targets one sweep plans.
inline constexpr int kMaxSweepTargets = 200;

//! Parses "FROM:TO:STEP" (newtons, e.g. "250:500:25"). Throws InputError naming `field` with the value and
//! what was expected: three numbers separated by ':', finite, 0 < FROM ≤ TO, STEP > 0, at most
//! kMaxSweepTargets targets.
TargetRange parse_target_range(const std::string& text, const std::string& field);

//! The targets of `range`, in increasing order.
std::vector<double> targets_of(const TargetRange& range);

//! One target's plan.
struct TargetSweepRow {
  double target_n = 0.0;                   //!< the target, N
  PlanStatus status = PlanStatus::kOk;     //!< the plan's status
  double cycle_time_s = 0.0;               //!< predicted cycle time, s
  double max_predicted_force_n = 0.0;      //!< largest predicted per-revolution peak, N
  int unreachable_samples = 0;             //!< engaged samples predicted above the target even at a vanishing feed
  double target_needed_n = 0.0;            //!< with status kTargetNotMet: the smallest target met everywhere, N
};

//! `settings` planned on `geometry` at every target of `range` (everything else as in `settings`).
std::vector<TargetSweepRow> sweep_targets(const PlanGeometry& geometry, const PlanSettings& settings,
                                          const TargetRange& range);

}  // namespace feedplan::planner
