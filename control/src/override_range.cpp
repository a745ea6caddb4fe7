#include "feedplan/control/override_range.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {

std::vector<InputProblem> validate(const OverrideRange& range, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("max_ratio", range.max_ratio);
  problems.non_negative("step_ratio", range.step_ratio);
  problems.non_negative("min_ratio", range.min_ratio);
  if (std::isfinite(range.max_ratio) && std::isfinite(range.min_ratio) && range.min_ratio > range.max_ratio) {
    problems.add_value("min_ratio", shortest_number_text(range.min_ratio),
                       "must be ≤ max_ratio = " + shortest_number_text(range.max_ratio));
  }
  if (std::isfinite(range.max_ratio) && std::isfinite(range.step_ratio) && range.step_ratio > range.max_ratio) {
    problems.add_value("step_ratio", shortest_number_text(range.step_ratio),
                       "must be ≤ max_ratio = " + shortest_number_text(range.max_ratio));
  }
  return problems.take();
}

std::vector<InputProblem> validate_override_start(const OverrideRange& range, double programmed_feed_mm_per_min,
                                                  double initial_feed_mm_per_min, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  const std::vector<InputProblem> range_problems = validate(range, field_prefix + "override_range.");
  problems.add_all(range_problems);
  const double top = range.max_ratio * programmed_feed_mm_per_min;
  const double initial = initial_feed_mm_per_min;
  if (!std::isfinite(initial) || initial < 0.0) {
    problems.add_value("initial_feed_mm_per_min", shortest_number_text(initial), "must be finite and ≥ 0");
  } else if (range_problems.empty() && std::isfinite(top) && initial > top) {
    problems.add_value("initial_feed_mm_per_min", shortest_number_text(initial),
                       "must be ≤ override_range.max_ratio × programmed_feed_mm_per_min = " + shortest_number_text(top));
  }
  return problems.take();
}

double applied_override(const OverrideRange& range, double ratio) {
  assert(!std::isnan(ratio));
  const double clamped = std::clamp(ratio, range.min_ratio, range.max_ratio);
  if (range.step_ratio <= 0.0) return clamped;
  const double top_step = std::floor(range.max_ratio / range.step_ratio + 1e-9);
  const double bottom_step = std::min(std::ceil(range.min_ratio / range.step_ratio - 1e-9), top_step);
  const double steps = std::clamp(std::round(clamped / range.step_ratio), bottom_step, top_step);
  return steps * range.step_ratio;
}

}  // namespace feedplan::control
