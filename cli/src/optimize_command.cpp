#include "optimize_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "database_path.hpp"
#include "model_choice.hpp"
#include "model_kind_choice.hpp"
#include "operation_figures.hpp"
#include "optimize_outputs.hpp"
#include "program_operations.hpp"
#include "number_flag.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "tool_flag.hpp"
#include "tool_runs.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/block_feed_reason.hpp"
#include "feedplan/planner/feed_prediction.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::cli {
namespace {

namespace mdb = model_db;

constexpr int kExitFailed = 1;

// --stock-box X0,Y0,Z0,X1,Y1,Z1: a block of material, corners in any order.
geometry::Stock stock_box(const std::string& text, std::vector<InputProblem>& problems, std::vector<double>& v) {
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (item.empty() || *end != '\0' || !std::isfinite(value)) {
      problems.push_back({"--stock-box", "item '" + item + "' is not a finite number (X0,Y0,Z0,X1,Y1,Z1 in mm)"});
      return {};
    }
    v.push_back(value);
  }
  if (v.size() != 6) {
    problems.push_back({"--stock-box", "= '" + text + "': " + std::to_string(v.size()) +
                                           " numbers; expected six, X0,Y0,Z0,X1,Y1,Z1 in mm (two opposite corners)"});
    return {};
  }
  if (v[0] == v[3] || v[1] == v[4] || v[2] == v[5]) {
    problems.push_back({"--stock-box", "= '" + text + "': the corners must differ in X, Y and Z (a block, not a face)"});
    return {};
  }
  geometry::Stock stock;
  stock.regions.push_back({geometry::Contour::rectangle({std::min(v[0], v[3]), std::min(v[1], v[4])},
                                                        {std::max(v[0], v[3]), std::max(v[1], v[4])}),
                           {}});
  stock.z_bottom_mm = std::min(v[2], v[5]);
  stock.z_top_mm = std::max(v[2], v[5]);
  return stock;
}

// What the user gave, checked before anything is planned or written.
struct OptimizeInputs {
  std::string text;                           // the program as read
  geometry::Program program;                  // its moves
  std::vector<gcode::WrittenMove> written;    // how each move's line was written
  std::vector<ToolRun> runs;                  // in program order
  geometry::Stock stock;
  std::vector<double> stock_box_mm;           // --stock-box's six numbers (empty with --stock)
  geometry::MachineLimits machine;
};

// The spindle speed run's feeds are planned for: --spindle-rpm, else the one S of its feed moves.
double spindle_speed(const OptimizeOptions& o, const geometry::Program& program, const ToolRun& run,
                     std::vector<InputProblem>& problems) {
  if (o.spindle_rpm) return *o.spindle_rpm;
  double rpm = 0.0;
  int line = 0;
  for (std::size_t i = run.first; i < run.end; ++i) {
    if (program.path.moves[i].kind == geometry::MoveKind::kRapid) continue;
    const geometry::BlockCommand& b = program.blocks[i];
    if (rpm == 0.0) {
      rpm = b.spindle_rpm;
      line = b.source_line;
    } else if (b.spindle_rpm != rpm) {
      problems.push_back({"PROGRAM", "line " + std::to_string(b.source_line) + " runs S" + shortest_number_text(b.spindle_rpm) +
                                         ", line " + std::to_string(line) + " S" + shortest_number_text(rpm) +
                                         " with the same tool: the feeds are planned for one spindle speed per tool; "
                                         "split the program where S changes, or give --spindle-rpm"});
      return rpm;
    }
  }
  if (!(rpm > 0.0) && line > 0) {
    problems.push_back({"PROGRAM", "sets no spindle speed (S) for the feed moves from line " + std::to_string(line) +
                                       ": give --spindle-rpm"});
  }
  return rpm;
}

