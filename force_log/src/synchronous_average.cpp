#include "feedplan/force_log/synchronous_average.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace feedplan::force_log {

namespace {

// Fewest bins an average is given with: fewer cannot tell the teeth's pulses apart.
constexpr int kMinBins = 4;

// The bins every revolution fills: `bins`, at most half the smallest sample count of a revolution (two
// samples per bin on average, so that sampling not locked to the spindle leaves no bin empty).
int usable_bins(const std::vector<RevolutionPeak>& revolutions, int bins) {
  std::size_t fewest = revolutions.front().samples;
  for (const RevolutionPeak& r : revolutions) fewest = std::min(fewest, r.samples);
  return std::min(bins, static_cast<int>(fewest / 2));
}

}  // namespace

SynchronousAverage synchronous_average(const std::vector<double>& t_s, const std::vector<double>& fx_n,
                                       const std::vector<double>& fy_n,
                                       const std::vector<RevolutionPeak>& revolutions, int bins) {
  assert(t_s.size() == fx_n.size() && t_s.size() == fy_n.size());
  SynchronousAverage average;
  if (revolutions.empty()) return average;
  const int n = usable_bins(revolutions, bins);
  if (n < kMinBins) return average;
  std::vector<double> sum_x(static_cast<std::size_t>(n), 0.0), sum_y(static_cast<std::size_t>(n), 0.0);
  std::vector<int> count(static_cast<std::size_t>(n), 0);
  for (const RevolutionPeak& r : revolutions) {
    const double period_s = r.t_end_s - r.t_start_s;
    if (!(period_s > 0.0)) continue;
    auto row = std::lower_bound(t_s.begin(), t_s.end(), r.t_start_s);
    for (; row != t_s.end() && *row < r.t_end_s; ++row) {
      const auto i = static_cast<std::size_t>(row - t_s.begin());
      const int bin = std::clamp(static_cast<int>(std::floor((*row - r.t_start_s) / period_s * n)), 0, n - 1);
      sum_x[static_cast<std::size_t>(bin)] += fx_n[i];
      sum_y[static_cast<std::size_t>(bin)] += fy_n[i];
      ++count[static_cast<std::size_t>(bin)];
    }
    ++average.revolutions;
  }
  if (std::any_of(count.begin(), count.end(), [](int c) { return c == 0; })) return {};
  average.fx_n.resize(static_cast<std::size_t>(n));
  average.fy_n.resize(static_cast<std::size_t>(n));
  for (std::size_t b = 0; b < static_cast<std::size_t>(n); ++b) {
    average.fx_n[b] = sum_x[b] / count[b];
    average.fy_n[b] = sum_y[b] / count[b];
  }
  return average;
}

}  // namespace feedplan::force_log
