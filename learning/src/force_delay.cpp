#include "force_delay.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "contact_signal.hpp"
#include "cross_correlation.hpp"
#include "fixed_text.hpp"
#include "log_rows.hpp"
#include "sampled_signal.hpp"

namespace feedplan::learning::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Delay search: bins no finer than this, s (the estimate is interpolated between bins).
constexpr double kMinDelayBinS = 0.5e-3;
// A weaker correlation of the measured and the planned contact does not place the forces (see below).
constexpr double kMinDelayCorrelation = 0.5;

// Per row: 1 where the plan has the tool engaged at the row's aligned place, 0 where it is not or the
// row has a position off the aligned path, NaN without a position.
std::vector<double> planned_engagement_at_rows(const force_log::ForceLog& log, const planner::PlanResult& plan,
                                               const std::vector<double>& s_mm) {
  std::vector<double> plan_s, plan_engaged;
  for (const auto& sample : plan.samples) {
    plan_s.push_back(sample.s_mm);
    plan_engaged.push_back(sample.engaged ? 1.0 : 0.0);
  }
  const std::size_t n = log.rows.size();
  std::vector<double> predicted(n, kNaN);
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isfinite(s_mm[i])) {
      predicted[i] = interpolate(plan_s, plan_engaged, s_mm[i], 0.0);
    } else if (finite_xy(log.rows[i])) {
      predicted[i] = 0.0;  // before or after the program, or off the path: not cutting the planned stock
    }
  }
  return predicted;
}

// Per bin: 1 where the plan has the tool out of the stock for `max_lag` bins either side (air whatever the
// delay searched), 0 elsewhere. `engaged` is the plan's engagement per bin (NaN: no position).
std::vector<double> surely_in_air(const std::vector<double>& engaged, long max_lag) {
  const std::size_t n = engaged.size();
  std::vector<std::size_t> engaged_before(n + 1, 0);  // bins engaged (> 0) among the first i
  for (std::size_t i = 0; i < n; ++i) engaged_before[i + 1] = engaged_before[i] + (engaged[i] > 0.0 ? 1 : 0);
  const auto reach = static_cast<std::size_t>(std::max(max_lag, 0L));
  std::vector<double> air(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t from = i >= reach ? i - reach : 0;
    const std::size_t to = std::min(n, i + reach + 1);
    if (std::isfinite(engaged[i]) && engaged_before[to] == engaged_before[from]) air[i] = 1.0;
  }
  return air;
}

}  // namespace

void estimate_delay(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options,
                    Alignment& out, std::string& text) {
  if (!log.has_forces) {
    text += "; force delay not estimated (the log has no forces)";
    return;
  }
  const std::size_t n = log.rows.size();
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = log.rows[i].t_s;
  const std::vector<double> predicted = planned_engagement_at_rows(log, plan, out.s_mm);
  const std::vector<double> measured_rows = force_xy(log);
  const double span_s = t.back() - t.front();
  double bin_s = std::max(median_step_s(log), kMinDelayBinS);
  bin_s = std::max(bin_s, span_s / 2e4);  // keeps the search small on long logs
  const std::size_t bins = static_cast<std::size_t>(span_s / bin_s) + 1;
  const int width = revolution_bins(spindle_rpm_for(log, plan), bin_s);
  const std::vector<double> expected = moving_max(bin_means(t, predicted, t.front(), bin_s, bins), width);
  const long max_lag = static_cast<long>(std::ceil(options.max_delay_s / bin_s));
  const std::vector<double> envelope = moving_max(bin_means(t, measured_rows, t.front(), bin_s, bins), width);
  const double noise_n = noise_envelope_n(envelope, width, surely_in_air(expected, max_lag));
  const std::vector<double> measured = contact_of_envelope(envelope, noise_n);
  const CorrelationPeak peak = correlate(measured, expected, -max_lag, max_lag, 0.0);
  if (!peak.found && noise_n > 0.0) {
    text += "; force delay not estimated (the log reads forces up to " + fixed(noise_n, 0) +
            " N where the plan has the tool in the air, as large as any in the cut: check that the log belongs to "
            "this plan)";
    return;
  }
  if (!peak.found) {
    text += "; force delay not estimated (no contact, or contact throughout, in the measured or planned force)";
    return;
  }
  const double delay_s = std::clamp(peak.lag_bins * bin_s, -options.max_delay_s, options.max_delay_s);
  text += "; force delay " + fixed(1e3 * delay_s, 1) + " ms (correlation " + fixed(peak.correlation, 2) + ")";
  if (peak.at_edge) {
    text += " at the edge of the searched range +-" + fixed(1e3 * options.max_delay_s, 0) +
            " ms: the true delay may be larger";
  }
  if (peak.correlation < kMinDelayCorrelation) {
    // A lag the contact signals hardly agree on is no measurement: applying it would move every entry's
    // force along the path (on a long log from a 9 N dynamometer whose noise passed for contact in places,
    // −170 ms at 0.08, 2.6 mm at the corner's entry feed: learning read air there and sped the entry up by half).
    text += ", weak: not applied (forces placed where the positions say); check that the log belongs to this plan";
    return;
  }
  out.delay_s = delay_s;
  out.delay_correlation = peak.correlation;
}

}  // namespace feedplan::learning::detail
