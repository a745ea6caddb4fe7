#pragma once
// The rows of a force log as both alignment methods see them: which hold a finite position or force,
// their median time step, the counts an Alignment reports (rows, NaN rows, gaps), and how a message
// names one. Internal to learning.

#include <cmath>
#include <cstddef>
#include <string>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/learning/log_alignment.hpp"

namespace feedplan::learning::detail {

//! True when the row's X and Y are finite.
inline bool finite_xy(const force_log::ForceLogRow& row) { return std::isfinite(row.x_mm) && std::isfinite(row.y_mm); }
//! True when the row's Fx and Fy are finite.
inline bool finite_force(const force_log::ForceLogRow& row) { return std::isfinite(row.fx_n) && std::isfinite(row.fy_n); }

//! Median time step of the rows, s (1 ms with fewer than two rows).
double median_step_s(const force_log::ForceLog& log);

//! Sets out.rows, out.rows_with_nan and out.gaps (time steps over 3 × the median step).
void count_rows(const force_log::ForceLog& log, Alignment& out);

//! "row 12 (t = 0.0110 s)": row i (from 0) as messages name it, counted from 1.
std::string row_text(const force_log::ForceLog& log, std::size_t i);

}  // namespace feedplan::learning::detail
