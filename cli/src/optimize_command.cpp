#include "optimize_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include "database_path.hpp"
#include "model_choice.hpp"
#include "number_flag.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "tool_flag.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::cli {
namespace {

namespace mdb = model_db;

constexpr int kExitFailed = 1;

// --stock-box X0,Y0,Z0,X1,Y1,Z1: a block of material, corners in any order.
geometry::Stock stock_box(const std::string& text, std::vector<InputProblem>& problems) {
  std::vector<double> v;
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
  geometry::Tool tool;
  geometry::Stock stock;
  double spindle_rpm = 0.0;
  geometry::MachineLimits machine;
};

// The spindle speed the feeds are planned for: --spindle-rpm, else the one S of the program's feed moves.
double spindle_speed(const OptimizeOptions& o, const geometry::Program& program, std::vector<InputProblem>& problems) {
  if (o.spindle_rpm) return *o.spindle_rpm;
  double rpm = 0.0;
  int line = 0;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    if (program.path.moves[i].kind == geometry::MoveKind::kRapid) continue;
    const geometry::BlockCommand& b = program.blocks[i];
    if (rpm == 0.0) {
      rpm = b.spindle_rpm;
      line = b.source_line;
    } else if (b.spindle_rpm != rpm) {
      problems.push_back({"PROGRAM", "line " + std::to_string(b.source_line) + " runs S" + shortest_number_text(b.spindle_rpm) +
                                         ", line " + std::to_string(line) + " S" + shortest_number_text(rpm) +
                                         ": the feeds are planned for one spindle speed; split the program where S "
                                         "changes, or give --spindle-rpm"});
      return rpm;
    }
  }
  if (!(rpm > 0.0)) {
    problems.push_back({"PROGRAM", "sets no spindle speed (S) for its feed moves: give --spindle-rpm"});
  }
  return rpm;
}

