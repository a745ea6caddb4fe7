#include "plan_baselines.hpp"

namespace feedplan::cli {

double time_saved_percent(double baseline_s, double planned_s) {
  return baseline_s > 0.0 ? 100.0 * (baseline_s - planned_s) / baseline_s : 0.0;
}

PlanBaselines plan_baselines(const PlanInputs& in, const PlannedCycle& planned, const std::optional<trial::PlanCheck>& check,
                             const std::string& materials_path) {
  PlanBaselines baselines;
  const std::optional<double>& spec_feed = in.spec.feed_mm_per_min;
  if (spec_feed) {
    baselines.spec_feed = planner::predict_constant_feed(planned.geometry, planned.settings, *spec_feed,
                                                         planned.result.summary.accel_used_mm_per_s2);
  }
  if (!check || !(check->max_peak_n > 0.0)) return baselines;
  const trial::VirtualMachine machine = trial::virtual_machine_for(in.spec, planned.cycle, materials_path);
  std::vector<trial::ConstantFeedRun> known;
  if (spec_feed) {
    baselines.spec_feed_simulated = trial::run_constant_feed(machine, planned.cycle.path, *spec_feed);
    known.push_back(*baselines.spec_feed_simulated);
  }
  baselines.equal_simulated_peak = trial::equal_peak_constant_feed(
      machine, planned.cycle.path, check->max_peak_n, planned.result.summary.baseline.feed_mm_per_min, known);
  return baselines;
}

}  // namespace feedplan::cli
