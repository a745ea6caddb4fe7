#include "feedplan/learning/measured_revolutions.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/planner/feed_limit.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::learning {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A window holding fewer than this share of the rows one revolution should hold has a gap.
constexpr double kMinRowShare = 0.5;
// A turn's largest tooth-period peak changing by less than this share from the turn before is steady
// (runout factor, step 5).
constexpr double kSteadyTurnChange = 0.02;
// Steady turns whose runout pattern a tooth period's factor is the median of.
constexpr std::size_t kRunoutTurns = 5;

// Row times with a per-row quantity, read at any time inside the log by linear interpolation between the
// two rows around it; NaN when either is NaN or the time is outside the rows.
class RowSeries {
 public:
  explicit RowSeries(const std::vector<double>& t_s) : t_s_(t_s) {}

  // First row at or after t.
  std::size_t first_at_or_after(double t) const {
    return static_cast<std::size_t>(std::lower_bound(t_s_.begin(), t_s_.end(), t) - t_s_.begin());
  }

  double at(const std::vector<double>& value, double t) const {
    if (t_s_.empty() || !(t >= t_s_.front()) || !(t <= t_s_.back())) return kNaN;
    const std::size_t j = first_at_or_after(t);
    if (t_s_[j] == t) return value[j];
    const double w = (t - t_s_[j - 1]) / (t_s_[j] - t_s_[j - 1]);
    return value[j - 1] + w * (value[j] - value[j - 1]);  // NaN when either is NaN
  }

  // True when every row in [t0, t1] and the rows just around the ends have a finite value.
  bool all_finite(const std::vector<double>& value, double t0, double t1) const {
    if (t_s_.empty() || !(t0 >= t_s_.front()) || !(t1 <= t_s_.back())) return false;
    std::size_t j = first_at_or_after(t0);
    if (j > 0 && t_s_[j] > t0) --j;
    for (; j < t_s_.size(); ++j) {
      if (!std::isfinite(value[j])) return false;
      if (t_s_[j] >= t1) break;
    }
    return true;
  }

 private:
  const std::vector<double>& t_s_;
};

// Windows of one tooth period (at `tooth_rate_per_min` = Z × rpm) over the rows from the first one that
// puts the force peaks in the middle of their windows. Counted from the first row, a window boundary
// can fall on a tooth's peak; then which flute's peak a window holds changes from revolution to
// revolution (with runout, by the runout's share of the force). The peaks' phase in the tooth period is
// their force-weighted circular mean over the windows holding more than a tenth of the largest peak.
std::vector<force_log::RevolutionPeak> tooth_periods_centred_on_peaks(const std::vector<double>& t, const std::vector<double>& fx,
                                                                const std::vector<double>& fy, double tooth_rate_per_min) {
  const std::vector<force_log::RevolutionPeak> from_first = force_log::revolution_peaks(t, fx, fy, tooth_rate_per_min);
  double largest = 0.0;
  for (const auto& p : from_first) largest = std::max(largest, p.peak_xy_n);
  const double period_s = 60.0 / tooth_rate_per_min;
  double sum_cos = 0.0, sum_sin = 0.0;
  for (const auto& p : from_first) {
    if (!(p.peak_xy_n > 0.1 * largest)) continue;
    const double phase_rad = kTwoPi * (p.t_peak_s - t.front()) / period_s;
    sum_cos += p.peak_xy_n * std::cos(phase_rad);
    sum_sin += p.peak_xy_n * std::sin(phase_rad);
  }
  if (sum_cos == 0.0 && sum_sin == 0.0) return from_first;
  // Start where the phase is half a period before the peaks'.
  double start_turns = std::atan2(sum_sin, sum_cos) / kTwoPi - 0.5;
  start_turns -= std::floor(start_turns);
  const std::size_t first = static_cast<std::size_t>(
      std::lower_bound(t.begin(), t.end(), t.front() + start_turns * period_s) - t.begin());
  if (first == 0 || first + 2 > t.size()) return from_first;
  const auto tail = [first](const std::vector<double>& v) { return std::vector<double>(v.begin() + static_cast<long>(first), v.end()); };
  return force_log::revolution_peaks(tail(t), tail(fx), tail(fy), tooth_rate_per_min);
}

