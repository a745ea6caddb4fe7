#pragma once
// What `feedplan plan --target-sweep` prints: the model and kind it planned with, then one row per target —
// status, predicted cycle time, largest predicted peak — and, where the target is below what the model says the
// cut can do at any feed, the smallest target met everywhere; as a table, or as JSON with --json.

#include <string>
#include <vector>

#include "plan_outcome.hpp"
#include "feedplan/planner/target_sweep.hpp"

namespace feedplan::cli {

//! Prints `rows` of `cycle` planned with `model` (JSON with `json`).
void print_target_sweep(bool json, const std::string& cycle, const PlanModel& model,
                        const std::vector<planner::TargetSweepRow>& rows);

}  // namespace feedplan::cli
