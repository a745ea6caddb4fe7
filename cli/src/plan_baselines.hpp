#pragma once
// The baselines of `feedplan plan`: the spec's own feed (feed_mm_per_min, the constant feed a CAM
// programmer would use) by the planner's controller model, and with --simulate on the virtual machine,
// with the constant feed whose simulated largest peak equals the plan's (found by running it).

#include "plan_outcome.hpp"

namespace feedplan::cli {

//! The spec's feed predicted; with `check` (the plan run on the virtual machine), the spec's feed and
//! the equal-peak constant feed simulated on `machine`.
PlanBaselines plan_baselines(const PlanInputs& in, const PlannedCycle& planned, const std::optional<trial::PlanCheck>& check,
                             const std::string& materials_path);

//! (baseline − planned) / baseline × 100 for cycle times in s; 0 when the baseline is not positive.
double time_saved_percent(double baseline_s, double planned_s);

}  // namespace feedplan::cli
