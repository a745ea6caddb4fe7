#pragma once
// What `feedplan optimize --report R.json --csv C.csv --plot P.svg` writes besides the re-fed program:
//
// Report (JSON, "format": "feedplan-optimize", "format_version": 1), keys in this order:
//   format, format_version, status ("ok", or "refused" when a tool run's plan cannot be written), program
//   (the input, absolute), output (-o, absolute; "" when refused), material, target_force_n,
//   stock {file (absolute) | box_mm [X0, Y0, Z0, X1, Y1, Z1]; z_bottom_mm, z_top_mm},
//   summary {cycle_time_s (the planned runs' cycle times added up, as the summary prints it),
//            input_cycle_time_s, max_predicted_force_n, input_max_predicted_force_n, lines_changed,
//            lines_added, moves_split, moves_at_lowest_feed},
//   runs [{tool_number (−1: the moves before any tool change), first_line, last_line, drilling (feeds kept
//          as written; no plan), model_kind_reason, plan (planner::plan_report_json of the run: tool,
//          material, model, target, machine, options, summary, blocks; spec and program name the input and
//          output G-code)}],
//   operations [{name, first_line, last_line, planned, drilling, input_time_s, refed_time_s,
//                input_peak_force_n, refed_peak_force_n}]  (the table the summary prints; the times of all
//                operations add up to summary.cycle_time_s and summary.input_cycle_time_s)
// The per-run plans are in the plan report's format, but `feedplan learn` re-plans a cycle spec and does
// not read them.
//
// CSV: one file for the whole program, the tool runs one after the other in program order: the columns of
// planner::plan_samples_csv, then `tool` (the run's T number, empty before any tool change) and `line` (the
// input program line of the sample's move). s_mm, time_s and block count from the start of each run.
//
// Plot: one SVG for the whole program (planner::plan_plot_svg), the runs one after the other along the path.

#include <optional>
#include <string>
#include <vector>

#include "operation_figures.hpp"
#include "optimize_command.hpp"
#include "output_files.hpp"
#include "program_operations.hpp"
#include "tool_runs.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/plan_report.hpp"

namespace feedplan::cli {

//! One tool run as the output files see it.
struct RecordedRun {
  ToolRun run;                               //!< its moves and tool
  int first_line = 0;                        //!< text lines of its first and last move
  int last_line = 0;
  bool drilling = false;                     //!< feeds kept as written: no plan
  std::string model_kind_reason;             //!< which kind of model planned and why
  planner::PlanResult result;                //!< the plan (empty when drilling)
  planner::PlanSettings settings;            //!< what it was asked to do
  planner::PlanReportContext context;        //!< the report's context of the run
  std::vector<int> sample_lines;             //!< per plan sample, the input line of its move
  double input_cycle_time_s = 0.0;           //!< the run at the input's feeds, s
  double input_peak_force_n = 0.0;           //!< largest predicted force at the input's feeds, N
};

//! Everything optimize's output files show.
struct OptimizeRecord {
  std::string program_path;                  //!< the input program
  std::string output_path;                   //!< -o ("" when the re-fed program is not written)
  std::string material;                      //!< --material
  double target_force_n = 0.0;               //!< --target-force, N
  std::string stock_path;                    //!< --stock ("" with --stock-box)
  geometry::Stock stock;                     //!< the stock before the first tool
  std::optional<std::vector<double>> stock_box_mm;  //!< --stock-box's six numbers
  std::vector<RecordedRun> runs;             //!< every tool run that cuts, in program order
  std::vector<ProgramOperation> operations;  //!< the summary's operations
  std::vector<OperationFigures> figures;     //!< their figures, one per operation
  gcode::RefeedResult refed;                 //!< what the re-feed changed (its text unused)
  bool refused = false;                      //!< a run's plan cannot be written
};

//! The report (format at the top of this file), indented by 2, ending in a newline.
std::string optimize_report_json(const OptimizeRecord& record);

//! The CSV of every planned run (columns at the top of this file).
std::string optimize_samples_csv(const OptimizeRecord& record);

//! The plot of every planned run, one after the other along the path.
std::string optimize_plot_svg(const OptimizeRecord& record);

//! Stages --report, --csv and --plot of `options` (those given) in `files`.
void stage_optimize_files(const OptimizeOptions& options, const OptimizeRecord& record, OutputFiles& files);

}  // namespace feedplan::cli
