#include "feedplan/geometry/machine_limits.hpp"

#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::geometry {
namespace {

bool finite_positive(double value) { return std::isfinite(value) && value > 0.0; }

void require_positive(ProblemList& problems, const char* field, double value, const char* unit) {
  if (!finite_positive(value)) {
    problems.add_value(field, six_digit_number_text(value), std::string("must be finite and > 0 ") + unit);
  }
}

}  // namespace

std::vector<InputProblem> validate(const MachineLimits& limits) {
  ProblemList problems("machine.");
  require_positive(problems, "max_accel_mm_per_s2", limits.max_accel_mm_per_s2, "mm/s²");
  require_positive(problems, "rapid_feed_mm_per_min", limits.rapid_feed_mm_per_min, "mm/min");
  require_positive(problems, "max_feed_mm_per_min", limits.max_feed_mm_per_min, "mm/min");
  require_positive(problems, "min_feed_mm_per_min", limits.min_feed_mm_per_min, "mm/min");
  if (finite_positive(limits.min_feed_mm_per_min) && finite_positive(limits.max_feed_mm_per_min) &&
      !(limits.min_feed_mm_per_min < limits.max_feed_mm_per_min)) {
    problems.add_value("min_feed_mm_per_min", six_digit_number_text(limits.min_feed_mm_per_min),
                       "must be < max_feed_mm_per_min = " + six_digit_number_text(limits.max_feed_mm_per_min));
  }
  if (!(std::isfinite(limits.block_time_min_s) && limits.block_time_min_s >= 0.0 && limits.block_time_min_s <= 1.0)) {
    problems.add_value("block_time_min_s", six_digit_number_text(limits.block_time_min_s),
                       "must be in [0, 1] s — the shortest block execution time of the control");
  }
  if (!(std::isfinite(limits.junction_deviation_mm) && limits.junction_deviation_mm >= 0.0)) {
    problems.add_value("junction_deviation_mm", six_digit_number_text(limits.junction_deviation_mm),
                       "must be finite and ≥ 0 mm");
  }
  return problems.take();
}

}  // namespace feedplan::geometry
