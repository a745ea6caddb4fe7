#pragma once
// The HTML report of a plan (html_page.hpp), and of a learning history — the plan of the next part with
// every cycle cut so far: the tool path drawn to scale and coloured by feed, predicted force or measured
// per-revolution peak, with a readout of every sample under the pointer; force (target, the model's
// uncertainty band), feed (the machine's limits) and engagement against path length, zoomed together;
// per cycle of a history, its peak error and cycle time and its curves overlaid; the summary and the notes.
//
// The page's data (JSON, read by report_app.js) carries the samples column by column, rounded as the plan
// CSV rounds them (plan_report.hpp): lengths and angles to 4 decimals, chip thickness to 6, feeds and
// forces to 3, times to 6, so the readout shows what the CSV holds.

#include <string>
#include <utility>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/path_history.hpp"

namespace feedplan::report {

//! One line of a summary: what, and its value with its unit ("cycle time", "30.64 s").
using SummaryLine = std::pair<std::string, std::string>;

//! A table: column headings and rows of cells, as text.
struct Table {
  std::vector<std::string> columns;            //!< headings
  std::vector<std::vector<std::string>> rows;  //!< one per row, as many cells as columns
};

//! What the page shows besides the plan itself.
struct PlanPage {
  std::string title;                  //!< the page's heading
  std::vector<SummaryLine> summary;   //!< the summary the command prints, line by line
  std::vector<std::string> notes;     //!< extrapolation, infeasible target, cautious mode, …: one sentence each
  //! Per plan sample, the measured per-revolution peak force there, N (0: none measured); empty: none.
  std::vector<double> measured_peak_n;
  //! A learning history: the parts cut so far, oldest first (path_history.hpp); empty for a plain plan.
  std::vector<planner::PathHistoryCycle> history;
  //! With a history: one row per cycle as the command prints it (peak error, cycle time, …); may be empty.
  Table cycle_table;
};

//! The summary lines every plan has, from its result and settings: status, target, cycle and cutting
//! time, the constant-feed baseline and the time saved against it, the largest predicted force, the
//! feed range, and the sample counts.
std::vector<SummaryLine> plan_summary_lines(const planner::PlanResult& result, const planner::PlanSettings& settings);

//! The report's data as JSON text (the document report_app.js draws; kind "plan", or "history" when
//! page.history is not empty). `page.measured_peak_n` and every history cycle's arrays must be empty or
//! have one value per sample of `result` (asserted).
std::string plan_page_json(const planner::PlanResult& result, const planner::PlanSettings& settings,
                           const PlanPage& page);

//! The whole page: html_page(page.title, plan_page_json(…)).
std::string plan_page_html(const planner::PlanResult& result, const planner::PlanSettings& settings,
                           const PlanPage& page);

}  // namespace feedplan::report
