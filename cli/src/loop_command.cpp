#include "loop_command.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <unistd.h>

#include "data_path.hpp"
#include "database_path.hpp"
#include "model_choice.hpp"
#include "number_flag.hpp"
#include "output_path.hpp"
#include "progress_bar.hpp"
#include "feedplan/learning/infeasible_places.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "output_files.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/trial/learning_loop.hpp"
#include "feedplan/planner/path_history_plot.hpp"
#include "feedplan/planner/revolution_table.hpp"
#include "feedplan/report/plan_page.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/material.hpp"

namespace feedplan::cli {

void add_loop_command(CLI::App& app, LoopOptions& options) {
  auto* cmd = app.add_subcommand(
      "loop",
      "Plan → cut on the virtual machine → learn from its force log → re-plan, N times, from a model that is\n"
      "deliberately wrong for the machine; prints the per-revolution force error and cycle time per cycle");
  cmd->add_option("spec", options.spec_path, "Cycle spec (YAML)")->required();
  add_integer_flag(cmd, "--cycles", options.cycles, "Repetitions (default 3)");
  cmd->add_option("--db", options.db_path, "Model database (default: $FEEDPLAN_DB, else the bundled sample database)");
  add_number_flag(cmd, "--machine-scale", options.machine_scale,
                  "The virtual machine's cutting coefficients × this: its forces ≈ this × the model's (default 1.4)");
  cmd->add_option("--machine", options.machine_path,
                  "Machine file (data/machines/*.yaml) to cut on instead of the spec's material × --machine-scale;\n"
                  "conflicts with --machine-scale");
  add_number_flag(cmd, "--target-force", options.target_force_n, "Per-revolution peak force to hold, N (default: the spec's)");
  add_number_flag(cmd, "--cautious", options.cautious,
                  "Cautious first cut: plan on F̂ + z·σ with this relative uncertainty of the starting model (e.g. 0.25;\n"
                  "0: off; default: from how far the model is borrowed, off for an exact one)");
  add_number_flag(cmd, "--sigmas", options.sigmas, "z of the cautious bound (default 2)");
  add_integer_flag(cmd, "--model-id", options.model_id, "Start from this model instead of the closest");
  cmd->add_option("--materials", options.materials_path, "Materials file of the virtual machine (default: the bundled one)");
  cmd->add_flag("--json", options.json, "Print the table as JSON");
  cmd->add_option("--revolutions", options.revolutions_path,
                  "Also write every cycle's simulated revolutions (s span, place, peak, planned force, error) as CSV");
  add_sensor_flags(cmd, options.sensor);
  cmd->add_option("--html", options.html_path,
                  "Write the learning history (every cycle's peak error, cycle time and curves) and the next plan as one\n"
                  "self-contained HTML file");
  cmd->add_option("--plot", options.plot_path,
                  "Also write the learning history (SVG): the force measured and the feed planned along the path in\n"
                  "every cycle (the newest 8), and the plan for the next part");
}

namespace {

// One row per simulated revolution of every cycle: where the error is, not only how large.
std::string revolutions_csv(const trial::LoopResult& result, double target_force_n) {
  std::string text = planner::revolution_table_header();
  for (const auto& c : result.cycles) text += planner::revolution_table_rows(std::to_string(c.cycle), c.comparison, target_force_n);
  return text;
}

// The virtual machine's forces over the material's without --machine.
double machine_scale(const LoopOptions& o) { return o.machine_scale.value_or(1.4); }

// The spec and the target, every flag checked.
struct LoopInputs {
  cycles::CycleSpec spec;       // the cycle spec
  double target_force_n = 0.0;  // --target-force, else the spec's, N
  double cautious = 0.0;        // r of the first cut's bound: --cautious, else from the borrowing (set with the model)
  std::optional<learning::SensorDynamics> sensor;  // --sensor-hz, --sensor-damping
};

LoopInputs read_loop_inputs(const LoopOptions& o) {
  LoopInputs in;
  in.sensor = sensor_dynamics(o.sensor);
  in.spec = cycles::load_cycle_spec(o.spec_path);
  const cycles::CycleSpec& spec = in.spec;
  std::vector<InputProblem> problems;
  if (!(o.cycles >= 1 && o.cycles <= 100)) problems.push_back({"--cycles", "= " + std::to_string(o.cycles) + ": must be in [1, 100]"});
  if (o.machine_scale && !o.machine_path.empty()) {
    problems.push_back({"--machine-scale", "conflicts with --machine " + o.machine_path +
                                               ", which sets the machine's physics; give one of them"});
  }
  if (const double scale = machine_scale(o); !(std::isfinite(scale) && scale > 0.1 && scale < 10.0)) {
    problems.push_back({"--machine-scale", "= " + shortest_number_text(scale) + ": must be in (0.1, 10)"});
  }
  check_flag(problems, "--cautious", o.cautious, {0.0, true, 2.0, true}, "a relative uncertainty (0: off)");
  check_flag(problems, "--sigmas", o.sigmas, {0.0, true, 10.0, true});
  check_flag(problems, "--target-force", o.target_force_n, {0.0, false}, "the per-revolution peak force to hold, N");
  if (o.model_id && *o.model_id < 1) {
    problems.push_back({"--model-id", "= " + std::to_string(*o.model_id) + ": must be ≥ 1 (see feedplan db list)"});
  }
  in.target_force_n = o.target_force_n.value_or(spec.target_force_n);
  if (!o.target_force_n && !(spec.target_force_n > 0.0)) {
    problems.push_back({"target_force_n", "is not in the spec: a target force > 0 N is required (in the spec or with "
                                          "--target-force)"});
  }
  if (!(spec.spindle_rpm > 0.0)) problems.push_back({"spindle_rpm", "is required (rev/min > 0)"});
  check_outputs({{"SPEC", o.spec_path},
                 {"--db", database_path(o.db_path)},
                 {"--machine", o.machine_path},
                 {"--materials", o.materials_path.empty() ? bundled_materials_path() : o.materials_path}},
                {{"--revolutions", o.revolutions_path}, {"--plot", o.plot_path}, {"--html", o.html_path}}, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return in;
}

// The plan side (engagement, model, target, machine) and the virtual machine (the material's cutting
// coefficients × --machine-scale).
trial::LoopRequest loop_request(const LoopOptions& o, const LoopInputs& in, const ChosenModel& chosen,
                                const std::optional<model::MechanisticModel>& kernel) {
  const cycles::CycleSpec& spec = in.spec;
  const sim::MaterialLibrary materials =
      sim::load_materials(o.materials_path.empty() ? bundled_materials_path() : o.materials_path);
  const cycles::Cycle cycle = cycles::generate(spec);
  trial::LoopRequest request;
  request.geometry = planner::analyse(cycle.path, cycle.stock, spec.tool);
  request.settings.model = chosen.record.model;
  request.settings.target_force_n = in.target_force_n;
  request.settings.spindle_rpm = spec.spindle_rpm;
  request.settings.machine = spec.machine;
  request.machine.tool = spec.tool;
  if (o.machine_path.empty()) {
    request.machine.coefficients = sim::scaled(materials.get(spec.material, "material").coefficients, machine_scale(o));
  } else {
    // The machine file's physics on the spec's catalogue tool (its helix moved by the file's offset).
    trial::use_machine_file(request.machine, sim::load_machine_file(o.machine_path, materials), spec.tool);
  }
  request.machine.stock = cycle.stock;
  request.machine.machine = spec.machine;
  request.machine.spindle_rpm = spec.spindle_rpm;
  request.cycles = o.cycles;
  request.first_cut_uncertainty = in.cautious;
  request.sigmas = o.sigmas;
  request.start_fit_covariance = chosen.record.fit.covariance;
  request.sensor = in.sensor;
  if (in.sensor) request.sensor_kernel = kernel;
  return request;
}

// Runs the loop with a progress bar on a terminal.
trial::LoopResult run_loop_with_progress(trial::LoopRequest request, int cycles) {
  ProgressBar progress(std::to_string(cycles) + (cycles == 1 ? " cycle" : " cycles") +
                       " of plan, cut on the virtual machine, learn");
  request.progress = [&progress](double fraction) { progress(fraction); };
  return trial::run_learning_loop(request);
}

void print_loop_json(const LoopOptions& o, const LoopInputs& in, const ChosenModel& chosen, const trial::LoopResult& result) {
  nlohmann::json out;
  out["spec"] = o.spec_path;
  out["target_force_n"] = in.target_force_n;
  if (o.machine_path.empty()) {
    out["machine_scale"] = machine_scale(o);
  } else {
    out["machine"] = o.machine_path;
  }
  out["cautious"] = in.cautious;
  out["start_model"] = {{"id", chosen.record.id}, {"version", chosen.record.version},
                        {"match_status", model_db::to_string(chosen.borrowing.status)},
                        {"match", model_db::describe(chosen.borrowing)}};
  out["cycles"] = nlohmann::json::array();
  for (const auto& c : result.cycles) {
    out["cycles"].push_back({{"cycle", c.cycle},
                             {"plan_status", planner::to_string(c.plan_status)},
                             {"planned_cycle_time_s", c.planned_cycle_time_s},
                             {"simulated_cycle_time_s", c.simulated_cycle_time_s},
                             {"steady", c.comparison.steady},
                             {"steady_max_abs_error_percent", c.comparison.steady_max_abs_error_percent},
                             {"steady_rms_error_percent", c.comparison.steady_rms_error_percent},
                             {"held", c.comparison.held},
                             {"held_max_abs_error_percent", c.comparison.max_abs_error_percent},
                             {"held_rms_error_percent", c.comparison.rms_error_percent},
                             {"max_overshoot_percent", c.comparison.max_overshoot_percent},
                             {"model_rms_error_before_percent", c.model_errors_before.rms_percent},
                             {"model_rms_error_after_percent", c.model_errors_after.rms_percent},
                             {"learned", learning::to_string(c.update_status)},
                             {"infeasible_revolutions", c.infeasible.revolutions},
                             {"infeasible_largest_peak_n", c.infeasible.largest_peak_n},
                             {"messages", c.messages}});
  }
  std::cout << out.dump(2) << "\n";
}

// The learning history of the loop and the plan of the part after its last cycle (path_history_plot.hpp).
std::string history_plot(const trial::LoopRequest& request, const trial::LoopResult& result, const LoopInputs& in) {
  const planner::PlanResult next = planner::plan(request.geometry, result.next_settings);
  std::vector<double> s_mm;
  for (const auto& sample : next.samples) s_mm.push_back(sample.s_mm);
  planner::PathHistoryPlotOptions plot;
  plot.title = in.spec.cycle + " on the virtual machine: learning along the path, " +
               std::to_string(result.cycles.size()) + (result.cycles.size() == 1 ? " cycle" : " cycles") +
               " (newest darkest) and the next plan";
  plot.next = &next;
  return planner::path_history_svg(s_mm, result.history, in.target_force_n, plot);
}

// The learning history of the loop, every cycle's figures, and the plan of the part after its last cycle.
std::string history_html(const LoopOptions& o, const trial::LoopRequest& request, const trial::LoopResult& result,
                         const LoopInputs& in, const ChosenModel& chosen) {
  const planner::PlanResult next = planner::plan(request.geometry, result.next_settings);
  report::PlanPage page;
  page.title = in.spec.cycle + " on the virtual machine: learning along the path, " + std::to_string(result.cycles.size()) +
               (result.cycles.size() == 1 ? " cycle" : " cycles") + ", and the next plan";
  page.summary.emplace_back("spec", o.spec_path);
  page.summary.emplace_back("virtual machine", o.machine_path.empty() ? "forces × " + shortest_number_text(machine_scale(o)) +
                                                                           " of the material's"
                                                                     : o.machine_path);
  page.summary.emplace_back("start model", "id " + std::to_string(chosen.record.id) + " v" +
                                               std::to_string(chosen.record.version) + ": " +
                                               model_db::describe(chosen.borrowing));
  for (report::SummaryLine& line : report::plan_summary_lines(next, result.next_settings)) {
    line.first = "next plan: " + line.first;
    page.summary.push_back(std::move(line));
  }
  if (in.cautious > 0.0) {
    page.notes.push_back("cautious first cut: F̂ + " + shortest_number_text(o.sigmas) + "σ held at the target (r = " +
                         shortest_number_text(in.cautious) + ")");
  }
  const trial::LoopCycle& last = result.cycles.back();
  if (const std::string text = learning::describe(last.infeasible, in.target_force_n); !text.empty()) {
    page.notes.push_back("cycle " + std::to_string(last.cycle) + ": " + text);
  }
  for (const trial::LoopCycle& c : result.cycles) {
    for (const std::string& message : c.messages) page.notes.push_back("cycle " + std::to_string(c.cycle) + ": " + message);
  }
  for (const std::string& message : next.messages) page.notes.push_back("next plan: " + message);
  page.history = result.history;
  if (!result.history.empty()) page.measured_peak_n = result.history.back().measured_n;
  page.cycle_table.columns = {"cycle", "plan [s]", "virtual machine [s]", "held revolutions", "held max |error| [%]",
                              "held RMS error [%]", "largest overshoot [%]", "model p95 before → after [%]"};
  for (const trial::LoopCycle& c : result.cycles) {
    page.cycle_table.rows.push_back({std::to_string(c.cycle), fixed_number_text(c.planned_cycle_time_s, 2),
                                     fixed_number_text(c.simulated_cycle_time_s, 2), std::to_string(c.comparison.held),
                                     fixed_number_text(c.comparison.max_abs_error_percent, 2),
                                     fixed_number_text(c.comparison.rms_error_percent, 2),
                                     fixed_number_text(c.comparison.max_overshoot_percent, 2),
                                     fixed_number_text(c.model_errors_before.p95_abs_percent, 1) + " → " +
                                         fixed_number_text(c.model_errors_after.p95_abs_percent, 1)});
  }
  return report::plan_page_html(next, result.next_settings, page);
}

void print_loop_text(const LoopOptions& o, const LoopInputs& in, const ChosenModel& chosen, const trial::LoopResult& result) {
  const std::string machine = o.machine_path.empty()
                                  ? "virtual machine forces × " + shortest_number_text(machine_scale(o)) + " of the material's"
                                  : "virtual machine " + o.machine_path;
  std::printf("%s: %s, target %s N, %s, start model id %lld v%d%s\n", o.spec_path.c_str(), in.spec.cycle.c_str(),
              shortest_number_text(in.target_force_n).c_str(), machine.c_str(), static_cast<long long>(chosen.record.id),
              chosen.record.version, in.cautious > 0 ? (", cautious first cut (r " + shortest_number_text(in.cautious) +
                                                        ", z " + shortest_number_text(o.sigmas) + ")").c_str()
                                                     : "");
  std::printf("model match: %s%s\n", model_db::describe(chosen.borrowing).c_str(),
              !o.cautious && in.cautious > 0 ? " — the first cut is cautious because the model is borrowed (--cautious R to change)" : "");
  std::printf("%5s %9s %9s | %8s %7s %7s | %8s %7s %7s | %9s | %15s\n", "cycle", "plan_s", "vm_s", "steady", "max%",
              "rms%", "held", "max%", "rms%", "overshoot", "model p95% b→a");
  for (const auto& c : result.cycles) {
    std::printf("%5d %9.2f %9.2f | %8d %7.2f %7.2f | %8d %7.2f %7.2f | %+8.2f%% | %6.1f → %6.1f\n", c.cycle,
                c.planned_cycle_time_s, c.simulated_cycle_time_s, c.comparison.steady,
                c.comparison.steady_max_abs_error_percent, c.comparison.steady_rms_error_percent, c.comparison.held,
                c.comparison.max_abs_error_percent, c.comparison.rms_error_percent, c.comparison.max_overshoot_percent,
                c.model_errors_before.p95_abs_percent, c.model_errors_after.p95_abs_percent);
  }
  const trial::LoopCycle& last = result.cycles.back();
  if (const std::string text = learning::describe(last.infeasible, in.target_force_n); !text.empty()) {
    std::printf("cycle %d: %s\n", last.cycle, text.c_str());
  }
}

}  // namespace

int run_loop_command(const LoopOptions& o) {
  LoopInputs in = read_loop_inputs(o);
  const model_db::Store store = model_db::Store::open(database_path(o.db_path), model_db::OpenMode::kReadOnly);
  const std::optional<ChosenModel> chosen = choose_model(store, in.spec, o.model_id);
  if (!chosen) return 1;
  in.cautious = planning_uncertainty(*chosen, o.cautious);
  const std::optional<model::MechanisticModel> kernel =
      sensor_kernel(store, chosen->record.tool_name, chosen->record.material_name);
  const trial::LoopRequest request = loop_request(o, in, *chosen, kernel);
  const trial::LoopResult result = run_loop_with_progress(request, o.cycles);
  OutputFiles files;
  if (!o.revolutions_path.empty()) files.add(o.revolutions_path, revolutions_csv(result, in.target_force_n));
  if (!o.plot_path.empty()) files.add(o.plot_path, history_plot(request, result, in));
  if (!o.html_path.empty()) files.add(o.html_path, history_html(o, request, result, in, *chosen));
  if (const std::string error = files.commit(); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";  // a write error is not bad input: exit 1
    return 1;
  }
  if (o.json) {
    print_loop_json(o, in, *chosen, result);
  } else {
    print_loop_text(o, in, *chosen, result);
    if (in.sensor) std::printf("%s\n", describe_sensor_correction(kernel).c_str());
  }
  return 0;
}

}  // namespace feedplan::cli
