#include "feedplan/trial/best_achievable_plan.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/trial/correction_step.hpp"

namespace feedplan::trial {
namespace {

//! Per sample, the largest true peak over the target among the in-cut revolutions whose span holds it (0:
//! none), and whether every such revolution was force-limited (a faster plan could run it faster).
struct SampleEvidence {
  double ratio = 0.0;
  bool force_limited = true;
};

std::vector<SampleEvidence> evidence(const planner::PlanResult& plan, const planner::PeakComparison& comparison,
                                     double target_force_n) {
  const auto& samples = plan.samples;
  std::vector<SampleEvidence> out(samples.size());
  for (const planner::RevolutionComparison& r : comparison.revolutions) {
    if (!r.in_cut) continue;
    // An overshoot is also given to the revolution's length before it: where the force rises along the path
    // the next plan, slower there, puts a revolution boundary elsewhere, and the place that needs the slower
    // feed may then lie in the revolution before.
    const double ratio = r.revolution.peak_n / target_force_n;
    const double reach_mm = ratio > 1.0 ? r.revolution.s_end_mm - r.revolution.s_start_mm : 0.0;
    const auto first = std::lower_bound(samples.begin(), samples.end(), r.revolution.s_start_mm - reach_mm,
                                        [](const planner::PlannedSample& p, double s) { return p.s_mm < s; });
    for (auto it = first; it != samples.end() && it->s_mm <= r.revolution.s_end_mm; ++it) {
      if (!it->engaged) continue;
      SampleEvidence& e = out[static_cast<std::size_t>(it - samples.begin())];
      const bool own = it->s_mm >= r.revolution.s_start_mm;
      e.ratio = std::max(e.ratio, own ? ratio : std::max(ratio, 1.0));
      if (own) e.force_limited = e.force_limited && r.force_limited;
    }
  }
  return out;
}

//! `value` strictly inside (lo, hi): their geometric middle when it is not (lo may be 0, hi infinite).
double inside(double value, double lo, double hi) {
  if (value > lo && value < hi) return value;
  if (std::isfinite(hi) && lo > 0.0) return std::sqrt(lo * hi);
  return value <= lo ? lo * 1.5 : hi / 1.5;
}

//! True when the cycle times of the last kStallPlans plans differ by less than kStallTimeShare.
bool stalled(const std::vector<BestPlanIteration>& iterations) {
  if (iterations.size() < static_cast<std::size_t>(kStallPlans)) return false;
  double shortest = INFINITY, longest = 0.0;
  for (auto it = iterations.end() - kStallPlans; it != iterations.end(); ++it) {
    shortest = std::min(shortest, it->cycle_time_s);
    longest = std::max(longest, it->cycle_time_s);
  }
  return longest - shortest < kStallTimeShare * shortest;
}

}  // namespace

planner::PlanSettings planned_with_own_physics(const planner::PlanSettings& settings, const VirtualMachine& machine) {
  planner::PlanSettings out = settings;
  out.mechanistic = own_physics(machine);
  out.uncertainty.reset();
  out.force_correction.clear();
  if (!settings.mechanistic) out.options.max_chip_thickness_mm = settings.model.range.chip_max_mm;
  return out;
}

BestPlan best_achievable_plan(const BestPlanRequest& request) {
  if (request.max_iterations < 1) {
    throw InputError("max_iterations", "= " + std::to_string(request.max_iterations) + ": must be ≥ 1");
  }
  if (!(request.tolerance > 0.0 && request.tolerance < 0.5)) {
    throw InputError("tolerance", "= " + shortest_number_text(request.tolerance) + ": must be in (0, 0.5)");
  }
  planner::PlanSettings settings = planned_with_own_physics(request.settings, request.machine);
  // One correction per plan sample (every plan of the geometry has the same samples).
  const std::size_t n = planner::plan(request.geometry, settings).samples.size();
  std::vector<double> c(n, 1.0);
  std::vector<double> lo(n, 0.0), hi(n, INFINITY);
  std::vector<CorrectionTry> previous(n);
  VirtualMachine machine = request.machine;
  machine.keep_log = false;
  BestPlan best;
  const double target_n = settings.target_force_n;
  bool settled = false;  // the search settled (file comment)
  for (int iteration = 0; iteration < request.max_iterations; ++iteration) {
    settings.force_correction = c;
    const planner::PlanResult plan = planner::plan(request.geometry, settings);
    const VirtualMachineRun run = run_on_virtual_machine(plan.program, machine, plan, target_n);
    const std::vector<SampleEvidence> seen = evidence(plan, run.comparison, target_n);

    BestPlanIteration it;
    it.cycle_time_s = run.simulation.summary.cycle_time_s;
    it.held_max_abs_error_percent = run.comparison.max_abs_error_percent;
    it.steady_max_abs_error_percent = run.comparison.steady_max_abs_error_percent;
    it.held_rms_error_percent = run.comparison.rms_error_percent;
    int infeasible = 0;
    bool all_met = true;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = seen[i].ratio;
      if (!(r > 0.0)) continue;
      const bool at_min_feed = plan.samples[i].limit_reason == planner::FeedLimitReason::kMinFeed;
      if (r > 1.0 + request.tolerance && at_min_feed) {
        ++infeasible;
        continue;
      }
      it.max_overshoot_percent = std::max(it.max_overshoot_percent, 100.0 * (r - 1.0));
      const CorrectionTry now{c[i], r};
      if (r > 1.0 + request.tolerance) {
        all_met = false;
        lo[i] = std::max(lo[i], c[i]);
        c[i] = inside(next_force_correction(c[i], r, previous[i]), lo[i], hi[i]);
      } else if (r < 1.0 - request.tolerance && seen[i].force_limited) {
        all_met = false;
        hi[i] = std::min(hi[i], c[i]);
        c[i] = inside(next_force_correction(c[i], r, previous[i]), lo[i], hi[i]);
      }
      previous[i] = now;
      c[i] = std::clamp(c[i], planner::kMinForceCorrection, planner::kMaxForceCorrection);
    }
    best.iterations.push_back(it);
    best.infeasible_samples = infeasible;
    if (it.max_overshoot_percent <= 100.0 * request.tolerance &&
        (best.best_iteration < 0 || it.cycle_time_s < best.best_cycle_time_s)) {
      best.best_cycle_time_s = it.cycle_time_s;
      best.best_iteration = iteration;
      best.force_correction = settings.force_correction;
    }
    if (all_met) {
      best.converged = true;
      break;
    }
    if (stalled(best.iterations) && it.max_overshoot_percent <= 100.0 * kMaxSettledOvershoot) {
      settled = true;
      break;
    }
  }
  const BestPlanIteration& last = best.iterations.back();
  if (best.best_iteration < 0 && (best.converged || settled)) {
    best.best_cycle_time_s = last.cycle_time_s;
    best.best_iteration = static_cast<int>(best.iterations.size()) - 1;
    best.force_correction = settings.force_correction;
  }
  if (best.best_iteration < 0) best.force_correction = c;
  return best;
}

}  // namespace feedplan::trial
