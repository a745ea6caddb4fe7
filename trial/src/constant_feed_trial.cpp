#include "feedplan/trial/constant_feed_trial.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <optional>

#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::trial {
namespace {

// Peak ∝ F^k before two runs give the slope: a per-revolution peak is about affine in the chip (seed
// 003 Eq. 1 at fixed engagement), so k < 1; 0.75 undershoots the step rather than overshoots it.
constexpr double kAssumedPeakExponent = 0.75;

// The runs below and above the peak sought that lie closest to it.
struct Bracket {
  std::optional<ConstantFeedRun> below;  // peak < sought, the largest such feed
  std::optional<ConstantFeedRun> above;  // peak ≥ sought, the smallest such feed
  void add(const ConstantFeedRun& r, double peak_n) {
    if (r.max_peak_n < peak_n) {
      if (!below || r.feed_mm_per_min > below->feed_mm_per_min) below = r;
    } else if (!above || r.feed_mm_per_min < above->feed_mm_per_min) {
      above = r;
    }
  }
};

// The feed F·(peak / p)^(1/k), with k the log-log slope between two runs (the assumed one when it is
// not positive or the runs coincide).
double secant_feed(const ConstantFeedRun& a, const ConstantFeedRun& b, double peak_n) {
  double k = kAssumedPeakExponent;
  if (a.feed_mm_per_min != b.feed_mm_per_min && a.max_peak_n > 0.0 && b.max_peak_n > 0.0) {
    const double slope = std::log(b.max_peak_n / a.max_peak_n) / std::log(b.feed_mm_per_min / a.feed_mm_per_min);
    if (std::isfinite(slope) && slope > 0.05) k = slope;
  }
  return b.feed_mm_per_min * std::pow(peak_n / std::max(b.max_peak_n, 1e-9), 1.0 / k);
}

// The next feed to run: the secant through the bracket (or the last two runs), kept strictly inside it.
double next_feed(const std::vector<ConstantFeedRun>& runs, const Bracket& bracket, double peak_n) {
  if (bracket.below && bracket.above) {
    const double lo = bracket.below->feed_mm_per_min;
    const double hi = bracket.above->feed_mm_per_min;
    const double feed = secant_feed(*bracket.below, *bracket.above, peak_n);
    const double margin = 0.02 * (hi - lo);
    return feed > lo + margin && feed < hi - margin ? feed : std::sqrt(lo * hi);
  }
  const ConstantFeedRun& last = runs.back();
  return secant_feed(runs.size() >= 2 ? runs[runs.size() - 2] : last, last, peak_n);
}

bool within_tolerance(const ConstantFeedRun& r, double peak_n) {
  return std::abs(r.max_peak_n - peak_n) <= kEqualPeakTolerance * peak_n;
}

const ConstantFeedRun& closest_run(const std::vector<ConstantFeedRun>& runs, double peak_n) {
  return *std::min_element(runs.begin(), runs.end(), [peak_n](const ConstantFeedRun& a, const ConstantFeedRun& b) {
    return std::abs(a.max_peak_n - peak_n) < std::abs(b.max_peak_n - peak_n);
  });
}

std::string method_text(const EqualPeakFeed& found, int made, bool at_range_end, double peak_n) {
  char text[320];
  if (at_range_end) {
    std::snprintf(text, sizeof text,
                  "the machine's feed range ends at F%.0f, where the constant feed peaks at %.1f N (sought %.1f N; "
                  "%d runs on the virtual machine)",
                  found.run.feed_mm_per_min, found.run.max_peak_n, peak_n, made);
  } else {
    std::snprintf(text, sizeof text,
                  "found in %d runs of the constant-feed program on the virtual machine by a secant search on log peak "
                  "vs log F; %s within %.0f %% of %.1f N",
                  made, found.converged ? "its peak is" : "its peak is NOT", 100.0 * kEqualPeakTolerance, peak_n);
  }
  return text;
}

}  // namespace

ConstantFeedRun run_constant_feed(const VirtualMachine& machine, const geometry::ToolPath& path, double feed_mm_per_min) {
  VirtualMachine quiet = machine;  // a baseline run: peaks and time only, no log rows, no progress of its own
  quiet.keep_log = false;
  quiet.progress = nullptr;
  const sim::SimulationResult result =
      simulate_on(planner::constant_feed_program(path, feed_mm_per_min, machine.spindle_rpm), quiet);
  return {feed_mm_per_min, result.summary.cycle_time_s, result.summary.max_revolution_peak_n};
}

EqualPeakFeed equal_peak_constant_feed(const VirtualMachine& machine, const geometry::ToolPath& path, double peak_n,
                                       double start_feed_mm_per_min, const std::vector<ConstantFeedRun>& known) {
  assert(peak_n > 0.0);
  const double min_feed = machine.machine.min_feed_mm_per_min;
  const double max_feed = machine.machine.max_feed_mm_per_min;
  EqualPeakFeed found;
  found.runs = known;
  Bracket bracket;
  for (const ConstantFeedRun& r : known) bracket.add(r, peak_n);
  double feed = known.empty() ? start_feed_mm_per_min : next_feed(found.runs, bracket, peak_n);
  int made = 0;
  bool at_range_end = false;
  while (found.runs.empty() || (!within_tolerance(closest_run(found.runs, peak_n), peak_n) && made < kEqualPeakMaxRuns)) {
    feed = std::clamp(feed, min_feed, max_feed);
    const ConstantFeedRun r = run_constant_feed(machine, path, feed);
    ++made;
    found.runs.push_back(r);
    bracket.add(r, peak_n);
    if ((r.max_peak_n < peak_n && feed >= max_feed) || (r.max_peak_n > peak_n && feed <= min_feed)) {
      at_range_end = !within_tolerance(r, peak_n);
      break;
    }
    feed = next_feed(found.runs, bracket, peak_n);
  }
  found.run = at_range_end ? found.runs.back() : closest_run(found.runs, peak_n);
  found.converged = within_tolerance(found.run, peak_n);
  found.method = method_text(found, static_cast<int>(found.runs.size()), at_range_end, peak_n);
  return found;
}

}  // namespace feedplan::trial
