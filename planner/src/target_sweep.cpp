#include "feedplan/planner/target_sweep.hpp"

#include <cmath>
#include <sstream>

#include "feedplan/core/number_text.hpp"
#include "feedplan/planner/target_advice.hpp"

namespace feedplan::planner {
namespace {

//! The number in `part`, or NaN when it is not one whole number text.
double number_of(const std::string& part) {
  std::istringstream in(part);
  double value = NAN;
  in >> value;
  return in && in.eof() ? value : NAN;
}

}  // namespace

TargetRange parse_target_range(const std::string& text, const std::string& field) {
  const auto fail = [&](const std::string& why) {
    throw InputError(field, "= '" + text + "': " + why + " (e.g. 250:500:25: targets 250, 275, … 500 N)");
  };
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, ':')) parts.push_back(part);
  if (!text.empty() && text.back() == ':') parts.push_back("");
  if (parts.size() != 3) fail("must be FROM:TO:STEP, three numbers in newtons separated by ':'");
  const TargetRange range{number_of(parts[0]), number_of(parts[1]), number_of(parts[2])};
  if (!std::isfinite(range.from_n) || !std::isfinite(range.to_n) || !std::isfinite(range.step_n)) {
    fail("FROM, TO and STEP must each be a finite number of newtons");
  }
  if (!(range.from_n > 0.0)) fail("FROM must be > 0 N");
  if (!(range.to_n >= range.from_n)) fail("TO must be ≥ FROM");
  if (!(range.step_n > 0.0)) fail("STEP must be > 0 N");
  const double count = std::floor((range.to_n - range.from_n) / range.step_n + 1e-6) + 1;
  if (count > kMaxSweepTargets) {
    fail("gives " + shortest_number_text(count) + " targets: at most " + std::to_string(kMaxSweepTargets) +
         " (take a larger STEP)");
  }
  return range;
}

std::vector<double> targets_of(const TargetRange& range) {
  std::vector<double> targets;
  const auto count = static_cast<long>(std::floor((range.to_n - range.from_n) / range.step_n + 1e-6)) + 1;
  for (long i = 0; i < count; ++i) targets.push_back(range.from_n + static_cast<double>(i) * range.step_n);
  return targets;
}

std::vector<TargetSweepRow> sweep_targets(const PlanGeometry& geometry, const PlanSettings& settings,
                                          const TargetRange& range) {
  std::vector<TargetSweepRow> rows;
  for (const double target_n : targets_of(range)) {
    PlanSettings at = settings;
    at.target_force_n = target_n;
    const PlanResult result = plan(geometry, at);
    TargetSweepRow row;
    row.target_n = target_n;
    row.status = result.status;
    row.cycle_time_s = result.summary.cycle_time_s;
    row.max_predicted_force_n = result.summary.max_predicted_force_n;
    if (result.status == PlanStatus::kTargetNotMet) {
      const TargetAdvice advice = target_advice(geometry, at, result);
      row.unreachable_samples = advice.unreachable_samples;
      row.target_needed_n = advice.target_needed_n;
    }
    rows.push_back(row);
  }
  return rows;
}

}  // namespace feedplan::planner
