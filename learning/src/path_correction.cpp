#include "feedplan/learning/path_correction.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "feedplan/model/model_prediction.hpp"
#include "feedplan/planner/feed_limit.hpp"
#include "local_linear_smoothing.hpp"
#include "place_search.hpp"

namespace feedplan::learning {

namespace {

// A measurement at a place, with the feed run there.
struct Placed {
  double s_mm = 0.0;
  PathMeasurement m;
  double feed_mm_per_min = 0.0;
  double predicted_n = 0.0;  // the planner's F̂ for the chip and L measured there, its transfer included
};

Placed lerp(const Placed& a, const Placed& b, double w) {
  const auto mix = [w](double x, double y) { return x + w * (y - x); };
  return {mix(a.s_mm, b.s_mm),
          {mix(a.m.chip_mm, b.m.chip_mm), mix(a.m.contact_length_mm, b.m.contact_length_mm), mix(a.m.force_n, b.m.force_n),
           std::max(a.m.window_mm, b.m.window_mm)},
          mix(a.feed_mm_per_min, b.feed_mm_per_min), mix(a.predicted_n, b.predicted_n)};
}

// The measurement at s inside a run of consecutive tooth periods: linear between the peak places
// around s, the end values beyond the first and last peak.
Placed measurement_at(const std::vector<Placed>& run, double s_mm) {
  if (s_mm <= run.front().s_mm) return run.front();
  if (s_mm >= run.back().s_mm) return run.back();
  const auto after = std::upper_bound(run.begin(), run.end(), s_mm, [](double s, const Placed& p) { return s < p.s_mm; });
  const Placed& b = *after;
  const Placed& a = *(after - 1);
  const double ds = b.s_mm - a.s_mm;
  return ds > 1e-12 ? lerp(a, b, (s_mm - a.s_mm) / ds) : (a.m.force_n >= b.m.force_n ? a : b);
}

// The largest raw peak (× its transfer) of the periods left out by the runout filter within half a turn
// either side of period `k` (floor(Z / 2) periods, in the run of consecutive periods that starts at
// `first`; 0 when Z is not known or none was left out): with runout the turn's dominant tooth carries the
// revolution's peak, and where the engagement changes (entries) the factor that says which tooth that is
// comes from steady turns elsewhere, so the period left out may be the dominant one.
double half_turn_envelope_n(const std::vector<ToothPeriodPeak>& periods, std::size_t first, std::size_t k, int flutes) {
  if (flutes < 1) return 0.0;
  const long reach = std::max(1, flutes / 2);
  const long window = periods[k].window;
  double largest = 0.0;
  for (std::size_t j = first; j < periods.size(); ++j) {
    if (j > first && periods[j].window != periods[j - 1].window + 1) break;
    if (periods[j].window > window + reach) break;
    if (periods[j].window < window - reach || periods[j].runout_factor <= kMaxRunoutFactor) continue;
    largest = std::max(largest, periods[j].sample.force_n * periods[j].sample.transfer_factor);
  }
  return largest;
}

// The measurement at plan sample `planned` from the one interpolated between peak places (`at`): the force
// as interpolated, but t_m and L the sample's own — t_m for the feed run where the tool passed the sample
// (t_m is proportional to the feed), L as the planner evaluates the model there — so that the chip a
// correction makes the planner run at the sample is the chip measured there, also where the feed changes
// between peak places (an entry, the slow-down before one).
PathMeasurement measurement_at_sample(const Placed& at, const planner::PlannedSample& planned,
                                      const model::ResponseSurfaceModel& model) {
  PathMeasurement m = at.m;
  if (planned.feed_mm_per_min > 0.0 && planned.chip_thickness_mm > 0.0 && at.feed_mm_per_min > 0.0) {
    m.chip_mm = planned.chip_thickness_mm * at.feed_mm_per_min / planned.feed_mm_per_min;
  }
  if (planned.contact_length_mm > 0.0) m.contact_length_mm = planner::model_contact_length_mm(model, planned.contact_length_mm);
  return m;
}

// The run's forces with the noise of single peak readings averaged out (see kReadingSmoothingHalfWidth):
// smoothed as the ratio to the planner's F̂ at each reading's chip and L, so that the force's own rise and
// fall with the chip is kept as the model has it and only the model's error is averaged, and only over
// readings whose contact length and chip are within kReadingSmoothingLengthSpread of the reading's own; and
// no reading is moved further than kReadingSmoothingNoiseSigmas × the log's noise per row (`noise_n`; not at
// all where the noise was not measured).
void smooth_forces(std::vector<Placed>& run, double noise_n) {
  std::vector<double> s_mm;
  std::vector<double> ratio;
  std::vector<double> length_mm;
  std::vector<double> chip_mm;
  std::vector<std::size_t> at;
  for (std::size_t k = 0; k < run.size(); ++k) {
    if (!(run[k].predicted_n > 0.0)) continue;
    s_mm.push_back(run[k].s_mm);
    ratio.push_back(run[k].m.force_n / run[k].predicted_n);
    length_mm.push_back(run[k].m.contact_length_mm);
    chip_mm.push_back(run[k].m.chip_mm);
    at.push_back(k);
  }
  const std::vector<double> smoothed =
      detail::local_linear_smoothed(s_mm, ratio, {length_mm, chip_mm}, kReadingSmoothingHalfWidth,
                                    kReadingSmoothingLengthSpread);
  const double reach_n = std::isfinite(noise_n) && noise_n > 0.0 ? kReadingSmoothingNoiseSigmas * noise_n : 0.0;
  for (std::size_t j = 0; j < at.size(); ++j) {
    const double read_n = run[at[j]].m.force_n;
    const double averaged_n = smoothed[j] * run[at[j]].predicted_n;
    run[at[j]].m.force_n = std::max(std::clamp(averaged_n, read_n - reach_n, read_n + reach_n), 0.0);
  }
}

// The feed per tooth (XY) at which the next plan runs plan sample `j` with correction c: the chip it is
// steered to over the sample's chip factor (t_m / f_z); 0 where it has none or the model gives no chip.
double steered_feed_per_tooth_mm(const planner::PlannedSample& sample, const detail::PlaceModel& place,
                                 const PathMeasurement& measured, double target_force_n, double c) {
  if (!sample.engaged || !(sample.chip_factor > 0.0)) return 0.0;
  const double reference_mm = measured.chip_mm > 0.0 ? measured.chip_mm : sample.chip_thickness_mm;
  if (!(reference_mm > 0.0)) return 0.0;
  const double chip_mm = detail::chip_at_correction_mm(place, target_force_n, c, reference_mm / (2.0 * kSlowingReach),
                                                       reference_mm * 2.0 * kSecantReach);
  return chip_mm > 0.0 ? chip_mm / sample.chip_factor : 0.0;
}

// The look-ahead's c at plan sample i from sample j ahead of it (see learn_along_path): no more than j's own
// c, nor more than what runs i at j's feed per tooth (`feed_per_tooth_mm`, 0 where not known: c alone).
double looked_ahead_correction(const planner::PlannedSample& sample_i, const detail::PlaceModel& place_i,
                               double feed_per_tooth_i_mm, double feed_per_tooth_j_mm, double correction_j,
                               double target_force_n) {
  if (!(feed_per_tooth_i_mm > 0.0) || !(feed_per_tooth_j_mm > 0.0)) return correction_j;
  if (feed_per_tooth_j_mm >= feed_per_tooth_i_mm) return 0.0;
  const double at_j_feed = place_i.correction_at(feed_per_tooth_j_mm * sample_i.chip_factor, target_force_n);
  return at_j_feed > 0.0 ? std::min(correction_j, at_j_feed) : correction_j;
}

// Look ahead one tooth period: a peak is placed only to within its tooth period, and where the force rises
// along the path (an entry) the next plan slows down before the place the rise was seen at (see
// learn_along_path). Only a place ahead with a larger c can raise a c (looked_ahead_correction gives no more
// than the c ahead, and every c is ≥ kMinPathCorrection > 0), so the feed per tooth a correction steers to — a
// search on the place's model — is found only for the samples such a place involves.
void look_ahead(const std::vector<planner::PlannedSample>& samples, const std::vector<detail::PlaceModel>& places,
                double target_force_n, PathLearning& out) {
  const std::size_t n = samples.size();
  std::vector<std::optional<double>> steered_mm(n);
  const auto feed_per_tooth_mm = [&](std::size_t j) {
    if (!steered_mm[j]) {
      steered_mm[j] =
          steered_feed_per_tooth_mm(samples[j], places[j], out.measurement[j], target_force_n, out.place_correction[j]);
    }
    return *steered_mm[j];
  };
  out.correction = out.place_correction;
  for (std::size_t i = 0; i < n; ++i) {
    const double reach_mm = samples[i].s_mm + out.measurement[i].window_mm;
    for (std::size_t j = i + 1; j < n && samples[j].s_mm <= reach_mm; ++j) {
      if (out.place_correction[j] <= out.correction[i]) continue;
      const double ahead = looked_ahead_correction(samples[i], places[i], feed_per_tooth_mm(i), feed_per_tooth_mm(j),
                                                   out.place_correction[j], target_force_n);
      out.correction[i] = std::max(out.correction[i], ahead);
    }
    // … but not slower than the place itself was measured to bear.
    const double not_slower = detail::largest_correction_not_slower(places[i], target_force_n, out.bracket[i]);
    out.correction[i] = std::max(out.place_correction[i], std::min(out.correction[i], not_slower));
  }
}

}  // namespace

PathLearning learn_along_path(const planner::PlanResult& plan, const model::ResponseSurfaceModel& model,
                              const std::vector<MeasuredRevolutions>& measured, double target_force_n,
                              const PathLearning& previous) {
  const auto& samples = plan.samples;
  const std::size_t n = samples.size();
  const std::vector<double>& previous_correction =
      previous.place_correction.size() == n ? previous.place_correction : previous.correction;
  const bool had_correction = previous_correction.size() == n;
  const bool had_measurement = previous.measurement.size() == n;

  // This step's measurement per plan sample, averaged over the logs (the window: the longest).
  std::vector<PathMeasurement> sum(n);
  std::vector<int> count(n, 0);
  const auto first_at_or_after = [&](double s_mm) {
    return static_cast<std::size_t>(std::lower_bound(samples.begin(), samples.end(), s_mm,
                                                     [](const planner::PlannedSample& p, double s) { return p.s_mm < s; }) -
                                    samples.begin());
  };
  for (const MeasuredRevolutions& log : measured) {
    const auto& periods = log.tooth_periods;
    const double noise_excess_n = log.noise.peak_excess_n;
    std::size_t k = 0;
    while (k < periods.size()) {
      // A run of consecutive tooth periods (no window between them skipped).
      std::vector<Placed> run;
      const double s_start_mm = periods[k].s_start_mm;
      double s_end_mm = periods[k].s_end_mm;
      const std::size_t first = k;
      for (; k < periods.size() && (k == first || periods[k].window == periods[k - 1].window + 1); ++k) {
        const ToothPeriodPeak& p = periods[k];
        s_end_mm = std::max(s_end_mm, p.s_end_mm);
        // A tooth short of its turn's largest by more than kMaxRunoutFactor says more about the runout
        // than about the cut, and its factor comes from steady turns elsewhere, at other chips.
        if (!(p.sample.force_n > 0.0) || p.runout_factor > kMaxRunoutFactor) continue;
        // The measured peak itself: compared with the planner's F̂ at each plan sample, its transfer included.
        // Less what the sensor's noise adds to a peak reading: the target is the true force's.
        const double read_n = std::max(p.runout_factor * p.sample.force_n * p.sample.transfer_factor,
                                       half_turn_envelope_n(periods, first, k, log.flutes));
        run.push_back({p.s_peak_mm, {p.sample.chip_mm, p.sample.contact_length_mm, std::max(read_n - noise_excess_n, 0.0),
                                     p.s_end_mm - p.s_start_mm},
                       p.sample.feed_mm_per_min,
                       p.sample.transfer_factor *
                           model::predict(model, p.sample.chip_mm, p.sample.contact_length_mm).force_n});
      }
      if (run.empty()) continue;
      std::stable_sort(run.begin(), run.end(), [](const Placed& a, const Placed& b) { return a.s_mm < b.s_mm; });
      smooth_forces(run, log.noise.sigma_n);
      for (std::size_t i = first_at_or_after(s_start_mm); i < n && samples[i].s_mm <= s_end_mm; ++i) {
        if (!samples[i].engaged) continue;
        const PathMeasurement m = measurement_at_sample(measurement_at(run, samples[i].s_mm), samples[i], model);
        sum[i].chip_mm += m.chip_mm;
        sum[i].contact_length_mm += m.contact_length_mm;
        sum[i].force_n += m.force_n;
        sum[i].window_mm = std::max(sum[i].window_mm, m.window_mm);
        ++count[i];
      }
    }
  }

  // The sensor's noise per row, as the logs measured it out of the cut (their mean; 0: not measured).
  double noise_sum_n = 0.0;
  int noise_logs = 0;
  for (const MeasuredRevolutions& log : measured) {
    if (log.noise.sigma_n > 0.0) {
      noise_sum_n += log.noise.sigma_n;
      ++noise_logs;
    }
  }
  const double noise_n = noise_logs > 0 ? noise_sum_n / noise_logs : 0.0;

  PathLearning out;
  out.place_correction = had_correction ? previous_correction : std::vector<double>(n, 1.0);
  out.measurement = had_measurement ? previous.measurement : std::vector<PathMeasurement>(n);
  out.bracket = previous.bracket.size() == n ? previous.bracket : std::vector<PlaceBracket>(n);
  out.step_force_n.assign(n, 0.0);
  std::vector<detail::PlaceModel> places(n);
  for (std::size_t i = 0; i < n; ++i) {
    places[i].model = &model;
    places[i].contact_length_mm = out.measurement[i].contact_length_mm > 0.0
                                      ? out.measurement[i].contact_length_mm
                                      : planner::model_contact_length_mm(model, samples[i].contact_length_mm);
    places[i].transfer_factor = samples[i].transfer_factor > 0.0 ? samples[i].transfer_factor : 1.0;
    if (count[i] == 0) continue;
    const double w = 1.0 / count[i];
    const PathMeasurement& before = out.measurement[i];
    // The window: the longest seen here (the next plan may run as fast as any earlier one did).
    const PathMeasurement now{w * sum[i].chip_mm, w * sum[i].contact_length_mm, w * sum[i].force_n,
                              std::max(sum[i].window_mm, before.window_mm)};
    places[i].contact_length_mm = now.contact_length_mm;
    out.bracket[i] = detail::bracket_with(out.bracket[i], now, target_force_n);
    out.place_correction[i] =
        detail::next_place_correction(places[i], target_force_n, now, before, out.bracket[i], out.place_correction[i],
                                      noise_n);
    out.measurement[i] = now;
    // The next plan's tooth period here is as much longer than this one's as its chip is thicker: a place sped
    // up slows down before a rise that far ahead of it.
    const bool sped_up = out.place_correction[i] < places[i].correction_at(now.chip_mm, target_force_n);
    const double next_chip_mm =
        sped_up ? detail::chip_at_correction_mm(places[i], target_force_n, out.place_correction[i], now.chip_mm,
                                                now.chip_mm * kSecantReach)
                : 0.0;
    if (next_chip_mm > now.chip_mm && now.chip_mm > 0.0) {
      out.measurement[i].window_mm = std::max(now.window_mm, sum[i].window_mm * next_chip_mm / now.chip_mm);
    }
    out.step_force_n[i] = now.force_n;
  }
  look_ahead(samples, places, target_force_n, out);
  return out;
}

}  // namespace feedplan::learning
