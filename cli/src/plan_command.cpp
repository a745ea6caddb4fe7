#include "plan_command.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "data_path.hpp"
#include "html_report_pages.hpp"
#include "database_path.hpp"
#include "model_choice.hpp"
#include "model_kind_choice.hpp"
#include "number_flag.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "plan_baselines.hpp"
#include "plan_outcome.hpp"
#include "plan_summary.hpp"
#include "progress_bar.hpp"
#include "target_sweep_summary.hpp"
#include "feedplan/trial/plan_check.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/model_db/closest_model.hpp"
#include "feedplan/model_db/engagement_groups.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/block_feed_reason.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/plan_plot.hpp"
#include "feedplan/planner/plan_report.hpp"
#include "feedplan/planner/target_sweep.hpp"
#include "feedplan/planner/target_sweep_plot.hpp"
#include "feedplan/report/plan_page.hpp"

namespace feedplan::cli {
namespace {

namespace fs = std::filesystem;
namespace mdb = model_db;

constexpr int kExitFailed = 1;

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
  writer.safe_return = !o.no_safe_return;
  writer.tool_number = o.tool_number;
  writer.program_number = o.program_number;
  writer.work_offset = o.work_offset;
  for (InputProblem problem : gcode::validate(writer)) {
    std::replace(problem.field.begin(), problem.field.end(), '_', '-');  // decimals, tool-number: the flags
    problem.field = "--" + problem.field;
    problems.push_back(problem);
  }
  return writer;
}

// Every numeric flag against its range (the planner's and the machine's), named after the flag.
void check_plan_numbers(const PlanCommandOptions& o, const cycles::CycleSpec& spec, std::vector<InputProblem>& problems) {
  const geometry::MachineLimits& m = spec.machine;
  const FlagRange feed_range{m.min_feed_mm_per_min, true, m.max_feed_mm_per_min, true};
  const std::string machine_range = "the machine's feed range, mm/min";
  check_flag(problems, "--target-force", o.target_force_n, {0.0, false}, "the per-revolution peak force to hold, N");
  check_flag(problems, "--air-feed", o.air_feed_mm_per_min, feed_range, machine_range + " (leave it out for the maximum)");
  check_flag(problems, "--merge-tolerance", o.merge_tolerance, {0.0, true, 0.5, true}, "a relative feed spread");
  check_flag(problems, "--feed-resolution", o.feed_resolution_mm_per_min, {0.0, false, 100.0, true}, "mm/min");
  check_flag(problems, "--feed-step", o.feed_step, {0.0, true, 0.5, true}, "a relative step between F levels (0: off)");
  check_flag(problems, "--min-block-s", o.min_block_duration_s, {0.0, true, 10.0, true}, "s");
  check_flag(problems, "--jerk", o.jerk_limit_mm_per_s3, {0.0, false}, "mm/s³ (leave it out for no jerk limit)");
  check_flag(problems, "--ds", o.ds_mm, {0.001, true, spec.tool.radius_mm(), true}, "mm, at most the tool radius");
  check_flag(problems, "--constant-feed", o.constant_feed_mm_per_min, feed_range, machine_range);
  check_flag(problems, "--cautious", o.model_uncertainty, {0.0, true, 2.0, true},
             "a relative standard deviation of the model's force (0: plan on the model alone)");
  if (o.model_id && *o.model_id < 1) {
    problems.push_back({"--model-id", "= " + std::to_string(*o.model_id) + ": must be ≥ 1 (see feedplan db list)"});
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
  if (!o.target_sweep.empty()) {
    in.sweep = planner::parse_target_range(o.target_sweep, "--target-sweep");
    for (const auto& [flag, given] : {std::pair<const char*, bool>{"-o", !o.program_path.empty()},
                                      {"--report", !o.report_path.empty()},
                                      {"--csv", !o.csv_path.empty()},
                                      {"--html", !o.html_path.empty()},
                                      {"--simulate", o.simulate},
                                      {"--explain", o.explain},
                                      {"--part-comments", o.part_comments},
                                      {"--constant-feed", o.constant_feed_mm_per_min.has_value()},
                                      {"--target-force", o.target_force_n.has_value()}}) {
      if (given) problems.push_back({flag, "is not used with --target-sweep, which plans at many targets and writes no "
                                           "program (only --plot, the curve): leave one of them out"});
    }
  } else if (o.program_path.empty()) {
    problems.push_back({"-o", "is required: the G-code program to write (or --target-sweep FROM:TO:STEP for the "
                              "time-versus-target curve)"});
  }
  in.target_force_n = o.target_force_n.value_or(spec.target_force_n);
  if (!o.target_force_n && !(spec.target_force_n > 0.0)) {
    problems.push_back({"target_force_n", "is not in the spec: a target force > 0 N is required (in the spec or "
                                          "with --target-force)"});
  }
  if (!(spec.spindle_rpm > 0.0)) problems.push_back({"spindle_rpm", "is required to plan feeds (rev/min > 0)"});
  check_plan_numbers(o, spec, problems);
  in.writer = writer_options(o, dialect, problems);
  check_outputs({{"SPEC", o.spec_path},
                 {"--db", database_path(o.db_path)},
                 {"--materials", o.materials_path.empty() ? bundled_materials_path() : o.materials_path}},
                {{"-o", o.program_path}, {"--report", o.report_path}, {"--csv", o.csv_path}, {"--plot", o.plot_path},
                 {"--html", o.html_path}},
                problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return in;
}

// --target-sweep: the plan at every target of `range`, printed (and drawn with --plot). Returns 0, or 1 when
// the plot cannot be written.
int run_target_sweep(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                     const PlannedCycle& planned, const planner::TargetRange& range) {
  const std::vector<planner::TargetSweepRow> rows = planner::sweep_targets(planned.geometry, planned.settings, range);
  print_target_sweep(o.json, in.spec.cycle, model, rows);
  if (!o.plot_path.empty()) {
    const std::string title = in.spec.cycle + ": cycle time and largest predicted peak against the target";
    if (const std::string error = write_file_atomically(o.plot_path, planner::target_sweep_svg(rows, title));
        !error.empty()) {
      std::cerr << "feedplan: failed: " << error << "\n";
      return kExitFailed;
    }
    if (!o.json) std::printf("plot: %s\n", o.plot_path.c_str());
  }
  return 0;
}

// The model from the database: --model-id, else the closest; nothing (after saying why) when none qualifies.
std::optional<PlanModel> choose_plan_model(const PlanCommandOptions& o, const cycles::CycleSpec& spec) {
  const std::string db_path = database_path(o.db_path);
  const mdb::Store store = mdb::Store::open(db_path, mdb::OpenMode::kReadOnly);
  std::optional<ChosenModel> chosen = choose_model(store, spec, o.model_id);
  if (!chosen) return std::nullopt;
  const double r = planning_uncertainty(*chosen, o.model_uncertainty);
  PlanModel model{stored_path(db_path), std::move(*chosen), r, o.model_uncertainty.has_value(), std::nullopt, ""};
  ModelKindChoice kind = choose_model_kind(store, model.chosen, spec.tool, o.model_kind, std::nullopt);
  model.relative_uncertainty = planning_uncertainty(kind, o.model_uncertainty);
  model.max_chip_thickness_mm = kind.max_chip_thickness_mm;
  model.mechanistic = std::move(kind.mechanistic);
  model.kind_reason = std::move(kind.reason);
  return model;
}

// The plan's settings; a borrowed model (or --cautious) plans on the cautious bound F̂ + z·σ.
planner::PlanSettings plan_settings(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model) {
  const ChosenModel& chosen = model.chosen;
  planner::PlanSettings settings;
  settings.model = chosen.record.model;
  if (model.mechanistic) settings.mechanistic = model.mechanistic->mechanistic->model;
  settings.uncertainty = cautious_bound(chosen.record, model.relative_uncertainty);
  settings.target_force_n = in.target_force_n;
  settings.spindle_rpm = in.spec.spindle_rpm;
  settings.machine = in.spec.machine;
  settings.options.mode = in.mode;
  settings.options.air_feed_mm_per_min = o.air_feed_mm_per_min.value_or(0.0);  // 0: the machine's maximum
  settings.options.merge_tolerance = o.merge_tolerance;
  settings.options.feed_resolution_mm_per_min = o.feed_resolution_mm_per_min;
  settings.options.feed_step = o.feed_step;
  settings.options.min_block_duration_s = o.min_block_duration_s;
  settings.options.jerk_limit_mm_per_s3 = o.jerk_limit_mm_per_s3.value_or(0.0);  // 0: none
  settings.options.ds_mm = o.ds_mm;
  settings.options.coordinate_resolution_mm = std::pow(10.0, -o.decimals);  // what the writer rounds to
  settings.options.max_chip_thickness_mm = model.max_chip_thickness_mm;
  return settings;
}

// Path, engagement, plan.
PlannedCycle plan_cycle(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model) {
  PlannedCycle planned;
  const auto started = std::chrono::steady_clock::now();
  planned.cycle = cycles::generate(in.spec);
  planned.geometry = planner::analyse(planned.cycle.path, planned.cycle.stock, in.spec.tool, o.ds_mm);  // = options.ds_mm
  const auto analysed = std::chrono::steady_clock::now();
  planned.settings = plan_settings(o, in, model);
  planned.result = planner::plan(planned.geometry, planned.settings);
  const auto finished = std::chrono::steady_clock::now();
  if (planned.settings.options.feed_step > 0.0) {
    planner::PlanSettings ramps = planned.settings;
    ramps.options.feed_step = 0.0;
    planned.ramps_written_out_s = planner::plan(planned.geometry, ramps).summary.cycle_time_s;
  }
  planned.analyse_s = std::chrono::duration<double>(analysed - started).count();
  planned.plan_s = std::chrono::duration<double>(finished - analysed).count();
  return planned;
}

// The program only when the target can be met everywhere, or the constant-feed one when asked for.
ProgramChoice choose_program(const PlanCommandOptions& o, const planner::PlanResult& result) {
  ProgramChoice choice;
  choice.planned = result.status != planner::PlanStatus::kTargetNotMet && result.status != planner::PlanStatus::kUnsafe &&
                   !o.constant_feed_mm_per_min;
  choice.constant = o.constant_feed_mm_per_min.has_value();
  return choice;
}

// The tool comment of the program: "T1 SC EM D10 Z4, D10 mm, 4 flutes, helix 30 deg" (the name once; the
// numbers the controller's operator checks against the tool in the holder).
std::string tool_comment(int tool_number, const geometry::Tool& tool) {
  std::string text(1, 'T');
  text += std::to_string(tool_number);
  if (!tool.name.empty()) text += " " + tool.name;
  text += ", D" + shortest_number_text(tool.diameter_mm) + " mm, " + std::to_string(tool.flutes) + " flutes, helix " +
          shortest_number_text(tool.helix_deg) + " deg";
  return text;
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
      {"tool", tool_comment(writer.tool_number, spec.tool)},
      {"material", spec.material}};
  if (program.constant) {
    writer.header_comments.push_back({"constant feed mm/min", shortest_number_text(*o.constant_feed_mm_per_min)});
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
  writer.part_comments = o.part_comments;
  return writer;
}

// The G-code of the program chosen; empty when none is written.
std::string program_text(const PlanCommandOptions& o, const PlanInputs& in, const PlannedCycle& planned,
                         const ProgramChoice& program, const gcode::WriterOptions& writer) {
  if (!program.any()) return "";
  if (program.constant) {
    // --constant-feed: the cycle's own moves, one F on every feed move (what the baseline is).
    const geometry::Program constant =
        planner::constant_feed_program(planned.cycle.path, *o.constant_feed_mm_per_min, in.spec.spindle_rpm);
    gcode::WriterOptions explained = writer;
    if (o.explain) explained.feed_comments.assign(constant.path.moves.size(), "constant feed, --constant-feed");
    return gcode::write_gcode(constant, explained);
  }
  gcode::WriterOptions explained = writer;
  if (o.explain) explained.feed_comments = planner::block_feed_reason_texts(planned.geometry, planned.settings, planned.result);
  return gcode::write_gcode(planned.result.program, explained);
}

planner::PlanReportContext report_context(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                                          const ProgramChoice& program, const gcode::WriterOptions& writer) {
  // The version that planned: the mechanistic one when the kind is mechanistic (learn then learns that kind).
  const mdb::ModelRecord& record = model.mechanistic ? *model.mechanistic : model.chosen.record;
  planner::PlanReportContext context;
  context.spec_path = stored_path(o.spec_path);  // absolute, as the database: learn finds both from any folder
  context.cycle = in.spec.cycle;
  context.tool = in.spec.tool;
  context.material = in.spec.material;
  context.model_id = record.id;
  context.model_version = record.version;
  context.model_tool = record.tool_name;
  context.model_material = record.material_name;
  context.model_match = model.chosen.explanation;
  context.model_match_status = model_db::to_string(model.chosen.borrowing.status);
  for (const model_db::ModelDifference& d : model.chosen.borrowing.differences) {
    context.model_differences.push_back(d.property + " " + d.used + " for " + d.wanted);
  }
  context.model_relative_uncertainty = model.relative_uncertainty;
  context.model_kind_reason = model.kind_reason;
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

// Stages --report, --csv, --plot, --html.
void stage_plan_files(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model, const PlannedCycle& planned,
                      const planner::PlanReportContext& context, const PlanOutputs& out, OutputFiles& files) {
  const planner::PlanResult& result = planned.result;
  if (!o.report_path.empty()) files.add(o.report_path, planner::plan_report_json(result, planned.settings, context));
  if (!o.csv_path.empty()) files.add(o.csv_path, planner::plan_samples_csv(result));
  if (!o.plot_path.empty()) {
    files.add(o.plot_path, planner::plan_plot_svg(result, in.target_force_n, plot_options(in, out.check)));
  }
  if (!o.html_path.empty()) {
    files.add(o.html_path, report::plan_page_html(result, planned.settings, plan_command_page(in, model, planned, out)));
  }
}

// Outputs: the program (only when the target can be met everywhere, or the constant-feed one), its run on
// the virtual machine, the report, CSV and plot — all staged first, then put in place together, so that an
// error leaves every existing output as it was. A plan that failed writes its report, CSV and plot to
// show where, but only to files that do not exist yet (out.kept lists the others). Returns the first
// error, or empty.
std::string write_plan_outputs(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                               const PlannedCycle& planned, PlanOutputs& out) {
  out.program = choose_program(o, planned.result);
  const gcode::WriterOptions writer = program_writer(o, in, model.chosen, out.program, planned.result);
  const std::string text = program_text(o, in, planned, out.program, writer);
  OutputFiles files;
  if (out.program.any() && !files.add(o.program_path, text)) return files.error();
  const std::string materials = o.materials_path.empty() ? bundled_materials_path() : o.materials_path;
  if (o.simulate && out.program.any()) {
    ProgressBar progress("running the program on the virtual machine");
    out.check = trial::check_on_virtual_machine(text, in.spec, planned.cycle, planned.result, in.target_force_n, materials,
                                                [&progress](double fraction) { progress(fraction); });
  }
  out.baselines = plan_baselines(in, planned, out.program.planned ? out.check : std::nullopt, materials);
  stage_plan_files(o, in, model, planned, report_context(o, in, model, out.program, writer), out, files);
  const std::string error = files.commit(out.program.any() ? ExistingFile::kReplace : ExistingFile::kKeep);
  out.written = files.written();
  out.kept = files.kept();
  return error;
}

// The outputs a failed plan left as they were, on stderr.
void print_kept_outputs(const PlanOutputs& out) {
  for (const std::string& path : out.kept) {
    std::cerr << "feedplan: note: " << path << " exists: left as it was (a plan that fails writes only new files)\n";
  }
}

// When a borrowed model's cautious bound is what the target cannot meet, a model of its own removes it.
std::string borrowed_model_advice(const PlanModel& model) {
  if (model.chosen.borrowing.status != model_db::ModelMatchStatus::kBorrowed || model.relative_uncertainty <= 0.0) return "";
  return "; or fit a model for this tool and material (feedplan db import-test, feedplan db fit): the borrowed "
         "model is planned with a bound " + shortest_number_text(std::round(100.0 * kBorrowedModelSigmas * model.relative_uncertainty)) +
         " % above its force";
}

}  // namespace

std::optional<PlanAsWritten> plan_as_written(const std::string& spec_path, const cycles::CycleSpec& spec,
                                             double target_force_n, const std::string& db_path) {
  PlanCommandOptions o;
  o.spec_path = spec_path;
  o.db_path = db_path;
  o.target_force_n = target_force_n;
  PlanAsWritten out;
  out.inputs.spec = spec;
  out.inputs.target_force_n = target_force_n;
  std::vector<InputProblem> problems;
  out.inputs.mode = plan_mode(o.mode, problems);
  out.inputs.writer = writer_options(o, gcode::dialect_from_string(o.dialect), problems);
  assert(problems.empty());  // plan's own defaults
  std::optional<PlanModel> model = choose_plan_model(o, spec);
  if (!model) return std::nullopt;
  out.model = std::move(*model);
  out.planned = plan_cycle(o, out.inputs, out.model);
  ProgramChoice program;
  program.planned = true;
  out.writer = program_writer(o, out.inputs, out.model.chosen, program, out.planned.result);
  return out;
}

void add_plan_command(CLI::App& app, PlanCommandOptions& options) {
  auto* cmd = app.add_subcommand(
      "plan",
      "Plan the feeds of a canned cycle: engagement along the path, the closest force model from the database,\n"
      "feeds that hold the predicted force at the target under the machine's limits; writes G-code with F words");
  cmd->add_option("spec", options.spec_path, "Cycle spec (YAML), e.g. samples/trochoid.yaml")->required();
  cmd->add_option("-o,--output", options.program_path, "G-code program to write (required unless --target-sweep)");
  cmd->add_option("--db", options.db_path, "Model database (default: $FEEDPLAN_DB, else the bundled sample database)");
  add_number_flag(cmd, "--target-force", options.target_force_n, "Per-revolution peak force to hold, N (default: the spec's)");
  cmd->add_option("--dialect", options.dialect, "G-code dialect: linuxcnc, fanuc or haas (default linuxcnc)");
  cmd->add_option("--report", options.report_path, "Write the plan report (JSON)");
  cmd->add_option("--csv", options.csv_path, "Write the plan per sample (CSV)");
  cmd->add_option("--plot", options.plot_path, "Write a plot of engagement, feed and predicted force (SVG)");
  cmd->add_option("--html", options.html_path,
                  "Write the plan as one self-contained HTML file: the tool path coloured by feed or force, force, feed\n"
                  "and engagement along the path, the summary and the notes (feedplan report draws it from --report too)");
  cmd->add_option("--mode", options.mode, "safe (F never above any limit inside its block) or regulate (default safe)");
  add_number_flag(cmd, "--air-feed", options.air_feed_mm_per_min, "Feed through air, mm/min (default: the machine's maximum)");
  add_number_flag(cmd, "--merge-tolerance", options.merge_tolerance, "Relative feed spread merged into one block (default 0.02)");
  add_number_flag(cmd, "--feed-step", options.feed_step,
                  "Controller-friendly blocks: F on levels this far apart, cut from the feed limits, each lasting at "
                  "least --min-block-s (default 0.02; 0: every acceleration ramp written out as F words)");
  add_number_flag(cmd, "--min-block-s", options.min_block_duration_s,
                  "Shortest block with --feed-step, s (default 0.006: at most 167 F changes a second; the spec's "
                  "block_time_min_s when longer)");
  add_number_flag(cmd, "--feed-resolution", options.feed_resolution_mm_per_min, "F resolution, mm/min (default 1)");
  add_number_flag(cmd, "--jerk", options.jerk_limit_mm_per_s3, "Path jerk limit, mm/s³ (default: none)");
  add_number_flag(cmd, "--ds", options.ds_mm, "Engagement sample spacing, mm (default 0.05)");
  add_integer_flag(cmd, "--model-id", options.model_id, "Plan with this model (id from feedplan db list) instead of the closest");
  cmd->add_option("--model-kind", options.model_kind,
                  "mechanistic (cutting coefficients on the exact engaged arcs) or response-surface (seed 003 Eq. 1)\n"
                  "(default: the kind with the lower leave-one-engagement-out error on the pair's cutting tests)")
;
  add_number_flag(cmd, "--cautious,--model-uncertainty", options.model_uncertainty,
                  "Relative uncertainty r of the model's force: plan on F̂ + 2σ (default: from how far the model is\n"
                  "borrowed, 0 for an exact one; 0 plans on the model alone). For a first part on a machine the model\n"
                  "was never checked on, 0.15");
  add_integer_flag(cmd, "--decimals", options.decimals, "Digits after the point in X Y Z I J (default 3)");
  cmd->add_flag("--line-numbers", options.line_numbers, "Number the blocks (N words)");
  cmd->add_flag("--coolant", options.coolant, "Flood coolant on (M8) while cutting");
  cmd->add_flag("--no-safe-return", options.no_safe_return,
                "End without the return to the machine's Z home (by default the program ends with G53 G0 Z0.,\n"
                "on Fanuc and Haas G91 G28 Z0. then G90, before M5): for a machine whose Z home is not safe to go\n"
                "to, or a program run inside another");
  add_integer_flag(cmd, "--tool-number", options.tool_number, "Tool number for T and H (default 1)");
  add_integer_flag(cmd, "--work-offset", options.work_offset, "Work offset G54..G59 as 54..59 (default 54; 0: none)");
  add_integer_flag(cmd, "--program-number", options.program_number, "Program number for the O word of Fanuc/Haas (default 1000)");
  cmd->add_flag("--json", options.json, "Print the summary as JSON");
  cmd->add_flag("--simulate", options.simulate,
                "Run the written program on the virtual machine (mechanistic forces for the spec's material),\n"
                "compare its per-revolution peak forces with the target, and find the constant feed with the same\n"
                "largest peak there (a few more runs)");
  add_number_flag(cmd, "--constant-feed", options.constant_feed_mm_per_min,
                  "Write the constant-feed program instead: this F (mm/min) on every feed move (a baseline to compare)");
  cmd->add_option("--materials", options.materials_path, "Materials file of the virtual machine (default: the bundled one)");
  cmd->add_flag("--explain", options.explain,
                "Write why every F is what it is as a comment on its line: (F: force 300 N at 58 deg engagement),\n"
                "(F: plunge limit 0.025 mm/tooth), (F: model range, chip 0.120 mm), (F: machine max feed), (F: air),\n"
                "(F: acceleration) where the machine's ramp sets it, (F: arc R 2.500 mm, acceleration)");
  cmd->add_flag("--part-comments", options.part_comments,
                "Write a comment line (part: <name>) before the first block of each cycle part (approach, loop 3, ...)");
  cmd->add_option("--target-sweep", options.target_sweep,
                  "FROM:TO:STEP in N, e.g. 250:500:25: plan at each target and print the cycle time and largest\n"
                  "predicted peak of each (--plot draws the curve); writes no program");
}

int run_plan_command(const PlanCommandOptions& o) {
  const PlanInputs in = read_plan_inputs(o);
  const std::optional<PlanModel> model = choose_plan_model(o, in.spec);
  if (!model) return kExitFailed;
  const PlannedCycle planned = plan_cycle(o, in, *model);
  if (in.sweep) return run_target_sweep(o, in, *model, planned, *in.sweep);
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
  print_kept_outputs(out);
  if (!out.program.any()) {
    if (planned.result.status == planner::PlanStatus::kUnsafe) {
      std::cerr << "feedplan: failed: the plan is unsafe (see the note above); no program written to " << o.program_path
                << "\n";
    } else {
      const planner::TargetAdvice advice = planner::target_advice(planned.geometry, planned.settings, planned.result);
      std::cerr << "feedplan: failed: the target cannot be met everywhere (see the note above); no program written to "
                << o.program_path << " — " << advice.text << borrowed_model_advice(*model) << "\n";
    }
    return kExitFailed;
  }
  return 0;
}

}  // namespace feedplan::cli