OptimizeInputs read_inputs(const OptimizeOptions& o) {
  OptimizeInputs in;
  std::vector<InputProblem> problems;
  if (o.output_path.empty()) problems.push_back({"-o", "is required: the re-fed program to write"});
  if (o.tool_text.empty() == o.tools_path.empty()) {
    problems.push_back({"--tool", "give one of --tool diameter_mm=6,flutes=3,helix_deg=35 (a program of one tool) and "
                                  "--tools TOOLS.yaml (the end mill of each T number)"});
  }
  if (o.material.empty()) problems.push_back({"--material", "is required to choose a force model, e.g. --material Al7075-T6"});
  if (!o.target_force_n) problems.push_back({"--target-force", "is required: the per-revolution peak force to hold, N"});
  if (o.stock_path.empty() == o.stock_box.empty()) {
    problems.push_back({"--stock", "give one of --stock STOCK.yaml and --stock-box X0,Y0,Z0,X1,Y1,Z1: the engagement "
                                   "needs the material the program cuts"});
  }
  check_flag(problems, "--target-force", o.target_force_n, {0.0, false}, "the per-revolution peak force to hold, N");
  check_flag(problems, "--spindle-rpm", o.spindle_rpm, {0.0, false}, "rev/min (leave it out for the program's S)");
  check_flag(problems, "--max-feed", o.max_feed_mm_per_min, {0.0, false}, "mm/min");
  check_flag(problems, "--min-feed", o.min_feed_mm_per_min, {0.0, false}, "mm/min");
  check_flag(problems, "--ds", o.ds_mm, {0.001, true, 1.0, true}, "mm");
  check_flag(problems, "--feed-step", o.feed_step, {0.0, true, 0.5, true}, "a relative step between F levels (0: off)");
  check_flag(problems, "--min-block-s", o.min_block_duration_s, {0.0, true, 10.0, true}, "s");
  std::optional<geometry::Tool> tool;
  if (!o.tool_text.empty()) tool = parse_tool(o.tool_text, problems);
  if (!o.stock_box.empty()) in.stock = stock_box(o.stock_box, problems, in.stock_box_mm);
  if (o.max_feed_mm_per_min) in.machine.max_feed_mm_per_min = *o.max_feed_mm_per_min;
  if (o.min_feed_mm_per_min) in.machine.min_feed_mm_per_min = *o.min_feed_mm_per_min;
  for (InputProblem problem : geometry::validate(in.machine)) {
    problem.field = problem.field == "machine.max_feed_mm_per_min" ? "--max-feed"
                    : problem.field == "machine.min_feed_mm_per_min" ? "--min-feed"
                                                                     : problem.field;
    problems.push_back(problem);
  }
  check_outputs({{"PROGRAM", o.program_path}, {"--db", database_path(o.db_path)}, {"--stock", o.stock_path},
                 {"--tools", o.tools_path}},
                {{"-o", o.output_path}, {"--report", o.report_path}, {"--csv", o.csv_path}, {"--plot", o.plot_path}},
                problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  const std::map<int, geometry::Tool> library =
      o.tools_path.empty() ? std::map<int, geometry::Tool>{} : cycles::load_tool_library(o.tools_path);
  const gcode::ReaderOptions reader = tool_change_reader(library, tool);  // each tool's moves planned on their own
  in.text = read_input_file(o.program_path, {"a G-code program of a milling job", reader.max_file_bytes,
                                             "ReaderOptions::max_file_bytes"});
  in.program = gcode::read_program(in.text, o.program_path, reader, in.written);
  if (!o.stock_path.empty()) in.stock = cycles::load_stock_spec(o.stock_path);
  in.runs = tool_runs(in.program, in.written, tool, library, o.tools_path, problems);
  for (ToolRun& run : in.runs) run.spindle_rpm = spindle_speed(o, in.program, run, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return in;
}

// The plan's settings for one tool's moves: the model, the cautious bound when it is borrowed (or --cautious).
planner::PlanSettings settings_for(const OptimizeOptions& o, const OptimizeInputs& in, const ToolRun& run,
                                   const ChosenModel& chosen, const ModelKindChoice& kind) {
  planner::PlanSettings settings;
  settings.model = chosen.record.model;
  if (kind.mechanistic) settings.mechanistic = kind.mechanistic->mechanistic->model;
  settings.options.max_chip_thickness_mm = kind.max_chip_thickness_mm;
  settings.uncertainty = cautious_bound(chosen.record, planning_uncertainty(kind, o.model_uncertainty));
  settings.target_force_n = *o.target_force_n;
  settings.spindle_rpm = run.spindle_rpm;
  settings.machine = in.machine;
  settings.options.ds_mm = o.ds_mm;
  settings.options.coordinate_resolution_mm = in.program.coordinate_resolution_mm;
  settings.options.feed_step = o.feed_step;
  settings.options.min_block_duration_s = o.min_block_duration_s;
  return settings;
}

// One tool's moves planned: the model, the plan, and the plan with every ramp written out for comparison.
struct PlannedRun {
  ChosenModel chosen;
  ModelKindChoice kind;
  planner::PlanGeometry geometry;
  planner::PlanSettings settings;
  planner::PlanResult result;
  std::optional<double> unconstrained_s;  // the cycle time of the plan with every ramp written out
  planner::FeedPrediction input;          // the run at the input program's own feeds
};

// The input program's own F of every move of `run` (0 on rapids), mm/min.
std::vector<double> input_feeds(const geometry::Program& program, const ToolRun& run) {
  std::vector<double> feeds;
  for (std::size_t i = run.first; i < run.end; ++i) feeds.push_back(program.blocks[i].feed_mm_per_min);
  return feeds;
}

// Plans one tool's moves on `stock` (the material the earlier tools left). Nothing when the database has
// no model for the tool (after saying why).
std::optional<PlannedRun> plan_run(const OptimizeOptions& o, const OptimizeInputs& in, const ToolRun& run,
                                   const model_db::Store& store, const geometry::Stock& stock) {
  cycles::CycleSpec spec;  // what the model choice reads: the tool and the material
  spec.tool = run.tool;
  spec.material = o.material;
  spec.spindle_rpm = run.spindle_rpm;
  spec.machine = in.machine;
  std::optional<ChosenModel> chosen = choose_model(store, spec, o.model_id);
  if (!chosen) return std::nullopt;
  PlannedRun planned{std::move(*chosen), {}, planner::analyse(run_path(in.program, run), stock, run.tool, o.ds_mm), {}, {}, {}, {}};
  planned.kind = choose_model_kind(store, planned.chosen, run.tool, o.model_kind,
                                   extrapolated_contact_share(planned.chosen.record.model, planned.geometry.engagement));
  planned.settings = settings_for(o, in, run, planned.chosen, planned.kind);
  planned.result = planner::plan(planned.geometry, planned.settings);
  if (planned.settings.options.feed_step > 0.0) {
    planner::PlanSettings unconstrained = planned.settings;
    unconstrained.options.feed_step = 0.0;
    planned.unconstrained_s = planner::plan(planned.geometry, unconstrained).summary.cycle_time_s;
  }
  planned.input = planner::predict_feeds(planned.geometry, planned.settings, input_feeds(in.program, run),
                                         planned.result.summary.accel_used_mm_per_s2);
  return planned;
}

// The planner's blocks of feed moves as pieces of the program's moves (the run starting at `first`), each
// with the reason of its feed when `reasons` has one per block (--explain).
void add_feed_pieces(const planner::PlanResult& result, std::size_t first, const std::vector<gcode::WrittenMove>& written,
                     const std::vector<std::string>& reasons, std::vector<gcode::FeedPiece>& pieces) {
  for (std::size_t k = 0; k < result.blocks.size(); ++k) {
    const planner::PlannedBlock& block = result.blocks[k];
    if (!(block.feed_mm_per_min > 0.0)) continue;
    if (written[first + static_cast<std::size_t>(block.move_index)].fixed_feed) continue;  // a drilling cycle's F
    pieces.push_back({block.move_index + static_cast<int>(first), result.program.path.moves[k], block.feed_mm_per_min,
                      k < reasons.size() ? reasons[k] : std::string()});
  }
}

// A tool run with its text lines, as the output files see it (the plan moved in when there is one).
RecordedRun recorded_run(const OptimizeOptions& o, const OptimizeInputs& in, const ToolRun& run) {
  RecordedRun r;
  r.run = run;
  r.first_line = in.written[run.first].line;
  r.last_line = in.written[run.end - 1].line;
  r.drilling = true;
  r.context.tool = run.tool;
  r.context.material = o.material;
  return r;
}

// The report context of a planned run: the input program as its source, the re-fed one as its program.
planner::PlanReportContext run_context(const OptimizeOptions& o, const ToolRun& run, const PlannedRun& p) {
  const mdb::ModelRecord& record = p.kind.mechanistic ? *p.kind.mechanistic : p.chosen.record;
  planner::PlanReportContext context;
  context.spec_path = stored_path(o.program_path);
  context.cycle = "program";
  context.tool = run.tool;
  context.material = o.material;
  context.model_id = record.id;
  context.model_version = record.version;
  context.model_tool = record.tool_name;
  context.model_material = record.material_name;
  context.model_match = p.chosen.explanation;
  context.model_match_status = model_db::to_string(p.chosen.borrowing.status);
  for (const model_db::ModelDifference& d : p.chosen.borrowing.differences) {
    context.model_differences.push_back(d.property + " " + d.used + " for " + d.wanted);
  }
  context.model_relative_uncertainty = p.settings.uncertainty ? planning_uncertainty(p.kind, o.model_uncertainty) : 0.0;
  context.model_kind_reason = p.kind.reason;
  context.database_path = stored_path(database_path(o.db_path));
  context.program_path = o.output_path;
  context.dialect = "as read";
  return context;
}

// The planned run moved into its record for the output files.
void record_plan(const OptimizeOptions& o, const OptimizeInputs& in, const ToolRun& run, PlannedRun&& p, RecordedRun& r) {
  r.drilling = false;
  r.model_kind_reason = p.kind.reason;
  r.context = run_context(o, run, p);
  r.input_cycle_time_s = p.input.cycle_time_s;
  r.input_peak_force_n = p.input.peak_force_n;
  r.sample_lines.reserve(p.result.samples.size());
  for (const planner::PlannedSample& sample : p.result.samples) {
    r.sample_lines.push_back(in.written[run.first + static_cast<std::size_t>(sample.move_index)].line);
  }
  r.settings = std::move(p.settings);
  r.result = std::move(p.result);
}

std::string seconds(double s) { return fixed_number_text(s, 2) + " s"; }

void print_run(const OptimizeOptions& o, const OptimizeInputs& in, const ToolRun& run, const PlannedRun& p) {
  const planner::PlanResult& result = p.result;
  std::printf("%s, lines %d–%d: %s (D%s, %d flutes) at S%s\n",
              run_name(run).c_str(), in.written[run.first].line,
              in.written[run.end - 1].line, run.tool.name.c_str(), shortest_number_text(run.tool.diameter_mm).c_str(),
              run.tool.flutes, shortest_number_text(run.spindle_rpm).c_str());
  for (const std::string& warning : p.geometry.engagement.warnings) std::printf("  warning: %s\n", warning.c_str());
  std::printf("  model: id %lld v%d (%s in %s) — %s\n", static_cast<long long>(p.chosen.record.id), p.chosen.record.version,
              p.chosen.record.tool_name.c_str(), p.chosen.record.material_name.c_str(), p.chosen.explanation.c_str());
  std::printf("  kind: %s\n", p.kind.reason.c_str());
  std::printf("  status: %s\n", planner::to_string(result.status).c_str());
  for (const std::string& message : result.messages) std::printf("    %s\n", message.c_str());
  std::printf("  planned: cycle time %s (cutting %s), predicted peak %s N, F %s–%s mm/min\n",
              seconds(result.summary.cycle_time_s).c_str(), seconds(result.summary.cutting_time_s).c_str(),
              fixed_number_text(result.summary.max_predicted_force_n, 1).c_str(),
              shortest_number_text(result.summary.min_feed_mm_per_min).c_str(),
              shortest_number_text(result.summary.max_feed_mm_per_min).c_str());
  if (p.unconstrained_s) {
    std::printf("  controller-friendly blocks (F levels %s %% apart, at least %s s each): %+.1f %% time against the "
                "plan with every acceleration ramp written out (%s)\n",
                shortest_number_text(100.0 * o.feed_step).c_str(), shortest_number_text(o.min_block_duration_s).c_str(),
                100.0 * (result.summary.cycle_time_s - *p.unconstrained_s) / *p.unconstrained_s,
                seconds(*p.unconstrained_s).c_str());
  }
  std::printf("  input: cycle time %s, predicted peak %s N (%+.1f %% time re-fed)\n", seconds(p.input.cycle_time_s).c_str(),
              fixed_number_text(p.input.peak_force_n, 1).c_str(),
              100.0 * (result.summary.cycle_time_s - p.input.cycle_time_s) / p.input.cycle_time_s);
}

void print_operations(const std::vector<ProgramOperation>& operations, const std::vector<OperationFigures>& figures) {
  std::printf("per operation (predicted): time input → re-fed, peak force input → re-fed\n");
  for (std::size_t k = 0; k < operations.size(); ++k) {
    const ProgramOperation& op = operations[k];
    const OperationFigures& f = figures[k];
    if (!f.planned && !f.drilling) continue;  // rapids only
    std::printf("  lines %d–%d %s: ", op.first_line, op.last_line, op.name.c_str());
    if (!f.planned) {
      std::printf("feeds kept as written (drilling)\n");
      continue;
    }
    std::printf("%s → %s, %s → %s N\n", seconds(f.input_s).c_str(), seconds(f.refed_s).c_str(),
                fixed_number_text(f.input_peak_n, 1).c_str(), fixed_number_text(f.refed_peak_n, 1).c_str());
  }
}

// The record the output files show, before any run is planned.
OptimizeRecord new_record(const OptimizeOptions& o, const OptimizeInputs& in) {
  OptimizeRecord record;
  record.program_path = o.program_path;
  record.output_path = o.output_path;
  record.material = o.material;
  record.target_force_n = *o.target_force_n;
  record.stock_path = o.stock_path;
  record.stock = in.stock;
  if (!in.stock_box_mm.empty()) record.stock_box_mm = in.stock_box_mm;
  record.operations = program_operations(in.text, in.written);
  record.figures.resize(record.operations.size());
  return record;
}

// The re-fed program (unless a plan was refused) with --report, --csv and --plot, staged and put in place
// together; a refused plan writes only the files that do not exist yet. Returns the exit code.
int write_optimize_outputs(const OptimizeOptions& o, const OptimizeRecord& record, const std::string& refed_text) {
  OutputFiles outputs;
  if (!record.refused) outputs.add(o.output_path, refed_text);
  stage_optimize_files(o, record, outputs);
  const std::string error = outputs.commit(record.refused ? ExistingFile::kKeep : ExistingFile::kReplace);
  for (const std::string& path : outputs.kept()) {
    std::cerr << "feedplan: note: " << path << " exists: left as it was (a run that fails writes only new files)\n";
  }
  if (!error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return kExitFailed;
  }
  if (record.refused) {
    std::printf("not written: the target cannot be met everywhere, or the safety check refuses a plan (above)\n");
    return kExitFailed;
  }
  for (const std::string& path : outputs.written()) std::printf("wrote %s\n", path.c_str());
  return 0;
}

}  // namespace

void add_optimize_command(CLI::App& app, OptimizeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "optimize", "Re-feed a program another system wrote: the same program with only its F words changed or added, "
                  "every feed move planned to hold the target force on the engagement its moves cut");
  cmd->add_option("PROGRAM", o.program_path, "the G-code program (RS274/NGC)")->required();
  cmd->add_option("-o", o.output_path, "the re-fed program to write");
  cmd->add_option("--tool", o.tool_text, "the end mill of a program of one tool: diameter_mm=…,flutes=…,helix_deg=…[,max_plunge_feed_per_tooth_mm=…][,name=…]");
  cmd->add_option("--tools", o.tools_path,
                  "the end mill of each T number (tools: {2: {diameter_mm: 6.35, flutes: 2, helix_deg: 30}, ...})");
  cmd->add_option("--material", o.material, "workpiece material (a name or alias in the model database)");
  cmd->add_option("--stock", o.stock_path, "the stock: a stock YAML, or a cycle spec whose stock is used");
  cmd->add_option("--stock-box", o.stock_box, "the stock as a block: X0,Y0,Z0,X1,Y1,Z1 in mm");
  add_number_flag(cmd, "--target-force", o.target_force_n, "per-revolution peak XY force to hold, N");
  add_number_flag(cmd, "--spindle-rpm", o.spindle_rpm, "spindle speed, rev/min (default: the program's S)");
  add_number_flag(cmd, "--max-feed", o.max_feed_mm_per_min, "the machine's largest feed, mm/min (default 10000)");
  add_number_flag(cmd, "--min-feed", o.min_feed_mm_per_min, "the lowest feed to write, mm/min (default 10)");
  cmd->add_option("--db", o.db_path, "model database (default: $FEEDPLAN_DB, else the sample database)");
  add_integer_flag(cmd, "--model-id", o.model_id, "plan with this stored model version (see feedplan db list)");
  cmd->add_option("--model-kind", o.model_kind,
                  "mechanistic or response-surface (default: mechanistic where the path leaves the response "
                  "surface's fitted engagement, else the kind that predicted untested engagements better)");
  add_number_flag(cmd, "--cautious", o.model_uncertainty,
                  "hold F̂·(1 + 2r) at the target (default: r from how far the model is borrowed)");
  add_number_flag(cmd, "--ds", o.ds_mm, "engagement sample spacing, mm (default 0.05)");
  add_number_flag(cmd, "--feed-step", o.feed_step,
                  "F levels this far apart, blocks cut from the feed limits (default 0.02; 0: every acceleration ramp "
                  "written out)");
  add_number_flag(cmd, "--min-block-s", o.min_block_duration_s,
                  "shortest block with --feed-step, s (default 0.006: at most 167 F changes a second)");
  cmd->add_flag("--explain", o.explain,
                "write why every new F is what it is as a comment with it: (F: force 300 N at 58 deg engagement),\n"
                "(F: plunge limit 0.025 mm/tooth), (F: model range, chip 0.120 mm), (F: machine max feed), (F: air),\n"
                "(F: acceleration); before the line's own comments, which LinuxCNC keeps acting on");
  cmd->add_option("--report", o.report_path,
                  "write the report (JSON): the input, tools, material, stock, target, each tool run's plan and model, "
                  "and the per-operation table");
  cmd->add_option("--csv", o.csv_path,
                  "write every tool run's plan per sample (CSV, one file: the plan CSV's columns, then tool and line)");
  cmd->add_option("--plot", o.plot_path,
                  "write engagement, feed and predicted force along the path (SVG, the tool runs one after the other)");
}

