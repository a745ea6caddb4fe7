#include "feedplan/planner/peak_comparison.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>

namespace feedplan::planner {

namespace {

// Count, largest |error| with where, and RMS of a set of revolutions' errors.
struct ErrorStatistics {
  int count = 0;
  double max_abs = 0.0;
  double sum_squares = 0.0;
  int worst = -1;
  void add(double error_percent, int index) {
    ++count;
    sum_squares += error_percent * error_percent;
    if (worst < 0 || std::abs(error_percent) > max_abs) {
      max_abs = std::abs(error_percent);
      worst = index;
    }
  }
  double rms() const { return count > 0 ? std::sqrt(sum_squares / count) : 0.0; }
};

// The first line: the largest peak anywhere, against the target, and where.
std::string largest_peak_line(const PeakComparison& c, double target_force_n) {
  if (c.largest_peak < 0) return "largest per-revolution peak: none (no revolution simulated)\n";
  const RevolutionComparison& r = c.revolutions[static_cast<std::size_t>(c.largest_peak)];
  char line[320];
  std::snprintf(line, sizeof line, "largest per-revolution peak: %s (%+.1f %% vs the target %.0f N%s)\n",
                where_text(r).c_str(), r.error_percent, target_force_n,
                r.in_cut ? "" : "; outside the plan's cut: the plan has no engagement there");
  return line;
}

}  // namespace

std::string where_text(const RevolutionComparison& r) {
  char text[200];
  std::snprintf(text, sizeof text, "%.1f N at s = %.1f mm, x %.2f y %.2f z %.2f", r.revolution.peak_n,
                0.5 * (r.revolution.s_start_mm + r.revolution.s_end_mm), r.position.x_mm, r.position.y_mm,
                r.position.z_mm);
  return text;
}

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
  ErrorStatistics held_errors;
  ErrorStatistics steady_errors;
  for (const MeasuredRevolution& revolution : revolutions) {
    RevolutionComparison c;
    c.revolution = revolution;
    c.error_percent = 100.0 * (revolution.peak_n - target_force_n) / target_force_n;
    bool all_force_limited = true;
    double closest_to_limit = 0.0;  // the largest speed / force limit over the span's engaged samples
    double farthest_from_limit = INFINITY;  // … and the smallest
    double engagement_min = 1e300;
    double engagement_max = -1e300;
    for (std::size_t i = first_at_or_after(revolution.s_start_mm); i < samples.size() && samples[i].s_mm <= revolution.s_end_mm; ++i) {
      if (!samples[i].engaged) continue;
      c.in_cut = true;
      all_force_limited = all_force_limited && samples[i].limit_reason == FeedLimitReason::kForce &&
                          samples[i].within_model_range;
      c.planned_force_n = std::max(c.planned_force_n, samples[i].predicted_force_n);
      if (samples[i].feed_limit_mm_per_min > 0.0) {
        const double share_of_limit = samples[i].feed_mm_per_min / samples[i].feed_limit_mm_per_min;
        closest_to_limit = std::max(closest_to_limit, share_of_limit);
        farthest_from_limit = std::min(farthest_from_limit, share_of_limit);
      }
      engagement_min = std::min(engagement_min, samples[i].engagement_rad);
      engagement_max = std::max(engagement_max, samples[i].engagement_rad);
    }
    c.force_limited = c.in_cut && all_force_limited && closest_to_limit >= 1.0 - kHeldFeedShortfall;
    c.held = c.force_limited && farthest_from_limit >= 1.0 - kHeldFeedShortfall;
    c.steady = c.held && engagement_max - engagement_min <= kSteadyEngagementSpreadRad;
    const std::size_t middle = std::min(first_at_or_after(0.5 * (revolution.s_start_mm + revolution.s_end_mm)),
                                        samples.empty() ? 0 : samples.size() - 1);
    if (!samples.empty()) c.position = samples[middle].position;
    const int index = static_cast<int>(out.revolutions.size());
    if (out.largest_peak < 0 || revolution.peak_n > out.revolutions[static_cast<std::size_t>(out.largest_peak)].revolution.peak_n) {
      out.largest_peak = index;
    }
    if (c.in_cut) {
      ++out.in_cut;
      if (out.worst_overshoot < 0 || c.error_percent > out.max_overshoot_percent) {
        out.max_overshoot_percent = c.error_percent;
        out.worst_overshoot = index;
      }
    }
    if (c.held) held_errors.add(c.error_percent, index);
    if (c.steady) steady_errors.add(c.error_percent, index);
    out.revolutions.push_back(c);
  }
  out.held = held_errors.count;
  out.max_abs_error_percent = held_errors.max_abs;
  out.rms_error_percent = held_errors.rms();
  out.worst_held = held_errors.worst;
  out.steady = steady_errors.count;
  out.steady_max_abs_error_percent = steady_errors.max_abs;
  out.steady_rms_error_percent = steady_errors.rms();
  out.worst_steady = steady_errors.worst;
  return out;
}


std::string describe(const PeakComparison& c, double target_force_n) {
  char line[512];
  std::string text = largest_peak_line(c, target_force_n);
  std::snprintf(line, sizeof line,
                "revolutions: %zu, in cut %d, held at the target (force-limited, inside the model's range, run at the limit throughout) %d, "
                "of them steady (constant engagement) %d\n",
                c.revolutions.size(), c.in_cut, c.held, c.steady);
  text += line;
  const auto error_line = [&](const char* what, int worst, double max_abs, double rms) {
    if (worst < 0) return;
    std::snprintf(line, sizeof line, "%s: max |error| %.2f %%, RMS %.2f %% (worst %s)\n", what, max_abs, rms,
                  where_text(c.revolutions[static_cast<std::size_t>(worst)]).c_str());
    text += line;
  };
  error_line("steady revolutions", c.worst_steady, c.steady_max_abs_error_percent, c.steady_rms_error_percent);
  error_line("all held revolutions", c.worst_held, c.max_abs_error_percent, c.rms_error_percent);
  if (c.worst_overshoot >= 0) {
    std::snprintf(line, sizeof line, "largest peak vs target over all in-cut revolutions: %+.2f %% (%s)\n",
                  c.max_overshoot_percent, where_text(c.revolutions[static_cast<std::size_t>(c.worst_overshoot)]).c_str());
    text += line;
  }
  return text;
}

}  // namespace feedplan::planner
