#pragma once
// `feedplan optimize PROGRAM.nc -o OUT.nc --tool … --material … (--stock STOCK.yaml | --stock-box …)
// --target-force N`: a program another system wrote, re-fed — the same text with only its F words changed
// or added (gcode/refeed.hpp), every feed move planned under the target on the engagement the program's
// own moves cut out of the stock.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::cli {

struct OptimizeOptions {
  std::string program_path;           //!< the G-code program to re-feed
  std::string output_path;            //!< -o: the re-fed program
  std::string tool_text;              //!< --tool diameter_mm=…,flutes=…,helix_deg=…[,name=…] (one tool)
  std::string tools_path;             //!< --tools: the end mill of each T number (cycles/spec_reader.hpp)
  std::string material;               //!< --material: name or alias in the model database
  std::string stock_path;             //!< --stock: stock YAML (or a cycle spec, whose stock is used)
  std::string stock_box;              //!< --stock-box X0,Y0,Z0,X1,Y1,Z1 in mm
  std::optional<double> target_force_n;  //!< --target-force
  std::optional<double> spindle_rpm;  //!< --spindle-rpm; unset: the program's S on its feed moves
  std::optional<double> max_feed_mm_per_min;  //!< --max-feed; unset: the machine default
  std::optional<double> min_feed_mm_per_min;  //!< --min-feed; unset: the machine default
  std::string db_path;                //!< --db; empty: $FEEDPLAN_DB, else the sample database
  std::optional<std::int64_t> model_id;  //!< --model-id
  std::string model_kind;                //!< --model-kind mechanistic|response-surface (empty: model_kind_choice.hpp)
  std::optional<double> model_uncertainty;  //!< --cautious r
  double ds_mm = 0.05;                //!< --ds
  //! --feed-step: controller-friendly F levels (0: blocks follow the command profile)
  double feed_step = planner::kControllerFriendlyFeedStep;
  //! --min-block-s: shortest block of the controller-friendly rule, s
  double min_block_duration_s = planner::kControllerFriendlyMinBlockS;
  bool explain = false;               //!< --explain: `(F: <reason>)` with every F word written
  std::string report_path;            //!< --report: the optimize report (JSON, optimize_outputs.hpp)
  std::string csv_path;               //!< --csv: every tool run's plan per sample (CSV)
  std::string plot_path;              //!< --plot: engagement, feed and predicted force along the path (SVG)
};

//! Registers the subcommand.
void add_optimize_command(CLI::App& app, OptimizeOptions& options);

//! Runs the command: 0 written, 1 failed (no model, the target cannot be met, an output cannot be
//! written); throws InputError on bad input before anything is written. The re-fed program, --report, --csv
//! and --plot are staged and put in place together: an error leaves every existing output as it was. When
//! the target cannot be met (or the safety check refuses a plan) the program is not written, and the
//! report, CSV and plot go only to files that do not exist yet.
int run_optimize_command(const OptimizeOptions& options);

}  // namespace feedplan::cli