OptimizeInputs read_inputs(const OptimizeOptions& o) {
  OptimizeInputs in;
  std::vector<InputProblem> problems;
  if (o.output_path.empty()) problems.push_back({"-o", "is required: the re-fed program to write"});
  if (o.tool_text.empty()) problems.push_back({"--tool", "is required, e.g. --tool diameter_mm=6,flutes=3,helix_deg=35"});
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
  if (!o.tool_text.empty()) in.tool = parse_tool(o.tool_text, problems);
  if (!o.stock_box.empty()) in.stock = stock_box(o.stock_box, problems);
  if (o.max_feed_mm_per_min) in.machine.max_feed_mm_per_min = *o.max_feed_mm_per_min;
  if (o.min_feed_mm_per_min) in.machine.min_feed_mm_per_min = *o.min_feed_mm_per_min;
  for (InputProblem problem : geometry::validate(in.machine)) {
    problem.field = problem.field == "machine.max_feed_mm_per_min" ? "--max-feed"
                    : problem.field == "machine.min_feed_mm_per_min" ? "--min-feed"
                                                                     : problem.field;
    problems.push_back(problem);
  }
  check_outputs({{"PROGRAM", o.program_path}, {"--db", database_path(o.db_path)}, {"--stock", o.stock_path}},
                {{"-o", o.output_path}}, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  gcode::ReaderOptions reader;
  in.text = read_input_file(o.program_path, {"a G-code program of a milling job", reader.max_file_bytes,
                                             "ReaderOptions::max_file_bytes"});
  in.program = gcode::read_program(in.text, o.program_path, reader, in.written);
  if (!o.stock_path.empty()) in.stock = cycles::load_stock_spec(o.stock_path);
  in.spindle_rpm = spindle_speed(o, in.program, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return in;
}

// The plan's settings: the model, the cautious bound when it is borrowed (or --cautious).
planner::PlanSettings settings_for(const OptimizeOptions& o, const OptimizeInputs& in, const ChosenModel& chosen) {
  planner::PlanSettings settings;
  settings.model = chosen.record.model;
  const double r = planning_uncertainty(chosen, o.model_uncertainty);
  if (r > 0.0) {
    planner::ForceUncertainty uncertainty;
    uncertainty.covariance = chosen.record.fit.covariance;
    uncertainty.sigmas = kBorrowedModelSigmas;
    uncertainty.relative = r;
    settings.uncertainty = uncertainty;
  }
  settings.target_force_n = *o.target_force_n;
  settings.spindle_rpm = in.spindle_rpm;
  settings.machine = in.machine;
  settings.options.ds_mm = o.ds_mm;
  settings.options.coordinate_resolution_mm = in.program.coordinate_resolution_mm;
  settings.options.feed_step = o.feed_step;
  settings.options.min_block_duration_s = o.min_block_duration_s;
  return settings;
}

// The planner's blocks of feed moves as pieces of the program's moves.
std::vector<gcode::FeedPiece> feed_pieces(const planner::PlanResult& result) {
  std::vector<gcode::FeedPiece> pieces;
  for (std::size_t k = 0; k < result.blocks.size(); ++k) {
    const planner::PlannedBlock& block = result.blocks[k];
    if (!(block.feed_mm_per_min > 0.0)) continue;
    pieces.push_back({block.move_index, result.program.path.moves[k], block.feed_mm_per_min});
  }
  return pieces;
}

// The one F of every feed move of the input, or 0 when they differ.
double single_input_feed(const geometry::Program& program) {
  double feed = 0.0;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    if (program.path.moves[i].kind == geometry::MoveKind::kRapid) continue;
    if (feed == 0.0) feed = program.blocks[i].feed_mm_per_min;
    if (program.blocks[i].feed_mm_per_min != feed) return 0.0;
  }
  return feed;
}

std::string seconds(double s) { return fixed_number_text(s, 2) + " s"; }

void print_summary(const OptimizeOptions& o, const OptimizeInputs& in, const ChosenModel& chosen,
                   const planner::PlanGeometry& geometry, const planner::PlanSettings& settings,
                   const planner::PlanResult& result, const std::optional<double>& unconstrained_s,
                   const gcode::RefeedResult& refed, double wall_s) {
  std::printf("%s: %zu moves (%zu lines), tool %s, target %s N at S%s\n", o.program_path.c_str(),
              in.program.path.moves.size(), static_cast<std::size_t>(std::count(in.text.begin(), in.text.end(), '\n')),
              in.tool.name.c_str(), shortest_number_text(settings.target_force_n).c_str(),
              shortest_number_text(in.spindle_rpm).c_str());
  for (const std::string& note : in.program.notes) std::printf("note: %s\n", note.c_str());
  for (const std::string& warning : geometry.engagement.warnings) std::printf("warning: %s\n", warning.c_str());
  std::printf("model: id %lld v%d (%s in %s) — %s\n", static_cast<long long>(chosen.record.id), chosen.record.version,
              chosen.record.tool_name.c_str(), chosen.record.material_name.c_str(), chosen.explanation.c_str());
  std::printf("status: %s\n", planner::to_string(result.status).c_str());
  for (const std::string& message : result.messages) std::printf("  %s\n", message.c_str());
  std::printf("planned: cycle time %s (cutting %s), predicted peak %s N, F %s–%s mm/min\n",
              seconds(result.summary.cycle_time_s).c_str(), seconds(result.summary.cutting_time_s).c_str(),
              fixed_number_text(result.summary.max_predicted_force_n, 1).c_str(),
              shortest_number_text(result.summary.min_feed_mm_per_min).c_str(),
              shortest_number_text(result.summary.max_feed_mm_per_min).c_str());
  if (unconstrained_s) {
    std::printf("controller-friendly blocks (F levels %s %% apart, at least %s s each): %+.1f %% time against the plan "
                "with every acceleration ramp written out (%s)\n",
                shortest_number_text(100.0 * o.feed_step).c_str(), shortest_number_text(o.min_block_duration_s).c_str(),
                100.0 * (result.summary.cycle_time_s - *unconstrained_s) / *unconstrained_s, seconds(*unconstrained_s).c_str());
  }
  if (const double feed = single_input_feed(in.program); feed > 0.0) {
    const planner::ConstantFeedPrediction input = planner::predict_constant_feed(geometry, settings, feed, result.summary.accel_used_mm_per_s2);
    std::printf("input: F%s on every feed move: cycle time %s, predicted peak %s N (%+.1f %% time re-fed)\n",
                shortest_number_text(std::round(feed * 10) / 10).c_str(), seconds(input.cycle_time_s).c_str(),
                fixed_number_text(input.peak_force_n, 1).c_str(),
                100.0 * (result.summary.cycle_time_s - input.cycle_time_s) / input.cycle_time_s);
  } else {
    std::printf("input: several F words (its cycle time is not predicted here; run both programs with feedplan "
                "simulate to compare)\n");
  }
  std::printf("re-fed: %d lines changed, %d lines added (%d moves split where their feed changes), %d moves at "
              "their lowest feed (not split: incremental or multi-turn)\n",
              refed.lines_changed, refed.lines_added, refed.moves_split, refed.moves_at_lowest_feed);
  std::printf("planned in %.2f s\n", wall_s);
}

}  // namespace

