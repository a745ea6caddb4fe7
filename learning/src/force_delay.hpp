#pragma once
// The force signal's lag behind the positions (log_alignment.hpp, "Force delay"): the measured contact
// signal cross-correlated with the plan's engagement at each row's aligned place. Internal to learning.

#include <string>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning::detail {

//! Sets out.delay_s and out.delay_correlation from out.s_mm, searching lags up to options.max_delay_s,
//! and appends the outcome to `text` (why not, when the log has no forces or no contact edge).
void estimate_delay(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options,
                    Alignment& out, std::string& text);

}  // namespace feedplan::learning::detail
