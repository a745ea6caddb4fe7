#include "feedplan/planner/peak_comparison.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>

namespace feedplan::planner {

PeakComparison compare_peaks(const PlanResult& result, double target_force_n,
                             const std::vector<MeasuredRevolution>& revolutions) {
  assert(target_force_n > 0.0);
  PeakComparison out;
  const auto& samples = result.samples;
  auto first_at_or_after = [&](double s_mm) {
    return static_cast<std::size_t>(std::lower_bound(samples.begin(), samples.end(), s_mm,
                                                     [](const PlannedSample& p, double s) { return p.s_mm < s; }) -
                                    samples.begin());
  };
  double sum_squares = 0.0;
  double steady_sum_squares = 0.0;
  for (const MeasuredRevolution& revolution : revolutions) {
    RevolutionComparison c;
    c.revolution = revolution;
    c.error_percent = 100.0 * (revolution.peak_n - target_force_n) / target_force_n;
    bool all_force_limited = true;
    double engagement_min = 1e300;
    double engagement_max = -1e300;
    for (std::size_t i = first_at_or_after(revolution.s_start_mm); i < samples.size() && samples[i].s_mm <= revolution.s_end_mm; ++i) {
      if (!samples[i].engaged) continue;
      c.in_cut = true;
      all_force_limited = all_force_limited && samples[i].limit_reason == FeedLimitReason::kForce &&
                          samples[i].within_model_range;
      c.planned_force_n = std::max(c.planned_force_n, samples[i].predicted_force_n);
      engagement_min = std::min(engagement_min, samples[i].engagement_rad);
      engagement_max = std::max(engagement_max, samples[i].engagement_rad);
    }
    c.held = c.in_cut && all_force_limited;
    c.steady = c.held && engagement_max - engagement_min <= kSteadyEngagementSpreadRad;
    const std::size_t middle = std::min(first_at_or_after(0.5 * (revolution.s_start_mm + revolution.s_end_mm)),
                                        samples.empty() ? 0 : samples.size() - 1);
    if (!samples.empty()) c.position = samples[middle].position;
    const int index = static_cast<int>(out.revolutions.size());
    if (c.in_cut) {
      ++out.in_cut;
      if (out.worst_overshoot < 0 || c.error_percent > out.max_overshoot_percent) {
        out.max_overshoot_percent = c.error_percent;
        out.worst_overshoot = index;
      }
    }
    if (c.held) {
      ++out.held;
      sum_squares += c.error_percent * c.error_percent;
      if (std::abs(c.error_percent) > out.max_abs_error_percent || out.worst_held < 0) {
        out.max_abs_error_percent = std::abs(c.error_percent);
        out.worst_held = index;
      }
    }
    if (c.steady) {
      ++out.steady;
      steady_sum_squares += c.error_percent * c.error_percent;
      if (std::abs(c.error_percent) > out.steady_max_abs_error_percent || out.worst_steady < 0) {
        out.steady_max_abs_error_percent = std::abs(c.error_percent);
        out.worst_steady = index;
      }
    }
    out.revolutions.push_back(c);
  }
  if (out.held > 0) out.rms_error_percent = std::sqrt(sum_squares / out.held);
  if (out.steady > 0) out.steady_rms_error_percent = std::sqrt(steady_sum_squares / out.steady);
  return out;
}

std::string describe(const PeakComparison& c) {
  char line[512];
  std::string text;
  std::snprintf(line, sizeof line,
                "revolutions: %zu, in cut %d, held at the target (force-limited, inside the model's range) %d, "
                "of them steady (constant engagement) %d\n",
                c.revolutions.size(), c.in_cut, c.held, c.steady);
  text += line;
  if (c.worst_steady >= 0) {
    const auto& w = c.revolutions[static_cast<std::size_t>(c.worst_steady)];
    std::snprintf(line, sizeof line,
                  "steady revolutions: max |error| %.2f %%, RMS %.2f %% (worst %.1f N at s = %.1f mm, x %.2f y %.2f)\n",
                  c.steady_max_abs_error_percent, c.steady_rms_error_percent, w.revolution.peak_n,
                  0.5 * (w.revolution.s_start_mm + w.revolution.s_end_mm), w.position.x_mm, w.position.y_mm);
    text += line;
  }
  if (c.worst_held >= 0) {
    const auto& w = c.revolutions[static_cast<std::size_t>(c.worst_held)];
    std::snprintf(line, sizeof line,
                  "all held revolutions: max |error| %.2f %%, RMS %.2f %% (worst %.1f N at s = %.1f mm, x %.2f y %.2f)\n",
                  c.max_abs_error_percent, c.rms_error_percent, w.revolution.peak_n,
                  0.5 * (w.revolution.s_start_mm + w.revolution.s_end_mm), w.position.x_mm, w.position.y_mm);
    text += line;
  }
  if (c.worst_overshoot >= 0) {
    const auto& w = c.revolutions[static_cast<std::size_t>(c.worst_overshoot)];
    std::snprintf(line, sizeof line, "largest peak vs target over all in-cut revolutions: %+.2f %% (%.1f N at s = %.1f mm, x %.2f y %.2f)\n",
                  c.max_overshoot_percent, w.revolution.peak_n, 0.5 * (w.revolution.s_start_mm + w.revolution.s_end_mm),
                  w.position.x_mm, w.position.y_mm);
    text += line;
  }
  return text;
}

}  // namespace feedplan::planner
