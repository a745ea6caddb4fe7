#include "feedplan/learning/path_correction.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning {

namespace {

// A measurement at a place.
struct Placed {
  double s_mm = 0.0;
  PathMeasurement m;
};

PathMeasurement lerp(const PathMeasurement& a, const PathMeasurement& b, double w) {
  return {a.chip_mm + w * (b.chip_mm - a.chip_mm), a.contact_length_mm + w * (b.contact_length_mm - a.contact_length_mm),
          a.force_n + w * (b.force_n - a.force_n), std::max(a.window_mm, b.window_mm)};
}

// The measurement at s inside a run of consecutive tooth periods: linear between the peak places
// around s, the end values beyond the first and last peak.
PathMeasurement measurement_at(const std::vector<Placed>& run, double s_mm) {
  if (s_mm <= run.front().s_mm) return run.front().m;
  if (s_mm >= run.back().s_mm) return run.back().m;
  const auto after = std::upper_bound(run.begin(), run.end(), s_mm, [](double s, const Placed& p) { return s < p.s_mm; });
  const Placed& b = *after;
  const Placed& a = *(after - 1);
  const double ds = b.s_mm - a.s_mm;
  return ds > 1e-12 ? lerp(a.m, b.m, (s_mm - a.s_mm) / ds) : (a.m.force_n >= b.m.force_n ? a.m : b.m);
}

double model_force_n(const model::ResponseSurfaceModel& model, double chip_mm, double contact_length_mm) {
  return model::predict(model, chip_mm, contact_length_mm).force_n;
}

// The correction at one place from its latest measurement `now` and the one before (force 0: none).
double place_correction(const model::ResponseSurfaceModel& model, double target_force_n, const PathMeasurement& now,
                        const PathMeasurement& before, double previous, bool first) {
  const double predicted = model_force_n(model, now.chip_mm, now.contact_length_mm);
  if (!(predicted > 0.0)) return previous;
  const double ratio = now.force_n / predicted;
  double c = first ? ratio : std::sqrt(previous * ratio);
  if (before.force_n > 0.0) {
    const double spread = std::abs(now.chip_mm - before.chip_mm);
    if (spread >= kMinSecantSpread * std::max(now.chip_mm, before.chip_mm)) {
      const double slope = (now.force_n - before.force_n) / (now.chip_mm - before.chip_mm);
      if (slope > 0.0) {
        const double lo = std::min(now.chip_mm, before.chip_mm) / kSecantReach;
        const double hi = std::max(now.chip_mm, before.chip_mm) * kSecantReach;
        const double chip_at_target = std::clamp(now.chip_mm + (target_force_n - now.force_n) / slope, lo, hi);
        const double predicted_there = model_force_n(model, chip_at_target, now.contact_length_mm);
        const double measured_there = now.force_n + slope * (chip_at_target - now.chip_mm);
        if (predicted_there > 0.0 && measured_there > 0.0) c = measured_there / predicted_there;
      }
    }
  }
  return std::clamp(c, kMinPathCorrection, kMaxPathCorrection);
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
        // The measured peak itself (untransferred): it is carried to each plan sample's own transfer below.
        run.push_back({p.s_peak_mm, {p.sample.chip_mm, p.sample.contact_length_mm,
                                     p.runout_factor * p.sample.force_n * p.sample.transfer_factor,
                                     p.s_end_mm - p.s_start_mm}});
      }
      if (run.empty()) continue;
      std::stable_sort(run.begin(), run.end(), [](const Placed& a, const Placed& b) { return a.s_mm < b.s_mm; });
      for (std::size_t i = first_at_or_after(s_start_mm); i < n && samples[i].s_mm <= s_end_mm; ++i) {
        if (!samples[i].engaged) continue;
        const PathMeasurement m = measurement_at(run, samples[i].s_mm);
        sum[i].chip_mm += m.chip_mm;
        sum[i].contact_length_mm += m.contact_length_mm;
        sum[i].force_n += m.force_n;
        sum[i].window_mm = std::max(sum[i].window_mm, m.window_mm);
        ++count[i];
      }
    }
  }

  PathLearning out;
  out.place_correction = had_correction ? previous_correction : std::vector<double>(n, 1.0);
  out.measurement = had_measurement ? previous.measurement : std::vector<PathMeasurement>(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (count[i] == 0) continue;
    const double w = 1.0 / count[i];
    const PathMeasurement& before = out.measurement[i];
    // The window: the longest seen here (the next plan may run as fast as any earlier one did).
    // On the straight-cut model's terms at this sample: the measured force and the target both over the
    // factor the planner puts on the model here (the chip-load or depth transfer), so that c · F̂ · factor
    // meets the target where the measurement says it will.
    const double factor = samples[i].transfer_factor > 0.0 ? samples[i].transfer_factor : 1.0;
    const PathMeasurement now{w * sum[i].chip_mm, w * sum[i].contact_length_mm, w * sum[i].force_n / factor,
                              std::max(sum[i].window_mm, before.window_mm)};
    out.place_correction[i] =
        place_correction(model, target_force_n / factor, now, before, out.place_correction[i], !had_correction);
    out.measurement[i] = now;
  }
  // Look ahead one tooth period: where the force rises along the path (an entry), the next plan slows
  // down before the place the rise was seen at.
  out.correction = out.place_correction;
  for (std::size_t i = 0; i < n; ++i) {
    const double reach_mm = samples[i].s_mm + out.measurement[i].window_mm;
    for (std::size_t j = i + 1; j < n && samples[j].s_mm <= reach_mm; ++j) {
      out.correction[i] = std::max(out.correction[i], out.place_correction[j]);
    }
  }
  return out;
}

}  // namespace feedplan::learning
