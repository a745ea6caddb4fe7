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
  if (std::isfinite(range.max_ratio) && std::isfinite(range.step_ratio) && range.step_ratio > range.max_ratio) {
    problems.add_value("step_ratio", shortest_number_text(range.step_ratio),
                       "must be ≤ max_ratio = " + shortest_number_text(range.max_ratio));
  }
  return problems.take();
}

double applied_override(const OverrideRange& range, double ratio) {
  assert(!std::isnan(ratio));
  const double clamped = std::clamp(ratio, 0.0, range.max_ratio);
  if (range.step_ratio <= 0.0) return clamped;
  const double top_step = std::floor(range.max_ratio / range.step_ratio + 1e-9);
  const double steps = std::min(std::round(clamped / range.step_ratio), top_step);
  return steps * range.step_ratio;
}

}  // namespace feedplan::control
