#include "feedplan/learning/measured_revolutions.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/planner/feed_limit.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/learning/peak_noise_bias.hpp"
#include "fixed_text.hpp"

namespace feedplan::learning {

namespace {

using detail::fixed;

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

// The log's rows as signals (step 1). NaN forces read as 0 for force_log::revolution_peaks; nan_rows is
// NaN there (0 elsewhere), so windows holding one are skipped.
struct RowSignals {
  std::vector<double> t, fx, fy, feed, nan_rows;
};

RowSignals row_signals(const force_log::ForceLog& log) {
  const std::size_t n = log.rows.size();
  RowSignals r;
  for (std::vector<double>* v : {&r.t, &r.fx, &r.fy, &r.feed, &r.nan_rows}) v->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& row = log.rows[i];
    r.t[i] = row.t_s;
    const bool finite = std::isfinite(row.fx_n) && std::isfinite(row.fy_n);
    r.fx[i] = finite ? row.fx_n : 0.0;
    r.fy[i] = finite ? row.fy_n : 0.0;
    r.nan_rows[i] = finite ? 0.0 : kNaN;
    r.feed[i] = row.feed_mm_per_min;
  }
  return r;
}

// What every window (a revolution or a tooth period) is judged against.
struct WindowContext {
  const RowSignals& signals;
  const RowSeries& rows;
  double mean_step_s;
  const Alignment& alignment;
  const std::vector<planner::PlannedSample>& samples;
  const model::ResponseSurfaceModel& model;
  int flutes;
  double spindle_rpm;
  const MeasuredRevolutionOptions& options;
};

// Index of the planned sample nearest to s.
std::size_t nearest_sample(const std::vector<planner::PlannedSample>& samples, double s_mm) {
  const auto it = std::lower_bound(samples.begin(), samples.end(), s_mm,
                                   [](const planner::PlannedSample& p, double s) { return p.s_mm < s; });
  std::size_t j = static_cast<std::size_t>(it - samples.begin());
  if (j == samples.size()) return samples.size() - 1;
  if (j > 0 && s_mm - samples[j - 1].s_mm < samples[j].s_mm - s_mm) --j;
  return j;
}

// XY speed / path speed around s (the plan's samples carry the chip factor without it).
double xy_speed_ratio(const std::vector<planner::PlannedSample>& samples, double s_mm) {
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
}

// Step 1's skip rule: a NaN force in the window, or fewer than half the rows it should hold.
bool has_nan_or_gap(const WindowContext& c, const force_log::RevolutionPeak& peak, double window_s) {
  const std::size_t first = c.rows.first_at_or_after(peak.t_start_s);
  const std::size_t end = c.rows.first_at_or_after(peak.t_end_s);
  bool has_nan = static_cast<double>(end - first) < kMinRowShare * window_s / c.mean_step_s;
  for (std::size_t i = first; i < end && !has_nan; ++i) has_nan = std::isnan(c.signals.nan_rows[i]);
  return has_nan;
}

// A window's times shifted by the force's lag behind the positions, and the alignment's s there.
struct ShiftedWindow {
  double t0 = 0.0, t1 = 0.0, tp = 0.0;      // start, end and peak, s
  double s0 = 0.0, s1 = 0.0, s_peak = 0.0;  // s at t0, at t1 (or the last row) and at tp, mm
};

// 2. Place, with the force's lag behind the positions; nothing when a row of the span is not aligned.
std::optional<ShiftedWindow> place_on_path(const WindowContext& c, const force_log::RevolutionPeak& peak) {
  const std::vector<double>& t = c.signals.t;
  const Alignment& alignment = c.alignment;
  const double delay_s = alignment.delay_s;
  const double t0 = peak.t_start_s - delay_s, t1 = peak.t_end_s - delay_s, tp = peak.t_peak_s - delay_s;
  if (!c.rows.all_finite(alignment.s_mm, t0, std::min(t1, t.back()))) return std::nullopt;
  const double s0 = c.rows.at(alignment.s_mm, t0);
  // The last window may end a fraction of a row past the last row (force_log::revolution_peaks' rule).
  const double s1 = c.rows.at(alignment.s_mm, std::min(t1, t.back()));
  const double s_peak = c.rows.at(alignment.s_mm, tp);
  if (!std::isfinite(s0) || !std::isfinite(s1) || !std::isfinite(s_peak)) return std::nullopt;
  return ShiftedWindow{t0, t1, tp, s0, s1, s_peak};
}

// The model's inputs where a window's peak was measured, at the feed run there.
struct PeakPlace {
  const planner::PlannedSample* planned = nullptr;  // nearest to the peak's place
  geometry::EngagementSample place;
  double feed_mm_per_min = 0.0;
};

// 3. Model inputs at the peak's place, at the feed run there.
PeakPlace model_inputs_at_peak(const WindowContext& c, const ShiftedWindow& w) {
  const double t0 = w.t0, t1 = w.t1, tp = w.tp, s0 = w.s0, s1 = w.s1, s_peak = w.s_peak;
  const planner::PlannedSample& planned = c.samples[nearest_sample(c.samples, s_peak)];
  PeakPlace at;
  at.planned = &planned;
  geometry::EngagementSample& place = at.place;
  place.s_mm = s_peak;
  place.position = planned.position;
  place.cutting = planned.engaged;
  place.engagement_rad = planned.engagement_rad;
  place.chip_factor = planned.chip_factor;
  place.xy_speed_ratio = xy_speed_ratio(c.samples, s_peak);
  place.contact_length_mm = planned.contact_length_mm;
  place.axial_depth_mm = planned.axial_depth_mm;
  double feed_mm_per_min = c.rows.at(c.signals.feed, tp);
  if (!std::isfinite(feed_mm_per_min)) feed_mm_per_min = std::abs(s1 - s0) / (t1 - t0) * 60.0;
  at.feed_mm_per_min = feed_mm_per_min;
  return at;
}

// 4. Engaged windows only: true when the plan has the peak's place out of the material (or too little
//    engaged), without a chip, or the feed is not positive.
bool not_engaged(const WindowContext& c, const PeakPlace& at) {
  const planner::PlannedSample& planned = *at.planned;
  const geometry::EngagementSample& place = at.place;
  const double feed_mm_per_min = at.feed_mm_per_min;
  return !planned.engaged || planned.engagement_rad < c.options.min_engagement_rad ||
         place.chip_factor * place.xy_speed_ratio < planner::kMinChipFactor || !(feed_mm_per_min > 0.0);
}

// The learning sample of an engaged window.
LearningSample learning_sample(const WindowContext& c, const force_log::RevolutionPeak& peak, const ShiftedWindow& w,
                               const PeakPlace& at) {
  const planner::PlannedSample& planned = *at.planned;
  LearningSample sample;
  sample.chip_mm = planner::chip_thickness_mm(at.place, at.feed_mm_per_min, c.flutes, c.spindle_rpm);
  sample.contact_length_mm = planner::model_contact_length_mm(c.model, planned.contact_length_mm);
  sample.force_n = peak.peak_xy_n;
  if (!c.options.sensor_peak_gain.empty()) {
    sample.force_n /= c.options.sensor_peak_gain[static_cast<std::size_t>(&planned - c.samples.data())];
  }
  if (c.options.transfer_to_model) {
    sample.transfer_factor = planner::force_transfer_factor(c.model, at.place, planned.load_ratio, at.feed_mm_per_min,
                                                            c.flutes, c.spindle_rpm);
    sample.force_n /= sample.transfer_factor;
  }
  sample.weight = 1.0;
  sample.s_mm = 0.5 * (w.s0 + w.s1);
  sample.feed_mm_per_min = at.feed_mm_per_min;
  sample.s_peak_mm = w.s_peak;
  return sample;
}

// One window (a revolution or a tooth period) → its place and, engaged, its sample (steps 1–4).
WindowPlace evaluate_window(const WindowContext& c, const force_log::RevolutionPeak& peak, double window_s) {
  WindowPlace w;
  if (has_nan_or_gap(c, peak, window_s)) {
    w.outcome = WindowOutcome::kNan;
    return w;
  }
  const std::optional<ShiftedWindow> shifted = place_on_path(c, peak);
  if (!shifted) {
    w.outcome = WindowOutcome::kNotAligned;
    return w;
  }
  w.s_start_mm = std::min(shifted->s0, shifted->s1);
  w.s_end_mm = std::max(shifted->s0, shifted->s1);
  w.s_peak_mm = shifted->s_peak;
  const PeakPlace at = model_inputs_at_peak(c, *shifted);
  if (not_engaged(c, at)) {
    w.outcome = WindowOutcome::kNotEngaged;
    return w;
  }
  w.outcome = WindowOutcome::kEngaged;
  w.sample = learning_sample(c, peak, *shifted, at);
  return w;
}

// Every revolution's window into out: its span and peak, its sample when engaged, or why it is skipped.
void add_revolutions(const WindowContext& c, const std::vector<force_log::RevolutionPeak>& peaks, double period_s,
                     MeasuredRevolutions& out, std::vector<force_log::RevolutionPeak>& air) {
  for (const force_log::RevolutionPeak& peak : peaks) {
    const WindowPlace w = evaluate_window(c, peak, period_s);
    switch (w.outcome) {
      case WindowOutcome::kNan: ++out.skipped_nan; continue;
      case WindowOutcome::kNotAligned: ++out.skipped_not_aligned; continue;
      case WindowOutcome::kNotEngaged:
        out.revolutions.push_back({w.s_start_mm, w.s_end_mm, peak.peak_xy_n});
        air.push_back(peak);
        ++out.skipped_not_engaged;
        continue;
      case WindowOutcome::kEngaged:
        out.revolutions.push_back({w.s_start_mm, w.s_end_mm, peak.peak_xy_n});
        out.samples.push_back(w.sample);
        out.sample_t_start_s.push_back(peak.t_start_s);
        break;
    }
  }
}

// 5. Tooth periods: the same rule on windows of 1/Z turn (window k in turn k / Z, flute window k mod Z),
//    phased so that the tooth peaks lie in the middle of their windows; the engaged ones.
std::vector<ToothPeriodPeak> engaged_tooth_periods(const WindowContext& c, double period_s,
                                                   std::vector<force_log::RevolutionPeak>& windows) {
  const RowSignals& s = c.signals;
  const std::vector<force_log::RevolutionPeak> periods =
      tooth_periods_centred_on_peaks(s.t, s.fx, s.fy, c.spindle_rpm * c.flutes);
  std::vector<ToothPeriodPeak> tooth_periods;
  for (const force_log::RevolutionPeak& period : periods) {
    const WindowPlace w = evaluate_window(c, period, period_s / c.flutes);
    if (w.outcome != WindowOutcome::kEngaged) continue;
    ToothPeriodPeak p;
    p.window = period.revolution;
    p.s_start_mm = w.s_start_mm;
    p.s_end_mm = w.s_end_mm;
    p.s_peak_mm = w.s_peak_mm;
    p.t_peak_s = period.t_peak_s;
    p.sample = w.sample;
    tooth_periods.push_back(p);
    windows.push_back(period);
  }
  return tooth_periods;
}

// A steady turn's runout pattern.
struct SteadyTurn {
  long number = 0;
  std::vector<double> ratio;  // per flute window
};

// Runout: the pattern (largest / own peak per flute window) of the steady turns — Z consecutive
// engaged windows whose largest peak is within kSteadyTurnChange of the turn before's.
std::vector<SteadyTurn> steady_turns(const std::vector<ToothPeriodPeak>& tooth_periods, int flutes) {
  const auto z = static_cast<std::size_t>(flutes);
  std::vector<SteadyTurn> steady;
  double previous_largest = 0.0;
  long previous_number = -2;
  for (std::size_t k = 0; k + z <= tooth_periods.size();) {
    const long number = tooth_periods[k].window / flutes;
    std::size_t end = k;
    while (end < tooth_periods.size() && tooth_periods[end].window / flutes == number) ++end;
    if (end - k == z) {
      double largest = 0.0;
      for (std::size_t j = k; j < end; ++j) largest = std::max(largest, tooth_periods[j].sample.force_n);
      if (number == previous_number + 1 && std::abs(largest / previous_largest - 1.0) < kSteadyTurnChange) {
        SteadyTurn turn{number, std::vector<double>(z, 1.0)};
        for (std::size_t j = k; j < end; ++j) {
          const auto& p = tooth_periods[j];
          if (p.sample.force_n > 0.0) turn.ratio[static_cast<std::size_t>(p.window % flutes)] = largest / p.sample.force_n;
        }
        steady.push_back(std::move(turn));
      }
      previous_largest = largest;
      previous_number = number;
    }
    k = std::max(end, k + 1);
  }
  return steady;
}

// Median of flute window j's ratio over the kRunoutTurns steady turns nearest to turn `number`.
double runout_factor(const std::vector<SteadyTurn>& steady, long number, std::size_t j) {
  auto hi = std::lower_bound(steady.begin(), steady.end(), number, [](const SteadyTurn& t, long n) { return t.number < n; });
  auto lo = hi;
  std::vector<double> ratios;
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
  return ratios[ratios.size() / 2];
}

// Each tooth period: the median pattern of the kRunoutTurns steady turns nearest to its own.
void set_runout_factors(std::vector<ToothPeriodPeak>& tooth_periods, int flutes) {
  const std::vector<SteadyTurn> steady = steady_turns(tooth_periods, flutes);
  if (steady.empty()) return;
  for (auto& p : tooth_periods) {
    p.runout_factor = runout_factor(steady, p.window / flutes, static_cast<std::size_t>(p.window % flutes));
  }
}

// Throws InputError when the tool, the speed, the options or the log cannot give samples.
void check_input(const force_log::ForceLog& log, int flutes, double spindle_rpm,
                 const MeasuredRevolutionOptions& options, std::size_t plan_samples) {
  std::vector<InputProblem> problems;
  const auto& gains = options.sensor_peak_gain;
  if (!gains.empty() && gains.size() != plan_samples) {
    problems.push_back({"sensor_peak_gain", "has " + std::to_string(gains.size()) + " values: must have " +
                                                std::to_string(plan_samples) + ", one per plan sample"});
  }
  for (std::size_t i = 0; i < gains.size(); ++i) {
    if (!(std::isfinite(gains[i]) && gains[i] > 0.0)) {
      std::string field = "sensor_peak_gain[";
      field += std::to_string(i);
      field += ']';
      problems.push_back({std::move(field), "= " + shortest_number_text(gains[i]) + ": must be > 0"});
      break;
    }
  }
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
}

// Counts and reasons, for people.
std::string counts_message(std::size_t revolutions, double spindle_rpm, double delay_s, const MeasuredRevolutions& out) {
  std::string message = std::to_string(revolutions) + " complete revolutions at " + fixed(spindle_rpm, 0) +
                        " rpm: " + std::to_string(out.samples.size()) + " engaged samples; skipped " +
                        std::to_string(out.skipped_not_engaged) + " out of the material, " +
                        std::to_string(out.skipped_nan) + " with NaN forces or gaps, " +
                        std::to_string(out.skipped_not_aligned) + " not aligned";
  if (delay_s != 0.0) message += "; places shifted by the force delay " + fixed(1e3 * delay_s, 1) + " ms";
  return message;
}

}  // namespace

