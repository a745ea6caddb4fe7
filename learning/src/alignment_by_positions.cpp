#include "alignment_by_positions.hpp"

#include <cstddef>
#include <limits>
#include <string>

#include "coverage.hpp"
#include "fixed_text.hpp"
#include "force_delay.hpp"
#include "forward_match.hpp"
#include "log_rows.hpp"
#include "path_index.hpp"

namespace feedplan::learning::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMmPerInch = 25.4;

// Why the rows do not follow the path, or "" when they do.
std::string not_this_program(const force_log::ForceLog& log, const PathIndex& path, const PositionMatch& m,
                             const AlignmentOptions& options, double scale) {
  const std::size_t n = log.rows.size();
  auto distance_of = [&](std::size_t i) {
    const auto& row = log.rows[i];
    return path.distance_to_path(scale * row.x_mm, scale * row.y_mm, scale * row.z_mm);
  };
  const std::string reach = fixed(options.max_distance_mm, 2) + " mm";
  if (m.first == n) {
    std::size_t i = 0;
    while (i < n && !finite_xy(log.rows[i])) ++i;
    if (i == n) return "no row has a position";
    return "no logged position comes within " + reach + " of the planned path; " + row_text(log, i) + " is " +
           fixed(distance_of(i), 2) + " mm from it";
  }
  const double span_rows = static_cast<double>(m.span_rows);
  if (m.off_path > options.max_off_path_fraction * span_rows) {
    return std::to_string(m.off_path) + " of " + std::to_string(m.span_rows) + " rows (" +
           percent(m.off_path / span_rows) + ", allowed " + percent(options.max_off_path_fraction) +
           ") are more than " + reach + " from the planned path; the first, " + row_text(log, m.first_off_path) +
           ", is " + fixed(distance_of(m.first_off_path), 2) + " mm from it";
  }
  return "";
}

// A log whose rows do not follow the path (`problem`): no s, and kUnitsLookWrong when (with `check_units`)
// they do after × or ÷ 25.4, else kNotThisProgram.
void reject(const force_log::ForceLog& log, const PathIndex& path, const CutSpan& cut, const AlignmentOptions& options,
            bool check_units, const std::string& problem, Alignment& out) {
  out.s_mm.assign(log.rows.size(), kNaN);
  if (check_units) {
    for (const double scale : {kMmPerInch, 1.0 / kMmPerInch}) {
      const PositionMatch scaled = match_positions(log, path, scale, options.max_distance_mm, cut);
      if (scaled.first < log.rows.size() && not_this_program(log, path, scaled, options, scale).empty()) {
        out.status = AlignmentStatus::kUnitsLookWrong;
        out.message = scale > 1.0
                          ? "the logged positions fit the planned path after x 25.4: the log looks like inches; "
                            "convert it to mm"
                          : "the logged positions fit the planned path after / 25.4: the log is scaled by "
                            "25.4 (mm read as inches?); convert it to mm";
        return;
      }
    }
  }
  out.status = AlignmentStatus::kNotThisProgram;
  out.message = "the log does not follow the planned path: " + problem;
}

// "aligned by positions" and the rows before, after and off the path.
std::string positions_text(const force_log::ForceLog& log, const PositionMatch& m) {
  std::string text = "aligned by positions";
  if (m.leading > 0) text += "; " + std::to_string(m.leading) + " rows before the path starts";
  if (m.trailing > 0) text += "; " + std::to_string(m.trailing) + " rows after it ends";
  if (m.off_path > 0) {
    text += "; " + std::to_string(m.off_path) + " rows off the path (first: " + row_text(log, m.first_off_path) + ")";
  }
  return text;
}

}  // namespace

Alignment align_by_positions(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options,
                             bool check_units) {
  Alignment out;
  out.method = AlignmentMethod::kPositions;
  count_rows(log, out);
  const PathIndex path(plan, options.max_distance_mm);
  const CutSpan cut = cut_span(plan);
  const PositionMatch m = match_positions(log, path, 1.0, options.max_distance_mm, cut);
  const std::string problem = not_this_program(log, path, m, options, 1.0);
  if (!problem.empty()) {
    reject(log, path, cut, options, check_units, problem, out);
    return out;
  }
  out.s_mm = m.s_mm;
  out.rows_off_path = m.off_path;
  finish_coverage(plan, log, out, positions_text(log, m));
  if (options.estimate_delay && usable(out.status)) estimate_delay(log, plan, options, out, out.message);
  return out;
}

}  // namespace feedplan::learning::detail
