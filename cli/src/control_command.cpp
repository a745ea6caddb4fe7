#include "control_command.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "calibration_command.hpp"
#include "data_path.hpp"
#include "database_path.hpp"
#include "model_choice.hpp"
#include "number_flag.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "program_stock.hpp"
#include "progress_bar.hpp"
#include "tool_flag.hpp"
#include "tool_runs.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/force_log/force_log_file_writer.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/trial/control_plot.hpp"
#include "feedplan/trial/controlled_run.hpp"
#include "feedplan/trial/depth_step_errors.hpp"
#include "feedplan/trial/depth_step_slot.hpp"

namespace feedplan::cli {

void add_control_command(CLI::App& app, ControlOptions& options) {
  auto* cmd = app.add_subcommand(
      "control",
      "Run a feedback force controller of the source papers on the virtual machine's feed override: alone on\n"
      "the spec's constant-feed program (or a PROGRAM), or with --hybrid trimming the plan's own program;\n"
      "prints how well the true per-revolution peaks held the target");
  cmd->add_option("input", options.input_path, "Cycle spec (.yaml) or G-code program (.nc, .ngc)")->required();
  cmd->add_option("--controller", options.controller,
                  "integral | variable-gain | variable-gain-lathe | robust-servo | model-reference | multi-model-1 |\n"
                  "multi-model-2 (seeds 000/001, 002 and 004)")
      ->required();
  add_number_flag(cmd, "--target-force", options.target_force_n,
                  "Force to hold, N (default: the spec's target_force_n): the per-revolution peak |F_xy| for the\n"
                  "dynamometer and the currents, the tangential force for the spindle");
  cmd->add_option("--sensor", options.sensor,
                  "What the controller reads: dynamometer (default) | spindle (spindle power) | currents (feed-drive\n"
                  "currents, seed 002)");
  cmd->add_option("--machine", options.machine_path,
                  "Machine file (data/machines/*.yaml) to cut on; conflicts with --machine-scale and --material");
  add_number_flag(cmd, "--machine-scale", options.machine_scale,
                  "The virtual machine's cutting coefficients × this (default 1: the material's as the file gives them)");
  cmd->add_flag("--hybrid", options.hybrid,
                "Run the feed-forward plan's program (planned with the database model, as `plan` does) with the\n"
                "controller trimming the override within 70–130 %; SPEC only");
  cmd->add_option("--log", options.log_path, "Force log to write (CSV, docs/method.md §4)");
  cmd->add_option("--plot", options.plot_path, "Plot of force and override against time to write (SVG)");
  cmd->add_flag("--json", options.json, "Print the summary as JSON");
  cmd->add_option("--db", options.db_path, "Model database for --hybrid (default: $FEEDPLAN_DB, else the sample database)");
  cmd->add_option("--materials", options.materials_path, "Materials file (default: the bundled data/materials.yaml)");
  cmd->add_option("--tool", options.tool_text, "PROGRAM only: the end mill, diameter_mm=10,flutes=4,helix_deg=30[,name=…]");
  cmd->add_option("--stock", options.stock_path,
                  "PROGRAM only: a stock YAML or a cycle spec; default: a solid block around the program below z = 0");
  cmd->add_option("--material", options.material_name, "PROGRAM only: the workpiece material (name or alias)");
  add_number_flag(cmd, "--spindle-rpm", options.spindle_rpm, "PROGRAM only: spindle speed for blocks without S, rev/min");
  cmd->add_option("--depth-steps", options.depth_steps,
                  "SPEC only: cut a straight full-width slot through a block instead of the spec's cycle, its axial\n"
                  "depth stepping through D1,D2,… mm (at least 2, each in (0, tool diameter]); prints each depth's\n"
                  "steady error");
  add_number_flag(cmd, "--step-length", options.step_length_mm,
                  "With --depth-steps: each depth is held for this, mm (default 30; > the tool's diameter)");
  cmd->add_option("--calibration", options.calibration_path,
                  "With --sensor currents: the calibration written by `feedplan calibrate-currents -o FILE`,\n"
                  "instead of the virtual machine's own drive constants");
}

namespace {

// Whether the input is a G-code program (by its extension) rather than a cycle spec.
bool is_program(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".nc" || ext == ".ngc" || ext == ".NC" || ext == ".NGC";
}

bool is_spec(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".yaml" || ext == ".yml" || ext == ".YAML" || ext == ".YML";
}

std::string quoted_list(const auto& names) {
  std::string text;
  for (const auto& name : names) {
    if (!text.empty()) text += ", ";
    text += name;
  }
  return text;
}

// The flags, checked all at once, and what they choose.
struct ControlChoice {
  trial::ControllerKind controller = trial::ControllerKind::kRobustServo;
  trial::ForceSensor sensor = trial::ForceSensor::kDynamometer;
  bool program = false;  // a G-code program, not a spec
  std::vector<double> depths_mm;  // --depth-steps, parsed (empty: the spec's cycle)
};

// --depth-steps' list: numbers separated by commas, each named by its place when it is not one.
std::vector<double> parse_depth_steps(const std::string& text, std::vector<InputProblem>& problems) {
  std::vector<double> depths;
  std::size_t start = 0;
  int index = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    double value = 0.0;
    std::size_t used = 0;
    bool ok = false;
    try {
      value = std::stod(item, &used);
      ok = used == item.size() && std::isfinite(value);
    } catch (const std::exception&) {
      ok = false;
    }
    if (!ok) {
      std::string message = "= '";
      message += text;
      message += "': item ";
      message += std::to_string(index + 1);
      message += " '";
      message += item;
      message += "' is not a finite number (depths in mm, e.g. --depth-steps 1,2)";
      problems.push_back({"--depth-steps", std::move(message)});
      return {};
    }
    depths.push_back(value);
    ++index;
    start = comma + 1;
  }
  return depths;
}

void check_program_only_flags(const ControlOptions& o, bool program, std::vector<InputProblem>& problems) {
  if (program) {
    if (o.hybrid) {
      problems.push_back({"--hybrid", "applies to a cycle spec (it runs the plan made for it); a PROGRAM is run as written"});
    }
    if (o.tool_text.empty()) problems.push_back({"--tool", "is required with a PROGRAM, e.g. --tool diameter_mm=10,flutes=4,helix_deg=30"});
    if (o.material_name.empty() && o.machine_path.empty()) {
      problems.push_back({"--material", "is required with a PROGRAM (or --machine MACHINE.yaml), e.g. --material S50C"});
    }
    if (!o.target_force_n) problems.push_back({"--target-force", "is required with a PROGRAM (a spec gives its own)"});
    return;
  }
  const std::pair<const char*, bool> program_flags[] = {{"--tool", !o.tool_text.empty()},
                                                        {"--stock", !o.stock_path.empty()},
                                                        {"--material", !o.material_name.empty()},
                                                        {"--spindle-rpm", o.spindle_rpm.has_value()}};
  for (const auto& [flag, given] : program_flags) {
    if (given) problems.push_back({flag, "only applies to a PROGRAM; a cycle spec gives its own"});
  }
}

ControlChoice read_control_choice(const ControlOptions& o) {
  std::vector<InputProblem> problems;
  ControlChoice choice;
  if (const auto kind = trial::controller_named(o.controller)) {
    choice.controller = *kind;
  } else {
    problems.push_back({"--controller", "= '" + o.controller + "': must be one of " + quoted_list(trial::kControllerNames)});
  }
  if (const auto sensor = trial::force_sensor_named(o.sensor)) {
    choice.sensor = *sensor;
  } else {
    problems.push_back({"--sensor", "= '" + o.sensor + "': must be one of dynamometer, spindle, currents"});
  }
  choice.program = is_program(o.input_path);
  if (!choice.program && !is_spec(o.input_path)) {
    problems.push_back({"input", "= '" + o.input_path + "': must be a cycle spec (.yaml, .yml) or a G-code program (.nc, .ngc)"});
  }
  check_program_only_flags(o, choice.program, problems);
  if (!o.depth_steps.empty()) {
    if (choice.program) {
      problems.push_back({"--depth-steps", "applies to a cycle spec (it cuts a slot with the spec's tool, material and feed); "
                                           "a PROGRAM is run as written"});
    } else if (o.hybrid) {
      problems.push_back({"--depth-steps", "conflicts with --hybrid: the slot is cut at the spec's constant feed"});
    } else {
      choice.depths_mm = parse_depth_steps(o.depth_steps, problems);
      if (!choice.depths_mm.empty() && choice.depths_mm.size() < 2) {
        std::string message = "= '";
        message += o.depth_steps;
        message += "': must give at least 2 depths, e.g. 1,2";
        problems.push_back({"--depth-steps", std::move(message)});
      }
    }
  } else if (o.step_length_mm) {
    problems.push_back({"--step-length", "only applies with --depth-steps"});
  }
  if (!o.calibration_path.empty() && choice.sensor != trial::ForceSensor::kServoCurrents) {
    problems.push_back({"--calibration", "only applies with --sensor currents (the calibration turns currents into forces)"});
  }
  check_flag(problems, "--target-force", o.target_force_n, {0.0, false}, "the force to hold, N");
  check_flag(problems, "--machine-scale", o.machine_scale, {0.1, false, 10.0, false},
             "the virtual machine's forces over the material's");
  check_flag(problems, "--spindle-rpm", o.spindle_rpm, {0.0, false}, "rev/min");
  if (!o.machine_path.empty()) {
    const std::string why = "conflicts with --machine " + o.machine_path + ", which sets ";
    if (o.machine_scale) problems.push_back({"--machine-scale", why + "the machine's physics; give one of them"});
    if (!o.material_name.empty()) problems.push_back({"--material", why + "the material; give one of them"});
  }
  if (!o.db_path.empty() && !o.hybrid) problems.push_back({"--db", "only applies with --hybrid (the plan needs a model)"});
  check_outputs({{"input", o.input_path},
                 {"--machine", o.machine_path},
                 {"--stock", o.stock_path},
                 {"--db", o.hybrid ? database_path(o.db_path) : ""},
                 {"--materials", o.materials_path.empty() ? bundled_materials_path() : o.materials_path},
                 {"--calibration", o.calibration_path}},
                {{"--log", o.log_path}, {"--plot", o.plot_path}}, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return choice;
}

// What runs: the program, the machine it runs on, the target; with --hybrid, the plan alone too.
struct ControlJob {
  std::string name;                 // in words
  geometry::Program program;        // run under control
  trial::VirtualMachine machine;    // without the controller
  double target_force_n = 0.0;
  std::string machine_text;         // the machine's physics in words
  std::vector<std::string> notes;
  bool hybrid = false;
  std::optional<double> planned_cycle_time_s;  // --hybrid: the plan's own prediction
  std::optional<trial::DepthStepSlot> slot;    // --depth-steps: the slot cut instead of the cycle
};

// The virtual machine's physics: --machine's file on `tool`, else the material × --machine-scale.
void set_physics(const ControlOptions& o, const sim::MaterialLibrary& materials, const std::string& material,
                 const std::string& material_field, const geometry::Tool& tool, ControlJob& job) {
  job.machine.tool = tool;
  if (!o.machine_path.empty()) {
    trial::use_machine_file(job.machine, sim::load_machine_file(o.machine_path, materials), tool);
    job.machine_text = "virtual machine " + o.machine_path;
    return;
  }
  const double scale = o.machine_scale.value_or(1.0);
  const sim::Material& m = materials.get(material, material_field);
  job.machine.coefficients = sim::scaled(m.coefficients, scale);
  job.machine_text = "virtual machine: " + m.name + (scale == 1.0 ? "" : " × " + shortest_number_text(scale));
}

ControlJob spec_job(const ControlOptions& o, const sim::MaterialLibrary& materials, const std::vector<double>& choice_depths) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(o.input_path);
  std::vector<InputProblem> problems;
  if (!o.target_force_n && !(spec.target_force_n > 0.0)) {
    problems.push_back({"--target-force", "is required: the spec has no target_force_n"});
  }
  if (!(spec.spindle_rpm > 0.0)) problems.push_back({o.input_path + ": spindle_rpm", "is required (rev/min > 0)"});
  if (!o.hybrid && !spec.feed_mm_per_min) {
    problems.push_back({o.input_path + ": feed_mm_per_min",
                        "is not in the spec: the controller alone runs the spec's constant-feed program — add "
                        "feed_mm_per_min, or give --hybrid to run the plan's program"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  ControlJob job;
  if (!choice_depths.empty()) {
    trial::DepthStepSlotRequest request;
    request.tool = spec.tool;
    request.depths_mm = choice_depths;
    request.step_length_mm = o.step_length_mm.value_or(30.0);
    request.feed_mm_per_min = *spec.feed_mm_per_min;
    request.spindle_rpm = spec.spindle_rpm;
    std::vector<InputProblem> slot_problems;
    for (InputProblem& p : trial::validate(request, "")) {
      if (p.field.rfind("depths_mm", 0) == 0) {
        p.message = p.field.substr(9) + " " + p.message;
        p.field = "--depth-steps";
      } else if (p.field == "step_length_mm") {
        p.field = "--step-length";
      }
      slot_problems.push_back(std::move(p));
    }
    if (!slot_problems.empty()) throw InputError(std::move(slot_problems));
    job.slot = trial::make_depth_step_slot(request);
    job.target_force_n = o.target_force_n.value_or(spec.target_force_n);
    set_physics(o, materials, spec.material, o.input_path + ": material", spec.tool, job);
    job.machine.stock = job.slot->stock;
    job.machine.machine = spec.machine;
    job.machine.spindle_rpm = spec.spindle_rpm;
    job.program = job.slot->program;
    std::string depths;
    for (double d : choice_depths) {
      if (!depths.empty()) depths += ", ";
      depths += shortest_number_text(d);
    }
    job.name = o.input_path;
    job.name += ": depth-step slot (";
    job.name += depths;
    job.name += " mm, each held ";
    job.name += shortest_number_text(request.step_length_mm);
    job.name += " mm) at ";
    job.name += shortest_number_text(request.feed_mm_per_min);
    job.name += " mm/min under the controller";
    return job;
  }
  const cycles::Cycle cycle = cycles::generate(spec);
  job.target_force_n = o.target_force_n.value_or(spec.target_force_n);
  set_physics(o, materials, spec.material, o.input_path + ": material", spec.tool, job);
  job.machine.stock = cycle.stock;
  job.machine.machine = spec.machine;
  job.machine.spindle_rpm = spec.spindle_rpm;
  job.hybrid = o.hybrid;
  if (!o.hybrid) {
    job.program = planner::constant_feed_program(cycle.path, *spec.feed_mm_per_min, spec.spindle_rpm);
    job.name = o.input_path + " (" + spec.cycle + "): constant feed " + shortest_number_text(*spec.feed_mm_per_min) +
               " mm/min under the controller";
    return job;
  }
  const model_db::Store store = model_db::Store::open(database_path(o.db_path), model_db::OpenMode::kReadOnly);
  const std::optional<ChosenModel> chosen = choose_model(store, spec, std::nullopt);
  if (!chosen) throw std::runtime_error("no model in the database for the spec's tool and material (see above)");
  planner::PlanSettings settings;
  settings.model = chosen->record.model;
  settings.uncertainty = cautious_bound(chosen->record, planning_uncertainty(*chosen, std::nullopt));
  settings.target_force_n = job.target_force_n;
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  const planner::PlanResult plan = planner::plan(planner::analyse(cycle.path, cycle.stock, spec.tool), settings);
  job.program = plan.program;
  job.planned_cycle_time_s = plan.summary.cycle_time_s;
  job.name = o.input_path + " (" + spec.cycle + "): the plan's program (model id " + std::to_string(chosen->record.id) +
             " v" + std::to_string(chosen->record.version) + ") trimmed by the controller within 70–130 %";
  job.notes.push_back("model: " + model_db::describe(chosen->borrowing));
  return job;
}

ControlJob program_job(const ControlOptions& o, const sim::MaterialLibrary& materials) {
  std::vector<InputProblem> problems;
  const geometry::Tool tool = parse_tool(o.tool_text, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  const gcode::ReaderOptions reader = tool_change_reader({}, tool);
  const std::string text =
      read_input_file(o.input_path, {"a G-code program of a milling job", reader.max_file_bytes, "ReaderOptions::max_file_bytes"});
  ControlJob job;
  job.program = gcode::read_program(text, o.input_path, reader);
  job.notes = job.program.notes;
  job.target_force_n = *o.target_force_n;
  set_physics(o, materials, o.material_name, "--material", tool, job);
  if (!o.stock_path.empty()) {
    job.machine.stock = cycles::load_stock_spec(o.stock_path);
  } else {
    job.machine.stock = default_stock(job.program, tool.radius_mm());
    job.notes.push_back(kDefaultStockNote);
  }
  job.machine.spindle_rpm = o.spindle_rpm.value_or(0.0);
  job.name = o.input_path + " under the controller";
  return job;
}

// The spindle speed the program cuts at: the machine's (a spec's, --spindle-rpm), else the first S word.
double job_spindle_rpm(const ControlJob& job) {
  if (job.machine.spindle_rpm > 0.0) return job.machine.spindle_rpm;
  for (const geometry::BlockCommand& block : job.program.blocks) {
    if (block.spindle_rpm > 0.0) return block.spindle_rpm;
  }
  return 0.0;
}

// The sensor as the controller reads it: the tool's radius for the spindle, the currents' calibration the
// virtual machine's drives follow (seed 002 Eqs. 12–13, sim::ServoCurrentOptions).
// With --calibration, the file's instead.
trial::ForceSensorSettings sensor_settings(trial::ForceSensor sensor, const geometry::Tool& tool,
                                           const std::optional<learning::CurrentCalibration>& calibration) {
  trial::ForceSensorSettings settings;
  settings.sensor = sensor;
  settings.tool_radius_mm = tool.radius_mm();
  if (calibration) {
    settings.calibration = *calibration;
    return settings;
  }
  const sim::ServoCurrentOptions drives;
  settings.calibration.x = {drives.x.a_amp, drives.x.b_amp_per_n, 1.0, 0};
  settings.calibration.y = {drives.y.a_amp, drives.y.b_amp_per_n, 1.0, 0};
  return settings;
}

// Which calibration the currents are read with, in words.
std::string calibration_text(const ControlOptions& o, const trial::ForceSensorSettings& sensor) {
  std::string text = o.calibration_path.empty() ? "the virtual machine's own drive constants" : "calibration ";
  if (!o.calibration_path.empty()) text += o.calibration_path;
  char numbers[160];
  std::snprintf(numbers, sizeof numbers, " (x: I = %.4f A + %.6f A/N · |F|, y: I = %.4f A + %.6f A/N · |F|)",
                sensor.calibration.x.a_a, sensor.calibration.x.b_a_per_n, sensor.calibration.y.a_a,
                sensor.calibration.y.b_a_per_n);
  text += numbers;
  return text;
}

std::string sensor_text(trial::ForceSensor sensor) {
  switch (sensor) {
    case trial::ForceSensor::kDynamometer: return "dynamometer (per-revolution peak |F_xy|)";
    case trial::ForceSensor::kSpindlePower: return "spindle power (tangential force P / (ω r))";
    case trial::ForceSensor::kServoCurrents: return "feed-drive currents (|F_xy| through I = a + b·|F|)";
  }
  return "";
}

// The run and, with --hybrid, the plan's program alone on the same machine.
struct ControlOutcome {
  trial::ControlledRun run;
  std::vector<trial::DepthSteadyError> depths;  // --depth-steps: each depth's steady error
  std::optional<trial::ControlJudgement> plan_alone;
};

nlohmann::json judgement_json(const trial::ControlJudgement& j) {
  return {{"max_peak_n", j.max_peak_n},
          {"max_overshoot_percent", j.max_overshoot_percent},
          {"in_cut_revolutions", j.in_cut_revolutions},
          {"rms_error_n", j.rms_error_n},
          {"rms_error_percent", j.rms_error_percent},
          {"within_5_percent_share", j.within_5_percent_share},
          {"time_above_target_s", j.time_above_target_s},
          {"cycle_time_s", j.cycle_time_s}};
}

void print_json(const ControlOptions& o, const ControlChoice& choice, const ControlJob& job, const ControlOutcome& out) {
  nlohmann::json json;
  json["job"] = job.name;
  json["controller"] = std::string(trial::to_string(choice.controller));
  json["sensor"] = std::string(trial::to_string(choice.sensor));
  json["target_force_n"] = job.target_force_n;
  json["hybrid"] = job.hybrid;
  json["machine"] = job.machine_text;
  json["result"] = judgement_json(out.run.judgement);
  if (out.plan_alone) json["plan_alone"] = judgement_json(*out.plan_alone);
  if (job.planned_cycle_time_s) json["planned_cycle_time_s"] = *job.planned_cycle_time_s;
  if (job.slot) {
    nlohmann::json depths = nlohmann::json::array();
    for (const trial::DepthSteadyError& d : out.depths) {
      depths.push_back({{"depth_mm", d.depth_mm},
                        {"steady_from_x_mm", d.from_x_mm},
                        {"steady_to_x_mm", d.to_x_mm},
                        {"revolutions", d.revolutions},
                        {"steady_error_n", d.max_abs_error_n},
                        {"mean_error_n", d.mean_error_n}});
    }
    json["depth_steps"] = depths;
  }
  int stepped = 0;
  for (const trial::ControlStep& step : out.run.trace.steps) stepped += step.in_cut ? 1 : 0;
  json["controller_steps"] = stepped;
  if (!o.log_path.empty()) json["log"] = o.log_path;
  if (!o.plot_path.empty()) json["plot"] = o.plot_path;
  json["notes"] = job.notes;
  json["warnings"] = out.run.simulation.warnings;
  std::cout << json.dump(2) << "\n";
}

void print_judgement(const char* what, const trial::ControlJudgement& j) {
  std::printf("%s: largest per-revolution peak %.1f N (%+.1f %% of the target); in cut %d revolutions: RMS error "
              "%.1f N (%.1f %%), %.0f %% within ±5 %%; cycle time %.3f s, %.3f s above the target\n",
              what, j.max_peak_n, j.max_overshoot_percent, j.in_cut_revolutions, j.rms_error_n, j.rms_error_percent,
              100.0 * j.within_5_percent_share, j.cycle_time_s, j.time_above_target_s);
}

void print_text(const ControlOptions& o, const ControlChoice& choice, const ControlJob& job, const ControlOutcome& out) {
  std::printf("%s\n", job.name.c_str());
  std::printf("controller %s on the %s, target %s N; %s\n", std::string(trial::to_string(choice.controller)).c_str(),
              sensor_text(choice.sensor).c_str(), shortest_number_text(job.target_force_n).c_str(), job.machine_text.c_str());
  print_judgement("under control", out.run.judgement);
  if (out.plan_alone) print_judgement("plan alone   ", *out.plan_alone);
  if (job.planned_cycle_time_s) std::printf("the plan predicted %.3f s\n", *job.planned_cycle_time_s);
  for (const trial::DepthSteadyError& d : out.depths) {
    std::printf("depth %s mm: steady error %.1f N (largest |peak − target| over %d revolutions at x %.1f…%.1f mm), "
                "mean %+.1f N\n",
                shortest_number_text(d.depth_mm).c_str(), d.max_abs_error_n, d.revolutions, d.from_x_mm, d.to_x_mm,
                d.mean_error_n);
  }
  if (!o.log_path.empty()) std::printf("force log written to %s\n", o.log_path.c_str());
  if (!o.plot_path.empty()) std::printf("plot written to %s\n", o.plot_path.c_str());
  for (const std::string& note : job.notes) std::printf("note: %s\n", note.c_str());
}

}  // namespace

int run_control_command(const ControlOptions& o) {
  const ControlChoice choice = read_control_choice(o);
  const std::string materials_path = o.materials_path.empty() ? bundled_materials_path() : o.materials_path;
  const sim::MaterialLibrary materials = sim::load_materials(materials_path);
  ControlJob job = choice.program ? program_job(o, materials) : spec_job(o, materials, choice.depths_mm);

  trial::ControllerSettings controller;
  controller.kind = choice.controller;
  controller.target_force_n = job.target_force_n;
  trial::OverrideControlSettings settings;
  std::optional<learning::CurrentCalibration> calibration;
  if (!o.calibration_path.empty()) calibration = load_current_calibration(o.calibration_path);
  const trial::ForceSensorSettings sensor = sensor_settings(choice.sensor, job.machine.tool, calibration);
  if (choice.sensor == trial::ForceSensor::kServoCurrents) job.notes.push_back("currents read with " + calibration_text(o, sensor));
  if (job.hybrid) {
    settings = trial::hybrid_override_settings(sensor, job.target_force_n);
  } else {
    settings.sensor = sensor;
    settings.target_force_n = job.target_force_n;
  }
  controller.max_ratio = settings.max_ratio;
  controller.min_ratio = settings.min_ratio;
  controller.flutes = job.machine.tool.flutes;
  controller.spindle_rpm = job_spindle_rpm(job);
  if (trial::is_model_reference(choice.controller) && !(controller.spindle_rpm > 0.0)) {
    std::string message = "is required with --controller ";
    message += o.controller;
    message += " when the program has no S word: the controller's plant needs the spindle speed";
    throw InputError("--spindle-rpm", std::move(message));
  }
  const trial::ControlLaw law = trial::make_control_law(controller);

  ControlOutcome out;
  std::optional<force_log::ForceLogFileWriter> log_file;
  if (!o.log_path.empty()) {
    log_file.emplace(o.log_path);
    if (!log_file->error().empty()) {
      std::cerr << "feedplan: failed: " << log_file->error() << "\n";
      return 1;
    }
  }
  {
    ProgressBar progress(job.hybrid ? "plan alone, then under control, on the virtual machine"
                                    : "under control on the virtual machine");
    trial::VirtualMachine machine = job.machine;
    if (job.hybrid) {
      machine.keep_log = false;
      machine.progress = [&progress](double f) { progress(0.5 * f); };
      const sim::SimulationResult alone = trial::simulate_on(job.program, machine);
      out.plan_alone = trial::judge_control(alone.revolutions, job.target_force_n, alone.summary.cycle_time_s);
      machine.progress = [&progress](double f) { progress(0.5 + 0.5 * f); };
    } else {
      machine.progress = [&progress](double f) { progress(f); };
    }
    machine.keep_log = false;
    if (log_file) machine.log_sink = &*log_file;
    trial::PositionTrack track;
    force_log::ForceLogFanOut both({log_file ? static_cast<force_log::ForceLogSink*>(&*log_file) : &track, &track});
    if (job.slot) machine.log_sink = log_file ? static_cast<force_log::ForceLogSink*>(&both) : &track;
    out.run = trial::run_under_control(job.program, machine, settings, law);
    if (job.slot) out.depths = trial::depth_steady_errors(*job.slot, out.run.simulation.revolutions, track, job.target_force_n);
  }

  OutputFiles files;
  if (!o.plot_path.empty()) {
    trial::ControlPlotOptions plot;
    plot.title = std::string(trial::to_string(choice.controller)) + " on the " + std::string(trial::to_string(choice.sensor)) +
                 (job.hybrid ? ", trimming the plan" : "") + ": force and feed override";
    plot.sensed_label = std::string("sensed per revolution (") + std::string(trial::to_string(choice.sensor)) + ")";
    files.add(o.plot_path, trial::control_plot_svg(out.run.trace, out.run.simulation.revolutions, job.target_force_n, plot));
  }
  if (!files.error().empty()) {
    std::cerr << "feedplan: failed: " << files.error() << "\n";
    return 1;
  }
  if (log_file) {
    if (const std::string error = log_file->finish(); !error.empty()) {
      std::cerr << "feedplan: failed: " << error << "\n";
      return 1;
    }
  }
  if (const std::string error = files.commit(); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return 1;
  }
  if (o.json) {
    print_json(o, choice, job, out);
  } else {
    print_text(o, choice, job, out);
  }
  for (const std::string& warning : out.run.simulation.warnings) std::cerr << "feedplan: warning: " << warning << "\n";
  return 0;
}

}  // namespace feedplan::cli
