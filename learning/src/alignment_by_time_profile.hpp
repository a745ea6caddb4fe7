#pragma once
// Method 2 of log_alignment.hpp, for logs without positions: the measured contact signal cross-correlated
// with the plan's engagement over the plan's predicted time finds when the program started on the log's
// clock; each row's s is then the plan's s at that time. Internal to learning.

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning::detail {

//! Aligns a log with forces with a plan with samples; kNoCut when the force never changes between air
//! and contact.
Alignment align_by_time_profile(const force_log::ForceLog& log, const planner::PlanResult& plan);

}  // namespace feedplan::learning::detail
