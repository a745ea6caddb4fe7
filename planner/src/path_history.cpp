#include "feedplan/planner/path_history.hpp"

#include <cassert>
#include <algorithm>
#include <cmath>

namespace feedplan::planner {

namespace {

// To 0.1 (the history's resolution, path_history.hpp).
double tenth(double value) { return std::isfinite(value) ? std::round(10.0 * value) / 10.0 : 0.0; }

}  // namespace

PathHistoryCycle history_cycle(const PlanResult& plan, const std::vector<double>& measured_n,
                               const std::vector<PathHistoryCycle>& history) {
  assert(measured_n.size() == plan.samples.size());
  PathHistoryCycle out;
  out.cycle = history.empty() ? 1 : history.back().cycle + 1;
  out.cycle_time_s = plan.summary.cycle_time_s;
  const std::size_t n = plan.samples.size();
  out.feed_mm_per_min.reserve(n);
  out.predicted_n.reserve(n);
  out.measured_n.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PlannedSample& sample = plan.samples[i];
    out.feed_mm_per_min.push_back(tenth(sample.feed_mm_per_min));
    out.predicted_n.push_back(sample.engaged ? tenth(sample.predicted_force_n) : 0.0);
    out.measured_n.push_back(tenth(std::max(measured_n[i], 0.0)));
  }
  return out;
}

std::vector<PathHistoryCycle> with_cycle(std::vector<PathHistoryCycle> history, PathHistoryCycle next) {
  history.push_back(std::move(next));
  if (history.size() > kPathHistoryCycles) {
    history.erase(history.begin(), history.end() - static_cast<std::ptrdiff_t>(kPathHistoryCycles));
  }
  return history;
}

}  // namespace feedplan::planner
