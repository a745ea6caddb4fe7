#pragma once
// The plot of a strategy comparison (`feedplan compare`, compare.svg), as self-contained SVG: one panel per
// row, stacked, each the row's true per-revolution peaks of |F_xy| against time with the target drawn —
// every panel on the same axes (time from 0 to the longest cycle, force from 0 to above the largest peak of
// all rows), so that the rows can be read against each other at a glance.

#include <string>

#include "feedplan/trial/strategy_comparison.hpp"

namespace feedplan::trial {

//! What to draw besides the data.
struct ComparisonPlotOptions {
  std::string title = "Strategies on the virtual machine";  //!< text above the panels
  double width_px = 1200.0;        //!< SVG width, px (≥ 400)
  double panel_height_px = 140.0;  //!< height of one row's panel, px (≥ 60)
};

//! The SVG text for `comparison` (its target > 0, asserted, as the sizes). A row without revolutions gets
//! its axes and a "no data" note.
std::string comparison_plot_svg(const StrategyComparison& comparison, const ComparisonPlotOptions& options = {});

}  // namespace feedplan::trial
