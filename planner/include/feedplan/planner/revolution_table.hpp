#pragma once
// Every revolution of a peak comparison (peak_comparison.hpp) as CSV rows: where along the path the error
// is, not only how large — what `loop --revolutions` writes per cycle, and what the learning benchmark
// writes for each cycle and the best achievable plan.

#include <string>

#include "feedplan/planner/peak_comparison.hpp"

namespace feedplan::planner {

//! The header line (with its newline): cycle, s_start_mm, s_end_mm, x_mm, y_mm, peak_n, planned_force_n,
//! target_n, error_percent, in_cut, held, steady.
std::string revolution_table_header();

//! One line per revolution of `comparison`, its first column `cycle` (a cycle number or a name such as
//! "best"), at target `target_force_n`.
std::string revolution_table_rows(const std::string& cycle, const PeakComparison& comparison, double target_force_n);

}  // namespace feedplan::planner
