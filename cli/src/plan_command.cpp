#include "plan_command.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "data_path.hpp"
#include "database_path.hpp"
#include "model_choice.hpp"
#include "output_path.hpp"
#include "feedplan/trial/plan_check.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/model_db/closest_model.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/plan_plot.hpp"
#include "feedplan/planner/plan_report.hpp"

namespace feedplan::cli {
namespace {

namespace fs = std::filesystem;
namespace mdb = model_db;

constexpr int kExitFailed = 1;

// What the user asked for, every flag checked.
struct PlanInputs {
  cycles::CycleSpec spec;                             // the cycle spec
  planner::PlanMode mode = planner::PlanMode::kSafe;  // --mode
  double target_force_n = 0.0;                        // --target-force, else the spec's, N
  gcode::WriterOptions writer;                        // --dialect and the format flags (no header yet)
};

// The model to plan with and the database it came from.
struct PlanModel {
  std::string db_path;  // --db, else $FEEDPLAN_DB, else the sample database
  ChosenModel chosen;   // the model and why
};

// The cycle, its plan and how long engagement and planning took.
struct PlannedCycle {
  cycles::Cycle cycle;              // path and stock
  planner::PlanSettings settings;   // what the plan was asked to do
  planner::PlanResult result;       // the plan
  double analyse_s = 0.0;           // wall time of the engagement analysis, s
  double plan_s = 0.0;              // wall time of the planning, s
};

// Which program is written: the plan's when the target can be met everywhere, or the constant-feed one.
struct ProgramChoice {
  bool planned = false;   // the plan's program
  bool constant = false;  // --constant-feed: the constant-feed program instead
  bool any() const { return planned || constant; }
};

// What the outputs step did.
struct PlanOutputs {
  ProgramChoice program;                  // which program was written
  std::optional<trial::PlanCheck> check;  // --simulate: the program run on the virtual machine
  std::vector<std::string> written;       // the files written, in order
};

planner::PlanMode plan_mode(const std::string& mode, std::vector<InputProblem>& problems) {
  if (mode == "regulate") return planner::PlanMode::kRegulate;
  if (mode != "safe") problems.push_back({"--mode", "= '" + mode + "': expected safe or regulate"});
  return planner::PlanMode::kSafe;
}

// The format flags as writer options; their problems named after the flags.
gcode::WriterOptions writer_options(const PlanCommandOptions& o, const std::optional<gcode::Dialect>& dialect,
                                    std::vector<InputProblem>& problems) {
  gcode::WriterOptions writer;
  if (dialect) writer.dialect = *dialect;
  writer.decimals = o.decimals;
  writer.line_numbers = o.line_numbers;
  writer.coolant = o.coolant;
  writer.tool_number = o.tool_number;
  writer.program_number = o.program_number;
  for (InputProblem problem : gcode::validate(writer)) {
    std::replace(problem.field.begin(), problem.field.end(), '_', '-');  // decimals, tool-number: the flags
    problem.field = "--" + problem.field;
    problems.push_back(problem);
  }
  return writer;
}

void check_constant_feed(const PlanCommandOptions& o, const cycles::CycleSpec& spec, std::vector<InputProblem>& problems) {
  if (o.constant_feed_mm_per_min != 0.0 &&
      !(o.constant_feed_mm_per_min >= spec.machine.min_feed_mm_per_min &&
        o.constant_feed_mm_per_min <= spec.machine.max_feed_mm_per_min)) {
    problems.push_back({"--constant-feed", "= " + shortest_number_text(o.constant_feed_mm_per_min) +
                                               ": must lie in the machine's feed range [" +
                                               shortest_number_text(spec.machine.min_feed_mm_per_min) + ", " +
                                               shortest_number_text(spec.machine.max_feed_mm_per_min) + "] mm/min"});
  }
}

// Everything the user gave, checked before anything is read from the database or written.
PlanInputs read_plan_inputs(const PlanCommandOptions& o) {
  PlanInputs in;
  in.spec = cycles::load_cycle_spec(o.spec_path);
  const cycles::CycleSpec& spec = in.spec;
  std::vector<InputProblem> problems;
  const auto dialect = gcode::dialect_from_string(o.dialect);
  if (!dialect) problems.push_back({"--dialect", "= '" + o.dialect + "': expected linuxcnc, fanuc or haas"});
  in.mode = plan_mode(o.mode, problems);
  in.target_force_n = o.target_force_n != 0.0 ? o.target_force_n : spec.target_force_n;
  if (!(std::isfinite(in.target_force_n) && in.target_force_n > 0.0)) {
    problems.push_back({o.target_force_n != 0.0 ? "--target-force" : "target_force_n",
                        "= " + shortest_number_text(in.target_force_n) +
                            ": a target force > 0 N is required (in the spec or with --target-force)"});
  }
  if (!(spec.spindle_rpm > 0.0)) problems.push_back({"spindle_rpm", "is required to plan feeds (rev/min > 0)"});
  if (!(o.ds_mm >= 0.001 && o.ds_mm <= spec.tool.radius_mm())) {
    problems.push_back({"--ds", "= " + shortest_number_text(o.ds_mm) + ": must be in [0.001, tool radius " +
                                    shortest_number_text(spec.tool.radius_mm()) + "] mm"});
  }
  in.writer = writer_options(o, dialect, problems);
  check_constant_feed(o, spec, problems);
  check_output_path("-o", o.program_path, problems);
  check_output_path("--report", o.report_path, problems);
  check_output_path("--csv", o.csv_path, problems);
  check_output_path("--plot", o.plot_path, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return in;
}

// The model from the database: --model-id, else the closest; nothing (after saying why) when none qualifies.
std::optional<PlanModel> choose_plan_model(const PlanCommandOptions& o, const cycles::CycleSpec& spec) {
  const std::string db_path = database_path(o.db_path);
  const mdb::Store store = mdb::Store::open(db_path, mdb::OpenMode::kReadOnly);
  std::optional<ChosenModel> chosen = choose_model(store, spec, o.model_id);
  if (!chosen) return std::nullopt;
  return PlanModel{db_path, std::move(*chosen)};
}

planner::PlanSettings plan_settings(const PlanCommandOptions& o, const PlanInputs& in, const ChosenModel& chosen) {
  planner::PlanSettings settings;
  settings.model = chosen.record.model;
  settings.target_force_n = in.target_force_n;
  settings.spindle_rpm = in.spec.spindle_rpm;
  settings.machine = in.spec.machine;
  settings.options.mode = in.mode;
  settings.options.air_feed_mm_per_min = o.air_feed_mm_per_min;
  settings.options.merge_tolerance = o.merge_tolerance;
  settings.options.feed_resolution_mm_per_min = o.feed_resolution_mm_per_min;
  settings.options.jerk_limit_mm_per_s3 = o.jerk_limit_mm_per_s3;
  settings.options.ds_mm = o.ds_mm;
  return settings;
}

// Path, engagement, plan.
PlannedCycle plan_cycle(const PlanCommandOptions& o, const PlanInputs& in, const ChosenModel& chosen) {
  PlannedCycle planned;
  const auto started = std::chrono::steady_clock::now();
  planned.cycle = cycles::generate(in.spec);
  const planner::PlanGeometry geometry =
      planner::analyse(planned.cycle.path, planned.cycle.stock, in.spec.tool, o.ds_mm);  // = options.ds_mm
  const auto analysed = std::chrono::steady_clock::now();
  planned.settings = plan_settings(o, in, chosen);
  planned.result = planner::plan(geometry, planned.settings);
  const auto finished = std::chrono::steady_clock::now();
  planned.analyse_s = std::chrono::duration<double>(analysed - started).count();
  planned.plan_s = std::chrono::duration<double>(finished - analysed).count();
  return planned;
}

// The program only when the target can be met everywhere, or the constant-feed one when asked for.
ProgramChoice choose_program(const PlanCommandOptions& o, const planner::PlanResult& result) {
  ProgramChoice choice;
  choice.planned = result.status != planner::PlanStatus::kTargetNotMet && result.status != planner::PlanStatus::kUnsafe &&
                   o.constant_feed_mm_per_min == 0.0;
  choice.constant = o.constant_feed_mm_per_min > 0.0;
  return choice;
}

// The writer options with the program's name and header comments.
gcode::WriterOptions program_writer(const PlanCommandOptions& o, const PlanInputs& in, const ChosenModel& chosen,
                                    const ProgramChoice& program, const planner::PlanResult& result) {
  const cycles::CycleSpec& spec = in.spec;
  const mdb::ModelRecord& record = chosen.record;
  gcode::WriterOptions writer = in.writer;
  writer.program_name = spec.cycle + " " + spec.tool.name;
  writer.header_comments = {
      {"cycle", spec.cycle + " from " + fs::path(o.spec_path).filename().string()},
      {"tool", spec.tool.name + " D" + shortest_number_text(spec.tool.diameter_mm) + " Z" + std::to_string(spec.tool.flutes)},
      {"material", spec.material}};
  if (program.constant) {
    writer.header_comments.push_back({"constant feed mm/min", shortest_number_text(o.constant_feed_mm_per_min)});
  } else {
    writer.header_comments.push_back(
        {"model", "id " + std::to_string(record.id) + " v" + std::to_string(record.version) + " " + record.tool_name +
                      " in " + record.material_name + " (" + chosen.match + ")"});
    writer.header_comments.push_back({"target force N", shortest_number_text(in.target_force_n)});
    writer.header_comments.push_back(
        {"planned cycle time s", shortest_number_text(std::round(result.summary.cycle_time_s * 100.0) / 100.0)});
  }
  writer.header_comments.push_back({"feedplan", FEEDPLAN_VERSION});
  writer.retract_z_mm = std::nullopt;
  return writer;
}

// The G-code of the program chosen; empty when none is written.
std::string program_text(const PlanCommandOptions& o, const PlanInputs& in, const PlannedCycle& planned,
                         const ProgramChoice& program, const gcode::WriterOptions& writer) {
  if (!program.any()) return "";
  if (program.constant) {
    // --constant-feed: the cycle's own moves, one F on every feed move (what the baseline is).
    return gcode::write_gcode(
        planner::constant_feed_program(planned.cycle.path, o.constant_feed_mm_per_min, in.spec.spindle_rpm), writer);
  }
  return gcode::write_gcode(planned.result.program, writer);
}

planner::PlanReportContext report_context(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                                          const ProgramChoice& program, const gcode::WriterOptions& writer) {
  const mdb::ModelRecord& record = model.chosen.record;
  planner::PlanReportContext context;
  context.spec_path = o.spec_path;
  context.cycle = in.spec.cycle;
  context.tool = in.spec.tool;
  context.material = in.spec.material;
  context.model_id = record.id;
  context.model_version = record.version;
  context.model_tool = record.tool_name;
  context.model_material = record.material_name;
  context.model_match = model.chosen.explanation;
  context.database_path = model.db_path;
  context.program_path = program.any() ? o.program_path : "";
  context.dialect = gcode::to_string(writer.dialect);
  return context;
}

// The plot's title, with the virtual machine's per-revolution peaks as markers when there are some.
planner::PlanPlotOptions plot_options(const PlanInputs& in, const std::optional<trial::PlanCheck>& check) {
  const cycles::CycleSpec& spec = in.spec;
  planner::PlanPlotOptions plot;
  plot.title = spec.cycle + " — " + spec.tool.name + " in " + spec.material + ", target " +
               shortest_number_text(in.target_force_n) + " N";
  if (check) {
    std::vector<std::pair<double, double>> peaks;
    for (const auto& r : check->comparison.revolutions) {
      if (r.in_cut) peaks.emplace_back(0.5 * (r.revolution.s_start_mm + r.revolution.s_end_mm), r.revolution.peak_n);
    }
    plot.measured_peaks = peaks;
    plot.title += " (markers: virtual machine, per-revolution peaks)";
  }
  return plot;
}

// --report, --csv, --plot; the first error, or empty.
std::string write_plan_files(const PlanCommandOptions& o, const PlanInputs& in, const PlannedCycle& planned,
                             const planner::PlanReportContext& context, PlanOutputs& out) {
  const planner::PlanResult& result = planned.result;
  if (!o.report_path.empty()) {
    if (auto error = planner::write_plan_report(o.report_path, result, planned.settings, context); !error.empty()) return error;
    out.written.push_back(o.report_path);
  }
  if (!o.csv_path.empty()) {
    if (auto error = planner::write_plan_samples_csv(o.csv_path, result); !error.empty()) return error;
    out.written.push_back(o.csv_path);
  }
  if (!o.plot_path.empty()) {
    const planner::PlanPlotOptions plot = plot_options(in, out.check);
    if (auto error = planner::write_plan_plot(o.plot_path, result, in.target_force_n, plot); !error.empty()) return error;
    out.written.push_back(o.plot_path);
  }
  return "";
}

// Outputs: the program (only when the target can be met everywhere, or the constant-feed one), its run on
// the virtual machine, the report, CSV and plot. Returns the first error, or empty.
std::string write_plan_outputs(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                               const PlannedCycle& planned, PlanOutputs& out) {
  out.program = choose_program(o, planned.result);
  const gcode::WriterOptions writer = program_writer(o, in, model.chosen, out.program, planned.result);
  const std::string text = program_text(o, in, planned, out.program, writer);
  if (out.program.any()) {
    if (auto error = write_file_atomically(o.program_path, text); !error.empty()) return error;
    out.written.push_back(o.program_path);
  }
  if (o.simulate && out.program.any()) {
    out.check = trial::check_on_virtual_machine(text, in.spec, planned.cycle, planned.result, in.target_force_n,
                                                o.materials_path.empty() ? bundled_materials_path() : o.materials_path);
  }
  return write_plan_files(o, in, planned, report_context(o, in, model, out.program, writer), out);
}

void print_plan_json(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                     const PlannedCycle& planned, const PlanOutputs& outputs) {
  const planner::PlanResult& result = planned.result;
  const planner::PlanSummary& s = result.summary;
  const mdb::ModelRecord& record = model.chosen.record;
  const std::optional<trial::PlanCheck>& check = outputs.check;
  nlohmann::json out;
  out["status"] = planner::to_string(result.status);
  out["messages"] = result.messages;
  out["spec"] = o.spec_path;
  out["model"] = {{"id", record.id}, {"version", record.version}, {"tool", record.tool_name},
                  {"material", record.material_name}, {"match", model.chosen.match}, {"explanation", model.chosen.explanation}};
  out["target_force_n"] = in.target_force_n;
  out["blocks"] = result.blocks.size();
  out["samples"] = result.samples.size();
  out["feed_min_mm_per_min"] = s.min_feed_mm_per_min;
  out["feed_max_mm_per_min"] = s.max_feed_mm_per_min;
  out["cycle_time_s"] = s.cycle_time_s;
  out["cutting_time_s"] = s.cutting_time_s;
  out["max_predicted_force_n"] = s.max_predicted_force_n;
  out["baseline"] = {{"feed_mm_per_min", s.baseline.feed_mm_per_min}, {"cycle_time_s", s.baseline.cycle_time_s},
                     {"peak_force_n", s.baseline.peak_force_n}};
  out["time_saved_percent"] = s.time_saved_percent;
  out["engagement_time_s"] = planned.analyse_s;
  out["plan_time_s"] = planned.plan_s;
  out["written"] = outputs.written;
  if (check) {
    const auto& c = check->comparison;
    out["virtual_machine"] = {{"cycle_time_s", check->cycle_time_s},
                              {"max_peak_n", check->max_peak_n},
                              {"revolutions", c.revolutions.size()},
                              {"in_cut", c.in_cut},
                              {"held", c.held},
                              {"steady", c.steady},
                              {"steady_max_abs_error_percent", c.steady_max_abs_error_percent},
                              {"steady_rms_error_percent", c.steady_rms_error_percent},
                              {"max_abs_error_percent", c.max_abs_error_percent},
                              {"rms_error_percent", c.rms_error_percent},
                              {"max_overshoot_percent", c.max_overshoot_percent},
                              {"warnings", check->warnings}};
  }
  std::cout << out.dump(2) << "\n";
}

void print_plan_text(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                     const PlannedCycle& planned, const PlanOutputs& outputs) {
  const cycles::CycleSpec& spec = in.spec;
  const planner::PlanResult& result = planned.result;
  const planner::PlanSummary& s = result.summary;
  const mdb::ModelRecord& record = model.chosen.record;
  const std::optional<trial::PlanCheck>& check = outputs.check;
  std::printf("%s: %s, tool %s, %s, target %s N\n", o.spec_path.c_str(), spec.cycle.c_str(), spec.tool.name.c_str(),
              spec.material.c_str(), shortest_number_text(in.target_force_n).c_str());
  std::printf("model: id %lld v%d (%s in %s) — %s\n", static_cast<long long>(record.id), record.version,
              record.tool_name.c_str(), record.material_name.c_str(), model.chosen.explanation.c_str());
  std::printf("status: %s\n", planner::to_string(result.status).c_str());
  std::printf("plan: %zu samples, %zu blocks, F %.0f–%.0f mm/min, predicted peak %.1f N (engagement %.3f s, plan %.3f s)\n",
              result.samples.size(), result.blocks.size(), s.min_feed_mm_per_min, s.max_feed_mm_per_min,
              s.max_predicted_force_n, planned.analyse_s, planned.plan_s);
  std::printf("cycle time: planned %.2f s (cutting %.2f s) vs constant F%.0f %.2f s: %.1f %% saved\n", s.cycle_time_s,
              s.cutting_time_s, s.baseline.feed_mm_per_min, s.baseline.cycle_time_s, s.time_saved_percent);
  if (check) {
    std::printf("virtual machine: cycle time %.2f s, largest per-revolution peak %.1f N\n", check->cycle_time_s,
                check->max_peak_n);
    std::printf("%s", planner::describe(check->comparison).c_str());
  }
  for (const std::string& path : outputs.written) std::printf("wrote %s\n", path.c_str());
}

// The virtual machine's warnings and the plan's notes, on stderr.
void print_plan_notes(const planner::PlanResult& result, const PlanOutputs& out) {
  if (out.check) {
    for (const std::string& warning : out.check->warnings) std::cerr << "feedplan: virtual machine: " << warning << "\n";
  }
  for (const std::string& message : result.messages) std::cerr << "feedplan: note: " << message << "\n";
}

}  // namespace

void add_plan_command(CLI::App& app, PlanCommandOptions& options) {
  auto* cmd = app.add_subcommand(
      "plan",
      "Plan the feeds of a canned cycle: engagement along the path, the closest force model from the database,\n"
      "feeds that hold the predicted force at the target under the machine's limits; writes G-code with F words");
  cmd->add_option("spec", options.spec_path, "Cycle spec (YAML), e.g. samples/trochoid.yaml")->required();
  cmd->add_option("-o,--output", options.program_path, "G-code program to write")->required();
  cmd->add_option("--db", options.db_path, "Model database (default: $FEEDPLAN_DB, else the bundled sample database)");
  cmd->add_option("--target-force", options.target_force_n, "Per-revolution peak force to hold, N (default: the spec's)");
  cmd->add_option("--dialect", options.dialect, "G-code dialect: linuxcnc, fanuc or haas (default linuxcnc)");
  cmd->add_option("--report", options.report_path, "Write the plan report (JSON)");
  cmd->add_option("--csv", options.csv_path, "Write the plan per sample (CSV)");
  cmd->add_option("--plot", options.plot_path, "Write a plot of engagement, feed and predicted force (SVG)");
  cmd->add_option("--mode", options.mode, "safe (F never above any limit inside its block) or regulate (default safe)");
  cmd->add_option("--air-feed", options.air_feed_mm_per_min, "Feed through air, mm/min (default: the machine's maximum)");
  cmd->add_option("--merge-tolerance", options.merge_tolerance, "Relative feed spread merged into one block (default 0.02)");
  cmd->add_option("--feed-resolution", options.feed_resolution_mm_per_min, "F resolution, mm/min (default 1)");
  cmd->add_option("--jerk", options.jerk_limit_mm_per_s3, "Path jerk limit, mm/s³ (default: none)");
  cmd->add_option("--ds", options.ds_mm, "Engagement sample spacing, mm (default 0.05)");
  cmd->add_option("--model-id", options.model_id, "Plan with this model (id from feedplan db list) instead of the closest");
  cmd->add_option("--decimals", options.decimals, "Digits after the point in X Y Z I J (default 3)");
  cmd->add_flag("--line-numbers", options.line_numbers, "Number the blocks (N words)");
  cmd->add_flag("--coolant", options.coolant, "Flood coolant on (M8) while cutting");
  cmd->add_option("--tool-number", options.tool_number, "Tool number for T and H (default 1)");
  cmd->add_option("--program-number", options.program_number, "Program number for the O word of Fanuc/Haas (default 1000)");
  cmd->add_flag("--json", options.json, "Print the summary as JSON");
  cmd->add_flag("--simulate", options.simulate,
                "Run the written program on the virtual machine (mechanistic forces for the spec's material) and\n"
                "compare its per-revolution peak forces with the target");
  cmd->add_option("--constant-feed", options.constant_feed_mm_per_min,
                  "Write the constant-feed program instead: this F (mm/min) on every feed move (a baseline to compare)");
  cmd->add_option("--materials", options.materials_path, "Materials file of the virtual machine (default: the bundled one)");
}

int run_plan_command(const PlanCommandOptions& o) {
  const PlanInputs in = read_plan_inputs(o);
  const std::optional<PlanModel> model = choose_plan_model(o, in.spec);
  if (!model) return kExitFailed;
  const PlannedCycle planned = plan_cycle(o, in, model->chosen);
  PlanOutputs out;
  if (auto error = write_plan_outputs(o, in, *model, planned, out); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return kExitFailed;
  }
  if (o.json) {
    print_plan_json(o, in, *model, planned, out);
  } else {
    print_plan_text(o, in, *model, planned, out);
  }
  print_plan_notes(planned.result, out);
  if (!out.program.any()) {
    if (planned.result.status == planner::PlanStatus::kUnsafe) {
      std::cerr << "feedplan: failed: the plan is unsafe (see the note above); no program written to " << o.program_path
                << "\n";
    } else {
      std::cerr << "feedplan: failed: the target cannot be met everywhere (see the note above); no program written to "
                << o.program_path << " — raise the target, or lower the machine's min_feed_mm_per_min\n";
    }
    return kExitFailed;
  }
  return 0;
}

}  // namespace feedplan::cli
