#pragma once
// Method 1 of log_alignment.hpp: the logged positions matched forward along the planned path, then the
// coverage and the force delay; or why the log is not this program's (off the path, or in inches).
// Internal to learning.

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning::detail {

//! Aligns a log with positions with a plan with samples; with `check_units`, a log that fits the path only
//! after × or ÷ 25.4 is kUnitsLookWrong instead of kNotThisProgram.
Alignment align_by_positions(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options,
                             bool check_units);

}  // namespace feedplan::learning::detail
