#include "alignment_by_time_profile.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "contact_signal.hpp"
#include "coverage.hpp"
#include "cross_correlation.hpp"
#include "fixed_text.hpp"
#include "log_rows.hpp"
#include "sampled_signal.hpp"

namespace feedplan::learning::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Time-profile search: at most this many bins over log + plan (keeps the full search quadratic but small).
constexpr double kMaxTimeProfileBins = 8000.0;
constexpr double kMinTimeProfileBinS = 2e-3;

}  // namespace

Alignment align_by_time_profile(const force_log::ForceLog& log, const planner::PlanResult& plan) {
  Alignment out;
  out.method = AlignmentMethod::kTimeProfile;
  count_rows(log, out);
  out.s_mm.assign(log.rows.size(), kNaN);
  const std::string method = "aligned by the plan's predicted time profile (the log has no positions)";
  std::vector<double> plan_t, plan_s, plan_engaged;
  for (const auto& sample : plan.samples) {
    plan_t.push_back(sample.time_s);
    plan_s.push_back(sample.s_mm);
    plan_engaged.push_back(sample.engaged ? 1.0 : 0.0);
  }
  const std::size_t n = log.rows.size();
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = log.rows[i].t_s;
  const double log_span_s = t.back() - t.front();
  const double plan_span_s = plan_t.back() - plan_t.front();
  const double bin_s = std::max(kMinTimeProfileBinS, (log_span_s + plan_span_s) / kMaxTimeProfileBins);
  const std::size_t log_bins = static_cast<std::size_t>(log_span_s / bin_s) + 1;
  const std::size_t plan_bins = static_cast<std::size_t>(plan_span_s / bin_s) + 1;
  const int width = revolution_bins(spindle_rpm_for(log, plan), bin_s);
  const std::vector<double> measured = in_contact(bin_means(t, force_xy(log), t.front(), bin_s, log_bins), width);
  std::vector<double> expected(plan_bins);
  for (std::size_t j = 0; j < plan_bins; ++j) {
    expected[j] = interpolate(plan_t, plan_engaged, plan_t.front() + (static_cast<double>(j) + 0.5) * bin_s, 0.0);
  }
  expected = moving_max(expected, width);
  // measured[i] (log time t0 + i h) pairs with expected[i − lag] (plan time (i − lag) h): the program
  // started at log time t0 + lag h. Outside the plan the machine does not cut: 0.
  const CorrelationPeak peak =
      correlate(measured, expected, -static_cast<long>(plan_bins), static_cast<long>(log_bins), 0.0);
  if (!peak.found) {
    out.status = AlignmentStatus::kNoCut;
    out.message = method +
                  "; the measured force never changes between air and contact (no cut, or in the cut throughout): "
                  "nothing to align the plan's time profile by";
    return out;
  }
  const double start_s = t.front() + peak.lag_bins * bin_s - plan_t.front();
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = t[i] - start_s;
    if (tau >= plan_t.front() && tau <= plan_t.back()) out.s_mm[i] = interpolate(plan_t, plan_s, tau, kNaN);
  }
  std::string text = method + ": the program starts at t = " + fixed(start_s, 3) +
                     " s on the log's clock (correlation " + fixed(peak.correlation, 2) +
                     "); s follows the predicted speeds, good to a few mm";
  if (peak.correlation < 0.5) text += "; weak correlation: check that the log belongs to this plan";
  finish_coverage(plan, log, out, text);
  return out;
}

}  // namespace feedplan::learning::detail
