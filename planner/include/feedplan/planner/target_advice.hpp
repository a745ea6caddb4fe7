#pragma once
// What a user can do when a plan cannot hold the target everywhere (PlanStatus::kTargetNotMet): advice
// that is true where it is given. Where the model (or its cautious bound) predicts more than the target
// even as the feed goes to 0, a lower minimum feed cannot help — only a higher target or less material
// per pass can; where the target needs a feed below the machine's minimum, a lower minimum feed helps,
// and by how much is computed, not guessed.

#include <string>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! The advice for one plan, with the figures it rests on.
struct TargetAdvice {
  int over_target_samples = 0;         //!< engaged samples predicted above the target (as the plan counts them)
  int unreachable_samples = 0;         //!< of them, above the target even as the feed goes to 0
  double zero_feed_force_n = 0.0;      //!< largest force predicted there at a vanishing feed, N (0: none)
  double needed_min_feed_mm_per_min = 0.0;  //!< the lowest feed the others need to meet the target, mm/min (0: none)
  double target_needed_n = 0.0;        //!< the smallest target met everywhere at the planned feeds, N
  std::string text;                    //!< what to do, in words ("" when the target is met everywhere)
};

//! The advice for `result`, planned from `geometry` with `settings` (the same ones). The force at a
//! vanishing feed and the feed each sample needs are the model's (F̂, or F̂ + z·σ with
//! settings.uncertainty, × settings.force_correction), as the planner evaluates them (feed_limit.hpp).
TargetAdvice target_advice(const PlanGeometry& geometry, const PlanSettings& settings, const PlanResult& result);

}  // namespace feedplan::planner
