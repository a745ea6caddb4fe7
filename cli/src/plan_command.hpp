#pragma once
// `feedplan plan SPEC.yaml -o PROGRAM.nc [--db PATH] [--target-force N] [--dialect …] [--report PLAN.json]
// [--csv PLAN.csv] [--plot PLAN.svg] …`: the main job — a cycle, the closest model in the database and a
// target force → a G-code program whose F words hold the predicted force at the target.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::cli {

struct PlanCommandOptions {
  std::string spec_path;              //!< the cycle spec (YAML)
  std::string program_path;           //!< -o: the G-code program to write
  std::string db_path;                //!< --db; empty: $FEEDPLAN_DB, else the sample database
  std::optional<double> target_force_n;  //!< --target-force; unset: the spec's target_force_n
  std::string dialect = "linuxcnc";   //!< --dialect linuxcnc | fanuc | haas
  std::string report_path;            //!< --report: JSON summary
  std::string csv_path;               //!< --csv: per-sample CSV
  std::string plot_path;              //!< --plot: SVG
  std::string html_path;              //!< --html: the self-contained HTML report
  std::string mode = "safe";          //!< --mode safe | regulate
  std::optional<double> air_feed_mm_per_min;  //!< --air-feed; unset: the machine's maximum feed
  double merge_tolerance = 0.02;      //!< --merge-tolerance
  double feed_resolution_mm_per_min = 1.0;  //!< --feed-resolution
  double feed_step = planner::kControllerFriendlyFeedStep;  //!< --feed-step: controller-friendly F levels (0: off)
  //! --min-block-s: shortest block of the controller-friendly rule, s
  double min_block_duration_s = planner::kControllerFriendlyMinBlockS;
  std::optional<double> jerk_limit_mm_per_s3;  //!< --jerk; unset: no jerk limit
  double ds_mm = 0.05;                //!< --ds: engagement sample spacing
  std::optional<std::int64_t> model_id;  //!< --model-id; unset: the closest active model
  std::optional<double> model_uncertainty;  //!< --cautious r; unset: from how far the model is borrowed
  std::string model_kind;  //!< --model-kind mechanistic|response-surface; empty: the lower cross-validated error
  int decimals = 3;                   //!< --decimals
  bool line_numbers = false;          //!< --line-numbers
  bool coolant = false;               //!< --coolant
  bool no_safe_return = false;        //!< --no-safe-return: end without the return to the machine's Z home
  int tool_number = 1;                //!< --tool-number
  int work_offset = 54;               //!< --work-offset (54..59, 0: none)
  int program_number = 1000;          //!< --program-number (Fanuc/Haas O word)
  bool json = false;                  //!< --json: summary as JSON on stdout
  bool simulate = false;              //!< --simulate: run the program on the virtual machine and compare
  std::optional<double> constant_feed_mm_per_min;  //!< --constant-feed: write this one F on every feed move instead
  std::string materials_path;         //!< --materials: the virtual machine's materials file
  std::string target_sweep;           //!< --target-sweep FROM:TO:STEP: plan at each target, print the curve, write no program
  bool explain = false;               //!< --explain: `(F: <reason>)` beside every F word of the program
  bool part_comments = false;         //!< --part-comments: a comment line before the first block of each cycle part
};

//! Registers the subcommand.
void add_plan_command(CLI::App& app, PlanCommandOptions& options);

//! Runs the command. Returns 0 (planned), 1 (failed: no model for the material, or the target cannot be
//! met — the program is then not written); throws InputError on bad input before anything is written. With
//! --target-sweep: plans at every target, prints the curve (and --plot draws it), writes no program; 0.
int run_plan_command(const PlanCommandOptions& options);

}  // namespace feedplan::cli
