#pragma once
// The HTML report of a comparison of strategies (`feedplan compare`) on one cycle: the table, and one bar
// chart per figure (largest peak, overshoot, RMS error, cycle time, …) across the strategies.

#include <string>
#include <vector>

#include "feedplan/report/plan_page.hpp"

namespace feedplan::report {

//! One figure every strategy has: its key in the data and its label with the unit.
struct ComparisonFigure {
  std::string key;    //!< e.g. "max_peak_n"
  std::string label;  //!< e.g. "largest per-revolution peak [N]"
};

//! What the comparison page shows.
struct ComparisonPage {
  std::string title;                        //!< the page's heading
  std::vector<SummaryLine> summary;         //!< what was compared, on what, against which target
  std::vector<std::string> notes;           //!< said under the summary
  Table table;                              //!< the table the command prints
  std::vector<std::string> strategies;      //!< the strategies' names, in the table's order
  std::vector<ComparisonFigure> figures;    //!< the figures charted
  //! values[k][j]: figure j of strategy k (NaN: none), as many rows as strategies, as many columns as figures.
  std::vector<std::vector<double>> values;
};

//! The page (html_page.hpp) with kind "comparison". Asserts that values has one row per strategy and one
//! value per figure in each.
std::string comparison_page_html(const ComparisonPage& page);

}  // namespace feedplan::report
