#pragma once
// Learning along a program's path drawn as one self-contained SVG: every cycle so far, over path length s:
//   1. force, N: the peak measured at each place in every cycle (one line per cycle, lighter the older),
//      the target (dashed green) and, when given, the force the next plan predicts (dashed black);
//   2. feed in the cut, mm/min: the feed every cycle's plan predicted at each place in the material, and the
//      next plan's (air moves and rapids would only set the scale).
// The legend names each cycle with the predicted cycle time of its plan. Places not measured are gaps.
//
// Element ids for tools and tests: the panels are <g id="panel-force"> and "panel-feed"; each cycle's
// series is a <path> with classes "measured cycle-K" (force) and "feed cycle-K" (feed), the next plan's
// "next-force" and "next-feed", the target a <line class="target">.

#include <string>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/path_history.hpp"

namespace feedplan::planner {

//! What to draw besides the history.
struct PathHistoryPlotOptions {
  std::string title;            //!< text above the panels (XML-escaped); empty: "Learning along the path"
  double width_px = 1200.0;     //!< SVG width, px (≥ 400)
  double height_px = 800.0;     //!< SVG height, px (≥ 400)
  const PlanResult* next = nullptr;  //!< the plan for the next part (same samples), or none
};

//! The plot (the panels at the top of this file). `s_mm` is every plan sample's path length, as many as
//! each history array holds. Sizes below the minimum are programmer errors (assert); an empty history still
//! gives both panels, with a "no data" note.
std::string path_history_svg(const std::vector<double>& s_mm, const std::vector<PathHistoryCycle>& history,
                             double target_force_n, const PathHistoryPlotOptions& options = {});

}  // namespace feedplan::planner