void add_optimize_command(CLI::App& app, OptimizeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "optimize", "Re-feed a program another system wrote: the same program with only its F words changed or added, "
                  "every feed move planned to hold the target force on the engagement its moves cut");
  cmd->add_option("PROGRAM", o.program_path, "the G-code program (RS274/NGC)")->required();
  cmd->add_option("-o", o.output_path, "the re-fed program to write");
  cmd->add_option("--tool", o.tool_text, "the end mill: diameter_mm=…,flutes=…,helix_deg=…[,name=…]");
  cmd->add_option("--material", o.material, "workpiece material (a name or alias in the model database)");
  cmd->add_option("--stock", o.stock_path, "the stock: a stock YAML, or a cycle spec whose stock is used");
  cmd->add_option("--stock-box", o.stock_box, "the stock as a block: X0,Y0,Z0,X1,Y1,Z1 in mm");
  add_number_flag(cmd, "--target-force", o.target_force_n, "per-revolution peak XY force to hold, N");
  add_number_flag(cmd, "--spindle-rpm", o.spindle_rpm, "spindle speed, rev/min (default: the program's S)");
  add_number_flag(cmd, "--max-feed", o.max_feed_mm_per_min, "the machine's largest feed, mm/min (default 10000)");
  add_number_flag(cmd, "--min-feed", o.min_feed_mm_per_min, "the lowest feed to write, mm/min (default 10)");
  cmd->add_option("--db", o.db_path, "model database (default: $FEEDPLAN_DB, else the sample database)");
  add_integer_flag(cmd, "--model-id", o.model_id, "plan with this stored model version (see feedplan db list)");
  add_number_flag(cmd, "--cautious", o.model_uncertainty,
                  "hold F̂·(1 + 2r) at the target (default: r from how far the model is borrowed)");
  add_number_flag(cmd, "--ds", o.ds_mm, "engagement sample spacing, mm (default 0.05)");
  add_number_flag(cmd, "--feed-step", o.feed_step,
                  "F levels this far apart, blocks cut from the feed limits (default 0.02; 0: every acceleration ramp "
                  "written out)");
  add_number_flag(cmd, "--min-block-s", o.min_block_duration_s, "shortest block with --feed-step, s (default 0.02)");
}

int run_optimize_command(const OptimizeOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  const OptimizeInputs in = read_inputs(o);
  const std::string db_path = database_path(o.db_path);
  const mdb::Store store = mdb::Store::open(db_path, mdb::OpenMode::kReadOnly);
  cycles::CycleSpec spec;  // what the model choice reads: the tool and the material
  spec.tool = in.tool;
  spec.material = o.material;
  spec.spindle_rpm = in.spindle_rpm;
  spec.machine = in.machine;
  const std::optional<ChosenModel> chosen = choose_model(store, spec, o.model_id);
  if (!chosen) return kExitFailed;
  const planner::PlanGeometry geometry = planner::analyse(in.program.path, in.stock, in.tool, o.ds_mm);
  const planner::PlanSettings settings = settings_for(o, in, *chosen);
  const planner::PlanResult result = planner::plan(geometry, settings);
  std::optional<double> unconstrained_s;  // the cycle time of the plan with every ramp written out
  if (settings.options.feed_step > 0.0) {
    planner::PlanSettings unconstrained = settings;
    unconstrained.options.feed_step = 0.0;
    unconstrained_s = planner::plan(geometry, unconstrained).summary.cycle_time_s;
  }
  const gcode::RefeedResult refed = gcode::refeed_text(in.text, in.program, in.written, feed_pieces(result));
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  print_summary(o, in, *chosen, geometry, settings, result, unconstrained_s, refed, wall_s);
  if (result.status == planner::PlanStatus::kTargetNotMet || result.status == planner::PlanStatus::kUnsafe) {
    std::printf("not written: %s\n", result.status == planner::PlanStatus::kUnsafe
                                         ? "the safety check refuses the plan (above)"
                                         : "the target cannot be met everywhere (above)");
    return kExitFailed;
  }
  OutputFiles outputs;
  outputs.add(o.output_path, refed.text);
  if (const std::string error = outputs.commit(); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return kExitFailed;
  }
  std::printf("wrote %s\n", o.output_path.c_str());
  return 0;
}

}  // namespace feedplan::cli