int run_optimize_command(const OptimizeOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  const OptimizeInputs in = read_inputs(o);
  const mdb::Store store = mdb::Store::open(database_path(o.db_path), mdb::OpenMode::kReadOnly);
  std::printf("%s: %zu moves (%zu lines), target %s N, %zu tool%s\n", o.program_path.c_str(), in.program.path.moves.size(),
              static_cast<std::size_t>(std::count(in.text.begin(), in.text.end(), '\n')),
              shortest_number_text(*o.target_force_n).c_str(), in.runs.size(), in.runs.size() == 1 ? "" : " runs");
  for (const std::string& note : in.program.notes) std::printf("note: %s\n", note.c_str());
  // What --report, --csv and --plot show: the plans are kept only when one of them is asked for.
  const bool record_plans = !o.report_path.empty() || !o.csv_path.empty() || !o.plot_path.empty();
  OptimizeRecord record = new_record(o, in);
  // Each tool's moves on the material the tools before it left.
  geometry::Stock stock = in.stock;
  std::vector<gcode::FeedPiece> pieces;
  double cycle_time_s = 0.0;
  std::vector<std::size_t> operation_of_move(in.written.size());
  for (std::size_t k = 0; k < record.operations.size(); ++k) {
    for (std::size_t m = record.operations[k].first_move; m < record.operations[k].end_move; ++m) operation_of_move[m] = k;
  }
  for (const ToolRun& run : in.runs) {
    if (rapids_only(in.program, run)) continue;
    RecordedRun recorded = recorded_run(o, in, run);
    if (feeds_kept(in.program, in.written, run)) {  // a drilling tool: its holes come out of the stock, its feeds stay
      std::printf("%s, lines %d–%d: drilling cycles, feeds kept as written; holes of Ø%s mm cut from the stock\n",
                  run_name(run).c_str(), in.written[run.first].line,
                  in.written[run.end - 1].line, shortest_number_text(run.tool.diameter_mm).c_str());
      stock = geometry::after_cutting(stock, run_path(in.program, run), run.tool.radius_mm());
      for (std::size_t m = run.first; m < run.end; ++m) record.figures[operation_of_move[m]].drilling = true;
      if (record_plans) record.runs.push_back(std::move(recorded));
      continue;
    }
    std::optional<PlannedRun> planned = plan_run(o, in, run, store, stock);
    if (!planned) return kExitFailed;
    print_run(o, in, run, *planned);
    add_operation_figures(run, planned->result, planned->input, operation_of_move, record.figures);
    const std::vector<std::string> reasons =
        o.explain ? planner::block_feed_reason_texts(planned->geometry, planned->settings, planned->result)
                  : std::vector<std::string>{};
    add_feed_pieces(planned->result, run.first, in.written, reasons, pieces);
    cycle_time_s += planned->result.summary.cycle_time_s;
    record.refused = record.refused || planned->result.status == planner::PlanStatus::kTargetNotMet ||
                     planned->result.status == planner::PlanStatus::kUnsafe;
    stock = geometry::after_cutting(stock, planned->geometry.path, run.tool.radius_mm());
    if (record_plans) {
      record_plan(o, in, run, std::move(*planned), recorded);
      record.runs.push_back(std::move(recorded));
    }
  }
  print_operations(record.operations, record.figures);
  const gcode::RefeedResult refed = gcode::refeed_text(in.text, in.program, in.written, pieces);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::printf("planned cycle time %s; re-fed: %d lines changed, %d lines added (%d moves split where their feed "
              "changes), %d moves at their lowest feed (not split: incremental, multi-turn, compensated, or one of several "
              "moves of a line); %.2f s\n",
              seconds(cycle_time_s).c_str(), refed.lines_changed, refed.lines_added, refed.moves_split,
              refed.moves_at_lowest_feed, wall_s);
  record.refed = {std::string(), refed.lines_changed, refed.lines_added, refed.moves_split, refed.moves_at_lowest_feed};
  if (record.refused) record.output_path.clear();
  return write_optimize_outputs(o, record, refed.text);
}

}  // namespace feedplan::cli
