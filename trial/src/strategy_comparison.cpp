#include "feedplan/trial/strategy_comparison.hpp"

#include <cmath>
#include <exception>
#include <future>
#include <mutex>
#include <utility>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/parallel_tasks.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/trial/controlled_run.hpp"

namespace feedplan::trial {

namespace {

// The rows' work in units of one run of the program on the virtual machine: a learning cycle (cut, then
// learn from the full log) costs about three.
constexpr double kLearningCycleRuns = 3.0;

// Progress over the rows, reported one call at a time whichever thread finished a part.
class ComparisonProgress {
 public:
  ComparisonProgress(const std::function<void(double)>& report, double total_runs) : report_(report), total_(total_runs) {}
  void done(double runs) {
    if (!report_) return;
    const std::lock_guard lock(mutex_);
    done_ += runs;
    report_(std::min(1.0, done_ / total_));
  }

 private:
  const std::function<void(double)>& report_;
  double total_;
  double done_ = 0.0;
  std::mutex mutex_;
};

geometry::Program received(const ComparisonRequest& request, const geometry::Program& program) {
  return request.as_received ? request.as_received(program) : program;
}

// The machine every row runs on, without a log kept or a controller.
VirtualMachine row_machine(const ComparisonRequest& request) {
  VirtualMachine machine = request.machine;
  machine.keep_log = false;
  machine.log_sink = nullptr;
  machine.override_loop = {};
  machine.progress = {};
  return machine;
}

// A program run alone (constant feed, a plan) and judged.
StrategyRow run_alone(const geometry::Program& program, const VirtualMachine& machine, double target_force_n) {
  sim::SimulationResult simulation = simulate_on(program, machine);
  StrategyRow row;
  row.judgement = judge_control(simulation.revolutions, target_force_n, simulation.summary.cycle_time_s);
  row.revolutions = std::move(simulation.revolutions);
  row.warnings = std::move(simulation.warnings);
  return row;
}

// A program run under `controller` on the dynamometer, with the override bounds of `settings`.
StrategyRow run_controlled(const geometry::Program& program, const VirtualMachine& machine,
                           OverrideControlSettings settings, ControllerKind controller) {
  ControllerSettings law;
  law.kind = controller;
  law.target_force_n = settings.target_force_n;
  law.max_ratio = settings.max_ratio;
  law.min_ratio = settings.min_ratio;
  law.spindle_rpm = machine.spindle_rpm;
  law.flutes = machine.tool.flutes;
  ControlledRun run = run_under_control(program, machine, settings, make_control_law(law));
  StrategyRow row;
  row.controller = controller;
  row.judgement = run.judgement;
  for (const ControlStep& step : run.trace.steps) row.controller_steps += step.in_cut ? 1 : 0;
  row.revolutions = std::move(run.simulation.revolutions);
  row.warnings = std::move(run.simulation.warnings);
  return row;
}

// The sensor every controller here reads: the dynamometer's per-revolution peak |F_xy|.
ForceSensorSettings dynamometer_sensor(const geometry::Tool& tool) {
  ForceSensorSettings sensor;
  sensor.sensor = ForceSensor::kDynamometer;
  sensor.tool_radius_mm = tool.radius_mm();
  return sensor;
}

// A plan's row: the plan's program as received, run alone.
StrategyRow plan_row(const ComparisonRequest& request, const planner::PlanResult& plan, int cycle,
                     const geometry::Program& program, const VirtualMachine& machine) {
  StrategyRow row = run_alone(program, machine, request.settings.target_force_n);
  row.kind = StrategyKind::kFeedForward;
  row.plan_cycle = cycle;
  row.planned_cycle_time_s = plan.summary.cycle_time_s;
  row.plan_status = plan.status;
  row.name = cycle == 1 ? "feed-forward, cycle 1 (the model's plan)"
                        : "feed-forward after learning, cycle " + std::to_string(cycle);
  return row;
}

// The robust servo trimming a plan's program.
StrategyRow hybrid_row(const ComparisonRequest& request, const planner::PlanResult& plan, int cycle,
                       const geometry::Program& program, const VirtualMachine& machine) {
  const OverrideControlSettings settings =
      hybrid_override_settings(dynamometer_sensor(machine.tool), request.settings.target_force_n);
  StrategyRow row = run_controlled(program, machine, settings, ControllerKind::kRobustServo);
  row.kind = StrategyKind::kHybrid;
  row.plan_cycle = cycle;
  row.planned_cycle_time_s = plan.summary.cycle_time_s;
  row.plan_status = plan.status;
  row.name = "hybrid: cycle-" + std::to_string(cycle) + " plan + robust-servo";
  return row;
}

// The loop's cycles 1 … N − 1 from the cycle-1 settings, as `feedplan loop` runs them; the settings the
// loop would plan cycle N with.
LoopResult learn_before(const ComparisonRequest& request, ComparisonProgress& progress) {
  LoopRequest loop;
  loop.geometry = request.geometry;
  loop.settings = request.learning_settings.value_or(request.settings);
  loop.machine = request.machine;
  loop.machine.keep_log = true;  // learning reads the log
  loop.machine.log_sink = nullptr;
  loop.machine.override_loop = {};
  loop.machine.progress = {};
  loop.cycles = request.learning_cycles - 1;
  loop.first_cut_uncertainty = request.first_cut_uncertainty;
  loop.sigmas = request.sigmas;
  loop.start_fit_covariance = request.start_fit_covariance;
  loop.on_cycle_done = [&progress](int) { progress.done(kLearningCycleRuns); };
  return run_learning_loop(loop);
}

}  // namespace

std::string_view to_string(StrategyKind kind) {
  switch (kind) {
    case StrategyKind::kConstantFeed: return "constant-feed";
    case StrategyKind::kFeedForward: return "feed-forward";
    case StrategyKind::kFeedback: return "feedback";
    case StrategyKind::kHybrid: return "hybrid";
  }
  return "";
}

std::vector<ControllerKind> all_controllers() {
  return {ControllerKind::kIntegral,       ControllerKind::kVariableGain, ControllerKind::kVariableGainLathe,
          ControllerKind::kRobustServo,    ControllerKind::kModelReference, ControllerKind::kMultiModel1,
          ControllerKind::kMultiModel2};
}

std::vector<InputProblem> validate(const ComparisonRequest& request, const std::string& field_prefix) {
  std::vector<InputProblem> problems;
  if (!(std::isfinite(request.constant_feed_mm_per_min) && request.constant_feed_mm_per_min > 0.0)) {
    problems.push_back({field_prefix + "constant_feed_mm_per_min",
                        "= " + shortest_number_text(request.constant_feed_mm_per_min) + ": must be finite and > 0 mm/min"});
  }
  if (request.learning_cycles < 2) {
    problems.push_back({field_prefix + "learning_cycles", "= " + std::to_string(request.learning_cycles) +
                                                              ": must be ≥ 2 (cycle 1 is the model's plan, not learned)"});
  }
  if (!(std::isfinite(request.settings.target_force_n) && request.settings.target_force_n > 0.0)) {
    problems.push_back({field_prefix + "settings.target_force_n",
                        "= " + shortest_number_text(request.settings.target_force_n) + ": must be finite and > 0 N"});
  }
  return problems;
}

StrategyComparison compare_strategies(const ComparisonRequest& request) {
  if (std::vector<InputProblem> problems = validate(request); !problems.empty()) throw InputError(std::move(problems));
  const double target_n = request.settings.target_force_n;
  const VirtualMachine machine = row_machine(request);
  const planner::PlanResult first_plan = planner::plan(request.geometry, request.settings);
  const geometry::Program first_program = received(request, first_plan.program);
  const geometry::Program constant_program = received(
      request, planner::constant_feed_program(request.geometry.path, request.constant_feed_mm_per_min,
                                              request.settings.spindle_rpm));

  const std::size_t controllers = request.controllers.size();
  // Rows: constant feed, cycle 1, cycle N, the controllers, the hybrid on cycle 1, the hybrid on cycle N.
  std::vector<StrategyRow> rows(5 + controllers);
  StrategyComparison out;
  const double learning_runs = kLearningCycleRuns * (request.learning_cycles - 1) + (request.hybrid_on_learned ? 2.0 : 1.0);
  ComparisonProgress progress(request.progress, learning_runs + 3.0 + static_cast<double>(controllers));

  // Task 0, the longest, first: the loop, and the plan it would cut as cycle N. The last tasks run that plan
  // alone and trimmed, waiting for it: tasks are taken in order, so task 0 has started (and on one thread,
  // finished) before any of them waits.
  struct LearnedPlan {
    planner::PlanResult plan;
    geometry::Program program;
  };
  std::promise<LearnedPlan> learned_promise;
  const std::shared_future<LearnedPlan> learned = learned_promise.get_future().share();
  const auto learn = [&] {
    try {
      const LoopResult loop = learn_before(request, progress);
      LearnedPlan next;
      next.plan = planner::plan(request.geometry, loop.next_settings);
      next.program = received(request, next.plan.program);
      out.learning = loop.cycles;
      learned_promise.set_value(std::move(next));
    } catch (...) {
      learned_promise.set_exception(std::current_exception());
      throw;
    }
  };
  const std::size_t first_learned_task = 3 + controllers;
  const std::size_t tasks = first_learned_task + (request.hybrid_on_learned ? 2 : 1);
  run_tasks(tasks, [&](std::size_t task) {
    if (task == 0) {
      learn();
      return;
    }
    if (task == 1) {
      rows[0] = run_alone(constant_program, machine, target_n);
      rows[0].kind = StrategyKind::kConstantFeed;
      rows[0].name = "constant feed " + shortest_number_text(request.constant_feed_mm_per_min) + " mm/min";
    } else if (task == 2) {
      rows[1] = plan_row(request, first_plan, 1, first_program, machine);
      rows[3 + controllers] = hybrid_row(request, first_plan, 1, first_program, machine);
      progress.done(1.0);
    } else if (task < first_learned_task) {
      const ControllerKind controller = request.controllers[task - 3];
      OverrideControlSettings settings;
      settings.sensor = dynamometer_sensor(machine.tool);
      settings.target_force_n = target_n;
      StrategyRow row = run_controlled(constant_program, machine, settings, controller);
      row.kind = StrategyKind::kFeedback;
      row.name = "feedback alone: ";
      row.name += to_string(controller);
      rows[task] = std::move(row);
    } else if (task == first_learned_task) {
      const LearnedPlan& next = learned.get();
      rows[2] = plan_row(request, next.plan, request.learning_cycles, next.program, machine);
    } else {
      const LearnedPlan& next = learned.get();
      rows[4 + controllers] = hybrid_row(request, next.plan, request.learning_cycles, next.program, machine);
    }
    progress.done(1.0);
  });
  if (!request.hybrid_on_learned) rows.pop_back();
  out.target_force_n = target_n;
  out.constant_feed_mm_per_min = request.constant_feed_mm_per_min;
  out.learning_cycles = request.learning_cycles;
  out.rows = std::move(rows);
  return out;
}

}  // namespace feedplan::trial
