#pragma once
// How much of the plan's in-cut path the aligned rows cover, and the status that follows from it (kOk,
// kTruncated, kNoCut), for both alignment methods once each row's s is known. Internal to learning.

#include <string>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning::detail {

//! From out.s_mm: sets out.rows_aligned, out.covered_fraction and out.status, and out.message to
//! `method_text` followed by the coverage, the NaN rows and the gaps (out.rows_with_nan, out.gaps).
void finish_coverage(const planner::PlanResult& plan, const force_log::ForceLog& log, Alignment& out,
                     const std::string& method_text);

}  // namespace feedplan::learning::detail
