#pragma once
// Logged positions matched forward along the planned path (method 1 of log_alignment.hpp): each row's
// place at or after the previous row's, then which unmatched rows are the machine arriving or leaving
// and which left the path. Internal to learning.

#include <cstddef>
#include <vector>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "path_index.hpp"

namespace feedplan::learning::detail {

//! Each row's place on the path and the counts of the rows that have none.
struct PositionMatch {
  std::vector<double> s_mm;
  std::size_t first = 0, last = 0;  // first and last matched rows (first > last: none)
  int off_path = 0;                 // unmatched rows among those
  std::size_t first_off_path = 0;
  int leading = 0, trailing = 0;  // rows before the program (first match at the path's start) / after it
  int span_rows = 0;              // rows with positions that should follow the path
};

// The part of the path where the tool is in material: from the first to the last engaged plan sample
// (the whole path when none is engaged).
struct CutSpan {
  double first_mm = 0.0;
  double last_mm = 0.0;
};

CutSpan cut_span(const planner::PlanResult& plan);

//! Matches the rows (positions × `scale`) forward along `path` within `reach_mm`; rows before and after
//! the first and last matches count as arriving or leaving when those lie before and after `cut`.
//! None matched: first == the row count, and every row with a position is leading.
PositionMatch match_positions(const force_log::ForceLog& log, const PathIndex& path, double scale, double reach_mm,
                              const CutSpan& cut);

}  // namespace feedplan::learning::detail
