#include "steady_run.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "median.hpp"

namespace feedplan::model_db::detail {
namespace {

// MAD → standard deviation for normally distributed data.
constexpr double kMadToSigma = 1.4826;
// Plateau search repeats at most this often (it normally settles in one or two rounds).
constexpr int kMaxPlateauRounds = 10;

//! The peaks with the revolutions step 1 left eligible.
struct EligiblePeaks {
  const std::vector<force_log::RevolutionPeak>& peaks;
  const std::vector<bool>& eligible;

  std::size_t size() const { return peaks.size(); }
  // Consecutive: both eligible and no gap in the revolution numbers between them.
  bool linked(std::size_t k) const {  // k and k + 1
    return eligible[k] && eligible[k + 1] && peaks[k + 1].revolution == peaks[k].revolution + 1;
  }
};

//! Step 2: the trend T_k of each eligible revolution (NaN for the others) and its largest value.
struct Trend {
  std::vector<double> values;
  double max = 0.0;
};

//! For each revolution, the stretch [begin, end) of consecutive eligible revolutions it lies in.
struct Stretches {
  std::vector<std::size_t> begin;
  std::vector<std::size_t> end;
};

Stretches consecutive_stretches(const EligiblePeaks& revolutions) {
  const std::size_t n = revolutions.size();
  Stretches stretches{std::vector<std::size_t>(n), std::vector<std::size_t>(n)};
  for (std::size_t k = 0; k < n;) {
    std::size_t e = k + 1;
    while (e < n && revolutions.linked(e - 1)) ++e;
    for (std::size_t j = k; j < e; ++j) {
      stretches.begin[j] = k;
      stretches.end[j] = e;
    }
    k = e;
  }
  return stretches;
}

//! Step 2: running median inside each stretch of consecutive eligible revolutions.
Trend running_median_trend(const EligiblePeaks& revolutions, const CuttingTestImportOptions& options) {
  const std::size_t n = revolutions.size();
  const Stretches stretches = consecutive_stretches(revolutions);
  const std::size_t half = static_cast<std::size_t>(options.trend_window_revolutions / 2);
  Trend trend{std::vector<double>(n, std::nan("")), 0.0};
  for (std::size_t k = 0; k < n; ++k) {
    if (!revolutions.eligible[k]) continue;
    std::vector<double> window;
    const std::size_t lo = std::max(stretches.begin[k], k >= half ? k - half : 0);
    const std::size_t hi = std::min(stretches.end[k], k + half + 1);
    for (std::size_t j = lo; j < hi; ++j) window.push_back(revolutions.peaks[j].peak_xy_n);
    trend.values[k] = median(window);
    trend.max = std::max(trend.max, trend.values[k]);
  }
  return trend;
}

//! The first longest run [begin, end) of consecutive eligible revolutions with |T_k − level| within the
//! plateau tolerance; empty when there is none.
std::pair<std::size_t, std::size_t> longest_run_near(const EligiblePeaks& revolutions, const Trend& trend,
                                                     double level, const CuttingTestImportOptions& options) {
  const std::size_t n = revolutions.size();
  std::size_t begin = 0, end = 0;
  bool is_open = false;
  std::size_t open = 0;  // first revolution of the run being extended, when is_open
  auto close = [&](std::size_t k) {
    if (is_open && k - open > end - begin) {
      begin = open;
      end = k;
    }
    is_open = false;
  };
  for (std::size_t k = 0; k < n; ++k) {
    const bool ok = revolutions.eligible[k] && std::abs(trend.values[k] - level) <= options.plateau_tolerance * level;
    if (is_open && (!ok || !revolutions.linked(k - 1))) close(k);
    if (ok && !is_open) {
      is_open = true;
      open = k;
    }
  }
  close(n);
  return {begin, end};
}

//! Step 3: the plateau and its level, re-found until it no longer changes.
void find_plateau(const EligiblePeaks& revolutions, const Trend& trend, const CuttingTestImportOptions& options,
                  SteadyRun& run) {
  const std::size_t n = revolutions.size();
  std::vector<double> loaded;
  for (std::size_t k = 0; k < n; ++k) {
    if (revolutions.eligible[k] && trend.values[k] >= options.loaded_fraction * trend.max) {
      loaded.push_back(revolutions.peaks[k].peak_xy_n);
    }
  }
  double level = median(loaded);
  std::size_t best_begin = 0, best_end = 0;
  for (int round = 0; round < kMaxPlateauRounds; ++round) {
    const auto [begin, end] = longest_run_near(revolutions, trend, level, options);
    if (end == begin) break;
    std::vector<double> values;
    for (std::size_t k = begin; k < end; ++k) values.push_back(revolutions.peaks[k].peak_xy_n);
    const double new_level = median(values);
    const bool same = begin == best_begin && end == best_end;
    best_begin = begin;
    best_end = end;
    level = new_level;
    if (same) break;
  }
  run.plateau_begin = run.begin = best_begin;
  run.plateau_end = run.end = best_end;
  run.level_n = level;
}

//! Step 4: drops the leading and trailing revolutions of the plateau that sit low.
void trim_ends(const std::vector<force_log::RevolutionPeak>& peaks, const CuttingTestImportOptions& options,
               SteadyRun& run) {
  const double level = run.level_n;
  std::vector<double> deviations;
  for (std::size_t k = run.begin; k < run.end; ++k) deviations.push_back(std::abs(peaks[k].peak_xy_n - level));
  const double sigma = kMadToSigma * median(deviations);
  const double threshold = level - std::max(options.trim_sigmas * sigma, options.trim_min_fraction * level);
  while (run.begin < run.end && peaks[run.begin].peak_xy_n < threshold) ++run.begin;
  while (run.end > run.begin && peaks[run.end - 1].peak_xy_n < threshold) --run.end;
}

}  // namespace

SteadyRun find_steady(const std::vector<force_log::RevolutionPeak>& peaks, const std::vector<bool>& eligible,
                      const CuttingTestImportOptions& options) {
  SteadyRun run;
  const EligiblePeaks revolutions{peaks, eligible};
  const Trend trend = running_median_trend(revolutions, options);
  if (!(trend.max > 0.0)) return run;
  run.any_force = true;
  find_plateau(revolutions, trend, options, run);
  if (run.size() == 0) return run;
  trim_ends(peaks, options, run);
  return run;
}

double median_over(const std::vector<double>& values, const SteadyRun& run) {
  return median(std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(run.begin),
                                    values.begin() + static_cast<std::ptrdiff_t>(run.end)));
}

}  // namespace feedplan::model_db::detail
