#pragma once
// A plan drawn along its path as one self-contained SVG (in the spirit of seed 003 Figs. 6, 10, 13):
// three panels stacked over a shared x axis — path length s in mm, or predicted time in s:
//   1. engagement angle α_en, deg;
//   2. feed, mm/min: the programmed block F as a step line, the feed the machine is predicted to run,
//      and the feed limit of the planner's step 1 (dotted, cut off at the panel's top);
//   3. predicted force, N, with the target as a dashed line and, when given, measured (or simulated)
//      per-revolution peaks as markers.
// Rapids are gaps in every line (their speed is not a cutting feed). Long series are reduced by min/max
// decimation per pixel column, so a plan of a million samples gives an SVG of a few hundred kB in
// which every peak that full resolution would show is still drawn at its exact value.
//
// Element ids for tools and tests: the panels are <g id="panel-engagement">, "panel-feed",
// "panel-force"; each series is a <path> with a class naming it ("engagement", "block-feed",
// "predicted-feed", "feed-limit", "predicted-force"), the target a <line class="target">, the markers
// a <g class="measured-peaks">. Each panel's y tick labels are <text class="y-tick"> placed at the
// tick's exact y (dominant-baseline middle).

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! What to draw besides the plan.
struct PlanPlotOptions {
  std::string title;          //!< text above the panels (XML-escaped); empty: "Feed plan"
  double width_px = 1200.0;   //!< SVG width, px (≥ 400)
  double height_px = 900.0;   //!< SVG height, px (≥ 400)
  bool x_is_time = false;     //!< x axis: predicted time t in s (true) or path length s in mm (false)
  //! Points (x, force N) drawn as markers on the force panel, x in the x axis' unit (mm or s), e.g.
  //! simulated or measured per-revolution peaks. Points outside the plan's x range are not drawn.
  std::optional<std::vector<std::pair<double, double>>> measured_peaks;
};

//! The plot of `result` as SVG text (the panels at the top of this file). `target_force_n` is drawn on
//! the force panel and labelled "target <value> N". A plan without samples still gives the three panels
//! with a "no data" note. Sizes below the minimum are programmer errors (assert).
std::string plan_plot_svg(const PlanResult& result, double target_force_n, const PlanPlotOptions& options = {});

//! Writes plan_plot_svg(...) to `path` atomically. Returns "" on success, otherwise a message naming
//! the path and the reason; the target is then left as it was.
std::string write_plan_plot(const std::filesystem::path& path, const PlanResult& result, double target_force_n,
                            const PlanPlotOptions& options = {});

}  // namespace feedplan::planner
