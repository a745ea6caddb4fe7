#include "feedplan/learning/log_alignment.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "alignment_by_positions.hpp"
#include "alignment_by_time_profile.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "log_rows.hpp"

namespace feedplan::learning {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Throws InputError when the options are out of range, or the log has no rows, nothing to align by, or
// times that do not increase.
void check_input(const force_log::ForceLog& log, const AlignmentOptions& options) {
  std::vector<InputProblem> problems;
  if (!(std::isfinite(options.max_distance_mm) && options.max_distance_mm > 0.0)) {
    problems.push_back(
        {"alignment.max_distance_mm", "= " + shortest_number_text(options.max_distance_mm) + ": must be > 0"});
  }
  if (!(options.max_off_path_fraction >= 0.0 && options.max_off_path_fraction <= 1.0)) {
    problems.push_back({"alignment.max_off_path_fraction",
                        "= " + shortest_number_text(options.max_off_path_fraction) + ": must be in [0, 1]"});
  }
  if (!(std::isfinite(options.max_delay_s) && options.max_delay_s >= 0.0)) {
    problems.push_back({"alignment.max_delay_s", "= " + shortest_number_text(options.max_delay_s) + ": must be >= 0"});
  }
  if (!log.has_positions && !log.has_forces) {
    problems.push_back({"log",
                        "has neither positions nor forces: nothing to align by (turn currents into forces "
                        "first, forces_from_currents)"});
  }
  if (log.rows.empty()) problems.push_back({"log", "has no rows"});
  for (std::size_t i = 1; i < log.rows.size(); ++i) {
    if (!(log.rows[i].t_s > log.rows[i - 1].t_s)) {
      problems.push_back({"log row " + std::to_string(i + 1) + " t_s",
                          "= " + shortest_number_text(log.rows[i].t_s) + ": must be greater than the previous row's " +
                              shortest_number_text(log.rows[i - 1].t_s)});
      break;
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

// A plan without samples: nothing to align with.
Alignment no_plan_samples(const force_log::ForceLog& log) {
  Alignment out;
  detail::count_rows(log, out);
  out.method = log.has_positions ? AlignmentMethod::kPositions : AlignmentMethod::kTimeProfile;
  out.status = AlignmentStatus::kNoCut;
  out.s_mm.assign(log.rows.size(), kNaN);
  out.message = "the plan has no samples: nothing to align with";
  return out;
}

}  // namespace

std::string to_string(AlignmentMethod method) {
  switch (method) {
    case AlignmentMethod::kPositions:
      return "positions";
    case AlignmentMethod::kTimeProfile:
      return "time profile";
  }
  return "?";
}

std::string to_string(AlignmentStatus status) {
  switch (status) {
    case AlignmentStatus::kOk:
      return "ok";
    case AlignmentStatus::kNotThisProgram:
      return "not this program";
    case AlignmentStatus::kNoCut:
      return "no cut";
    case AlignmentStatus::kTruncated:
      return "truncated";
    case AlignmentStatus::kUnitsLookWrong:
      return "units look wrong";
  }
  return "?";
}

bool usable(AlignmentStatus status) { return status == AlignmentStatus::kOk || status == AlignmentStatus::kTruncated; }

Alignment align_log(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options) {
  check_input(log, options);
  if (plan.samples.empty()) return no_plan_samples(log);
  return log.has_positions ? detail::align_by_positions(log, plan, options, true)
                           : detail::align_by_time_profile(log, plan);
}

}  // namespace feedplan::learning