MeasuredRevolutions measured_revolutions(const force_log::ForceLog& log, const Alignment& alignment,
                                         const planner::PlanResult& plan, const model::ResponseSurfaceModel& model,
                                         int flutes, double spindle_rpm, const MeasuredRevolutionOptions& options) {
  check_input(log, flutes, spindle_rpm, options, plan.samples.size());
  assert(alignment.s_mm.size() == log.rows.size());

  MeasuredRevolutions out;
  out.flutes = flutes;
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

  const RowSignals signals = row_signals(log);
  const std::vector<double>& t = signals.t;
  const std::vector<force_log::RevolutionPeak> peaks = force_log::revolution_peaks(t, signals.fx, signals.fy, spindle_rpm);
  const double period_s = 60.0 / spindle_rpm;
  const double mean_step_s = (t.back() - t.front()) / static_cast<double>(n - 1);
  const RowSeries rows(t);
  const WindowContext context{signals, rows, mean_step_s, alignment, plan.samples, model, flutes, spindle_rpm, options};

  std::vector<force_log::RevolutionPeak> air, tooth_windows;
  add_revolutions(context, peaks, period_s, out, air);
  out.tooth_periods = engaged_tooth_periods(context, period_s, tooth_windows);
  set_runout_factors(out.tooth_periods, flutes);
  out.noise = peak_noise(t, signals.fx, signals.fy, air, tooth_windows);
  out.message = counts_message(peaks.size(), spindle_rpm, alignment.delay_s, out) + "; " + out.noise.message;
  return out;
}

}  // namespace feedplan::learning
