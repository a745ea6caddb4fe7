#include "feedplan/trial/learning_loop.hpp"

#include <optional>

#include "feedplan/learning/path_correction.hpp"

namespace feedplan::trial {

namespace {

// The virtual machine's share of a cycle's time, roughly: it steps through the whole program, while
// planning and learning pass over it once each.
constexpr double kCutShareOfCycle = 0.85;

}  // namespace

LoopResult run_learning_loop(const LoopRequest& request) {
  if (request.cycles < 1) throw InputError("cycles", "= " + std::to_string(request.cycles) + ": must be ≥ 1");
  LoopResult result;
  planner::PlanSettings settings = request.settings;
  // The first cycle: the starting model's fit covariance and the relative uncertainty of a model not yet
  // checked on this machine; later cycles: the covariance of the model planned with alone (the starting
  // model's while learning along the path, else the refit's).
  std::optional<model::Covariance> covariance;  // of the model learned so far
  double relative = request.first_cut_uncertainty;
  if (request.first_cut_uncertainty > 0.0) covariance = request.start_fit_covariance;
  std::optional<model::Covariance> plan_covariance = covariance;
  std::vector<learning::LearningSample> earlier;
  learning::PathLearning along_path;
  model::ResponseSurfaceModel learned_model = settings.model;
  learning::ModelUpdateOptions update_options = request.update;
  if (request.sensor) {
    update_options.revolutions.sensor_peak_gain = learning::sensor_peak_gains(
        request.geometry.engagement, request.geometry.tool, settings.spindle_rpm, *request.sensor);
  }
  // The cautious bound a plan is made on now: entries off the straight cuts at their worst (force_bound.hpp)
  // until learning along the path has measured a larger factor there (PlanSettings::force_correction).
  const auto bound_now = [&]() -> std::optional<planner::ForceUncertainty> {
    if (!plan_covariance || !(request.first_cut_uncertainty > 0.0)) return std::nullopt;
    return planner::ForceUncertainty{*plan_covariance, request.sigmas, relative, true};
  };
  for (int cycle = 1; cycle <= request.cycles; ++cycle) {
    settings.uncertainty = bound_now();
    const planner::PlanResult plan = planner::plan(request.geometry, settings);
    VirtualMachine machine = request.machine;
    if (request.progress) {
      machine.progress = [&request, cycle](double fraction) {
        request.progress((cycle - 1 + kCutShareOfCycle * fraction) / request.cycles);
      };
    }
    VirtualMachineRun run = run_on_virtual_machine(plan.program, machine, plan, settings.target_force_n);
    if (request.sensor && request.sensor_kernel) {  // the kernel's factor at the feeds this cycle cut
      update_options.revolutions.sensor_peak_gain =
          learning::sensor_peak_gains(request.geometry.engagement, request.geometry.tool, settings.spindle_rpm,
                                      *request.sensor, {&*request.sensor_kernel, planner::sample_feeds_mm_per_min(plan)});
    }

    LoopCycle out;
    out.cycle = cycle;
    out.plan_status = plan.status;
    out.planned_cycle_time_s = plan.summary.cycle_time_s;
    out.simulated_cycle_time_s = run.simulation.summary.cycle_time_s;
    out.comparison = run.comparison;
    out.model_used = settings.model;
    out.messages = plan.messages;

    // The log moves to learning (a copy would double the loop's memory: 0.5 GB for a 9 min cycle).
    std::vector<learning::NamedLog> logs;
    logs.push_back({"cycle " + std::to_string(cycle), std::move(run.simulation.log)});
    // The refit goes on from the model learned so far, whichever model the plan was made with.
    planner::PlanSettings learn_settings = settings;
    learn_settings.model = learned_model;
    const learning::ModelUpdate update = learning::update_model(plan, learn_settings, request.geometry.tool.flutes,
                                                                std::move(logs), earlier, covariance, update_options);
    out.update_status = update.status;
    std::vector<learning::MeasuredRevolutions> measured;
    for (const learning::LogEvidence& log : update.logs) measured.push_back(log.revolutions);
    out.infeasible = learning::infeasible_places(plan, measured, settings.target_force_n);
    out.model_errors_before = update.before;
    out.model_errors_after = update.after_batch;
    out.messages.insert(out.messages.end(), update.messages.begin(), update.messages.end());
    if (update.status == learning::ModelUpdateStatus::kOk) {
      earlier.insert(earlier.end(), update.samples.begin(), update.samples.end());
      learned_model = update.model;
      covariance = update.covariance;
      relative = 0.0;
      if (request.path_correction) {
        // The same program again: its plan keeps its model and learns a correction per place
        // (path_correction.hpp), a fixed knob per place from part to part; the refit is for other programs.
        along_path = learning::learn_along_path(plan, settings.model, measured, settings.target_force_n, along_path);
        settings.force_correction = along_path.correction;
        // The entry first: it numbers itself after the history, which with_cycle then takes.
        planner::PathHistoryCycle entry = planner::history_cycle(plan, along_path.step_force_n, result.history);
        result.history = planner::with_cycle(std::move(result.history), std::move(entry));
      } else {
        settings.model = learned_model;
        plan_covariance = covariance;
      }
    }
    result.cycles.push_back(std::move(out));
    if (request.on_cycle_done) request.on_cycle_done(cycle);
    if (request.progress) request.progress(static_cast<double>(cycle) / request.cycles);
  }
  result.final_model = learned_model;
  result.next_settings = settings;
  result.next_settings.uncertainty = bound_now();
  if (covariance) result.final_covariance = *covariance;
  return result;
}

}  // namespace feedplan::trial
