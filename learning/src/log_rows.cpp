#include "log_rows.hpp"

#include <algorithm>
#include <vector>

#include "fixed_text.hpp"

namespace feedplan::learning::detail {

namespace {

// A time step longer than this many median steps is a gap in the data.
constexpr double kGapFactor = 3.0;

}  // namespace

// Median time step of the rows, s.
double median_step_s(const force_log::ForceLog& log) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < log.rows.size(); ++i) dt.push_back(log.rows[i].t_s - log.rows[i - 1].t_s);
  if (dt.empty()) return 1e-3;
  std::nth_element(dt.begin(), dt.begin() + static_cast<long>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

// Rows, NaN rows and gaps (shared by both methods).
void count_rows(const force_log::ForceLog& log, Alignment& out) {
  out.rows = static_cast<int>(log.rows.size());
  std::vector<double> dt;
  dt.reserve(log.rows.size());
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    const auto& row = log.rows[i];
    if ((log.has_positions && !finite_xy(row)) || (log.has_forces && !finite_force(row))) ++out.rows_with_nan;
    if (i > 0) dt.push_back(row.t_s - log.rows[i - 1].t_s);
  }
  if (dt.empty()) return;
  const double median = median_step_s(log);
  for (double step : dt) {
    if (step > kGapFactor * median) ++out.gaps;
  }
}

std::string row_text(const force_log::ForceLog& log, std::size_t i) {
  return "row " + std::to_string(i + 1) + " (t = " + fixed(log.rows[i].t_s, 4) + " s)";
}

}  // namespace feedplan::learning::detail