// What became of one window.
enum class WindowOutcome { kNan, kNotAligned, kNotEngaged, kEngaged };

struct WindowPlace {
  WindowOutcome outcome = WindowOutcome::kNan;
  double s_start_mm = 0.0, s_end_mm = 0.0, s_peak_mm = 0.0;
  LearningSample sample;  // kEngaged only
};

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

}  // namespace

MeasuredRevolutions measured_revolutions(const force_log::ForceLog& log, const Alignment& alignment,
                                         const planner::PlanResult& plan, const model::ResponseSurfaceModel& model,
                                         int flutes, double spindle_rpm, const MeasuredRevolutionOptions& options) {
  std::vector<InputProblem> problems;
  if (flutes < 1) problems.push_back({"flutes", "= " + std::to_string(flutes) + ": must be >= 1"});
  if (!(std::isfinite(spindle_rpm) && spindle_rpm > 0.0)) {
    problems.push_back({"spindle_rpm", "= " + shortest_number_text(spindle_rpm) + ": must be > 0"});
  }
  if (!(options.min_engagement_rad >= 0.0 && std::isfinite(options.min_engagement_rad))) {
    problems.push_back(
        {"min_engagement_rad", "= " + shortest_number_text(options.min_engagement_rad) + ": must be >= 0"});
  }
  if (!log.has_forces) {
    problems.push_back(
        {"log", "has no forces (only servo currents?): turn them into forces first (forces_from_currents)"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  assert(alignment.s_mm.size() == log.rows.size());

  MeasuredRevolutions out;
  if (!usable(alignment.status)) {
    out.message =
        "no revolutions: the alignment is not usable (" + to_string(alignment.status) + ": " + alignment.message + ")";
    return out;
  }
  const std::size_t n = log.rows.size();
  if (n < 2 || plan.samples.empty()) {
    out.message = "no revolutions: too few rows or an empty plan";
    return out;
  }

  // 1. Windows. NaN forces read as 0 for force_log::revolution_peaks; windows holding one are skipped below.
  std::vector<double> t(n), fx(n), fy(n), feed(n), nan_rows(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& row = log.rows[i];
    t[i] = row.t_s;
    const bool finite = std::isfinite(row.fx_n) && std::isfinite(row.fy_n);
    fx[i] = finite ? row.fx_n : 0.0;
    fy[i] = finite ? row.fy_n : 0.0;
    nan_rows[i] = finite ? 0.0 : kNaN;
    feed[i] = row.feed_mm_per_min;
  }
  const std::vector<force_log::RevolutionPeak> peaks = force_log::revolution_peaks(t, fx, fy, spindle_rpm);
  const double period_s = 60.0 / spindle_rpm;
  const double mean_step_s = (t.back() - t.front()) / static_cast<double>(n - 1);
  const RowSeries rows(t);

  const auto& samples = plan.samples;
  auto nearest_sample = [&](double s_mm) {
    const auto it = std::lower_bound(samples.begin(), samples.end(), s_mm,
                                     [](const planner::PlannedSample& p, double s) { return p.s_mm < s; });
    std::size_t j = static_cast<std::size_t>(it - samples.begin());
    if (j == samples.size()) return samples.size() - 1;
    if (j > 0 && s_mm - samples[j - 1].s_mm < samples[j].s_mm - s_mm) --j;
    return j;
  };
  // XY speed / path speed around s (the plan's samples carry the chip factor without it).
  auto xy_speed_ratio = [&](double s_mm) {
    if (samples.size() < 2) return 1.0;
    const auto it = std::upper_bound(samples.begin(), samples.end(), s_mm,
                                     [](double s, const planner::PlannedSample& p) { return s < p.s_mm; });
    std::size_t k = static_cast<std::size_t>(std::max<long>(0, (it - samples.begin()) - 1));
    k = std::min(k, samples.size() - 2);
    const auto& a = samples[k];
    const auto& b = samples[k + 1];
    const double ds = b.s_mm - a.s_mm;
    if (ds <= 1e-12) return 1.0;
    return std::min(1.0, std::hypot(b.position.x_mm - a.position.x_mm, b.position.y_mm - a.position.y_mm) / ds);
  };

  // One window (a revolution or a tooth period) → its place and, engaged, its sample.
  const double delay_s = alignment.delay_s;
  auto evaluate = [&](const force_log::RevolutionPeak& peak, double window_s) {
    WindowPlace w;
    const std::size_t first = rows.first_at_or_after(peak.t_start_s);
    const std::size_t end = rows.first_at_or_after(peak.t_end_s);
    bool has_nan = static_cast<double>(end - first) < kMinRowShare * window_s / mean_step_s;
    for (std::size_t i = first; i < end && !has_nan; ++i) has_nan = std::isnan(nan_rows[i]);
    if (has_nan) {
      w.outcome = WindowOutcome::kNan;
      return w;
    }
    // 2. Place, with the force's lag behind the positions.
    const double t0 = peak.t_start_s - delay_s, t1 = peak.t_end_s - delay_s, tp = peak.t_peak_s - delay_s;
    if (!rows.all_finite(alignment.s_mm, t0, std::min(t1, t.back()))) {
      w.outcome = WindowOutcome::kNotAligned;
      return w;
    }
    const double s0 = rows.at(alignment.s_mm, t0);
    // The last window may end a fraction of a row past the last row (force_log::revolution_peaks' rule).
    const double s1 = rows.at(alignment.s_mm, std::min(t1, t.back()));
    const double s_peak = rows.at(alignment.s_mm, tp);
    if (!std::isfinite(s0) || !std::isfinite(s1) || !std::isfinite(s_peak)) {
      w.outcome = WindowOutcome::kNotAligned;
      return w;
    }
    w.s_start_mm = std::min(s0, s1);
    w.s_end_mm = std::max(s0, s1);
    w.s_peak_mm = s_peak;

    // 3. Model inputs at the peak's place, at the feed run there.
    const planner::PlannedSample& planned = samples[nearest_sample(s_peak)];
    geometry::EngagementSample place;
    place.s_mm = s_peak;
    place.position = planned.position;
    place.cutting = planned.engaged;
    place.engagement_rad = planned.engagement_rad;
    place.chip_factor = planned.chip_factor;
    place.xy_speed_ratio = xy_speed_ratio(s_peak);
    place.contact_length_mm = planned.contact_length_mm;
    place.axial_depth_mm = planned.axial_depth_mm;
    double feed_mm_per_min = rows.at(feed, tp);
    if (!std::isfinite(feed_mm_per_min)) feed_mm_per_min = std::abs(s1 - s0) / (t1 - t0) * 60.0;

    // 4. Engaged windows only.
    if (!planned.engaged || planned.engagement_rad < options.min_engagement_rad ||
        place.chip_factor * place.xy_speed_ratio < planner::kMinChipFactor || !(feed_mm_per_min > 0.0)) {
      w.outcome = WindowOutcome::kNotEngaged;
      return w;
    }
    w.outcome = WindowOutcome::kEngaged;
    w.sample.chip_mm = planner::chip_thickness_mm(place, feed_mm_per_min, flutes, spindle_rpm);
    w.sample.contact_length_mm = planner::model_contact_length_mm(model, planned.contact_length_mm);
    w.sample.force_n = peak.peak_xy_n;
    if (options.scale_to_model_axial_depth) {
      w.sample.force_n /= planner::axial_depth_ratio(model, planned.axial_depth_mm);
    }
    w.sample.weight = 1.0;
    w.sample.s_mm = 0.5 * (s0 + s1);
    return w;
  };

  for (const force_log::RevolutionPeak& peak : peaks) {
    const WindowPlace w = evaluate(peak, period_s);
    switch (w.outcome) {
      case WindowOutcome::kNan: ++out.skipped_nan; continue;
      case WindowOutcome::kNotAligned: ++out.skipped_not_aligned; continue;
      case WindowOutcome::kNotEngaged:
        out.revolutions.push_back({w.s_start_mm, w.s_end_mm, peak.peak_xy_n});
        ++out.skipped_not_engaged;
        continue;
      case WindowOutcome::kEngaged:
        out.revolutions.push_back({w.s_start_mm, w.s_end_mm, peak.peak_xy_n});
        out.samples.push_back(w.sample);
        out.sample_t_start_s.push_back(peak.t_start_s);
        break;
    }
  }

  // 5. Tooth periods: the same rule on windows of 1/Z turn (window k in turn k / Z, flute window k mod Z),
  //    phased so that the tooth peaks lie in the middle of their windows; then each one's runout factor.
  const std::vector<force_log::RevolutionPeak> periods = tooth_periods_centred_on_peaks(t, fx, fy, spindle_rpm * flutes);
  const auto z = static_cast<std::size_t>(flutes);
  for (const force_log::RevolutionPeak& period : periods) {
    const WindowPlace w = evaluate(period, period_s / flutes);
    if (w.outcome != WindowOutcome::kEngaged) continue;
    ToothPeriodPeak p;
    p.window = period.revolution;
    p.s_start_mm = w.s_start_mm;
    p.s_end_mm = w.s_end_mm;
    p.s_peak_mm = w.s_peak_mm;
    p.t_peak_s = period.t_peak_s;
    p.sample = w.sample;
    out.tooth_periods.push_back(p);
  }
  // Runout: the pattern (largest / own peak per flute window) of the steady turns — Z consecutive
  // engaged windows whose largest peak is within kSteadyTurnChange of the turn before's.
  struct SteadyTurn {
    long number = 0;
    std::vector<double> ratio;  // per flute window
  };
  std::vector<SteadyTurn> steady;
  double previous_largest = 0.0;
  long previous_number = -2;
  for (std::size_t k = 0; k + z <= out.tooth_periods.size();) {
    const long number = out.tooth_periods[k].window / flutes;
    std::size_t end = k;
    while (end < out.tooth_periods.size() && out.tooth_periods[end].window / flutes == number) ++end;
    if (end - k == z) {
      double largest = 0.0;
      for (std::size_t j = k; j < end; ++j) largest = std::max(largest, out.tooth_periods[j].sample.force_n);
      if (number == previous_number + 1 && std::abs(largest / previous_largest - 1.0) < kSteadyTurnChange) {
        SteadyTurn turn{number, std::vector<double>(z, 1.0)};
        for (std::size_t j = k; j < end; ++j) {
          const auto& p = out.tooth_periods[j];
          if (p.sample.force_n > 0.0) turn.ratio[static_cast<std::size_t>(p.window % flutes)] = largest / p.sample.force_n;
        }
        steady.push_back(std::move(turn));
      }
      previous_largest = largest;
      previous_number = number;
    }
    k = std::max(end, k + 1);
  }
  // Each tooth period: the median pattern of the kRunoutTurns steady turns nearest to its own.
  for (auto& p : out.tooth_periods) {
    if (steady.empty()) break;
    const long number = p.window / flutes;
    auto hi = std::lower_bound(steady.begin(), steady.end(), number, [](const SteadyTurn& t, long n) { return t.number < n; });
    auto lo = hi;
    std::vector<double> ratios;
    const auto j = static_cast<std::size_t>(p.window % flutes);
    while (ratios.size() < kRunoutTurns && (lo != steady.begin() || hi != steady.end())) {
      const bool take_low = hi == steady.end() || (lo != steady.begin() && number - (lo - 1)->number <= hi->number - number);
      if (take_low) {
        --lo;
        ratios.push_back(lo->ratio[j]);
      } else {
        ratios.push_back(hi->ratio[j]);
        ++hi;
      }
    }
    std::nth_element(ratios.begin(), ratios.begin() + static_cast<long>(ratios.size() / 2), ratios.end());
    p.runout_factor = ratios[ratios.size() / 2];
  }

  out.message = std::to_string(peaks.size()) + " complete revolutions at " + fixed(spindle_rpm, 0) +
                " rpm: " + std::to_string(out.samples.size()) + " engaged samples; skipped " +
                std::to_string(out.skipped_not_engaged) + " out of the material, " + std::to_string(out.skipped_nan) +
                " with NaN forces or gaps, " + std::to_string(out.skipped_not_aligned) + " not aligned";
  if (delay_s != 0.0) out.message += "; places shifted by the force delay " + fixed(1e3 * delay_s, 1) + " ms";
  return out;
}

}  // namespace feedplan::learning
