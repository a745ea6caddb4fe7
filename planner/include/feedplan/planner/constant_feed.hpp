#pragma once
// The constant-feed program: the cycle's own moves with one F on every feed move — what a CAM programmer
// runs without a planner, and the baseline a planned program is compared with on the machine (or the
// virtual one). The plan's own estimate of one such baseline (the one F with the plan's predicted peak
// force) is PlanSummary::baseline (feed_plan.hpp); predict_constant_feed gives the same prediction for
// any F, e.g. the feed a spec says a CAM programmer would use.

#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! The constant-feed program for `path`: the same moves in the same order (part names kept), one block
//! per move with F = `feed_mm_per_min` on every feed move (lines and arcs, cutting or not) and F = 0 on
//! rapids, the spindle turning clockwise (M3) at `spindle_rpm` throughout. Needs a feed the machine can
//! run (in its [min, max] feed range; the caller checks, the value is not changed here) and
//! `spindle_rpm` > 0. Never fails; an empty path gives an empty program.
geometry::Program constant_feed_program(const geometry::ToolPath& path, double feed_mm_per_min, double spindle_rpm);

//! What the controller model predicts for a constant-feed program.
struct ConstantFeedPrediction {
  double feed_mm_per_min = 0.0;  //!< its F on every feed move, mm/min
  double cycle_time_s = 0.0;     //!< predicted cycle time, s
  double cutting_time_s = 0.0;   //!< of which on cutting moves, s
  double peak_force_n = 0.0;     //!< largest force the model predicts at the speed run, N
};

//! The controller model of feed_plan.hpp (look-ahead at `accel_mm_per_s2`, exact stops, v² ≤ a·R on arcs
//! with the machine's acceleration, rapids at the rapid rate) running the constant-feed program of
//! `geometry`'s path at `feed_mm_per_min`, and the force `settings.model` predicts along it (with
//! settings.force_correction when given). Pass PlanSummary::accel_used_mm_per_s2 as the acceleration to
//! compare with a plan on equal terms. Needs what plan() needs (valid settings, a feed > 0).
ConstantFeedPrediction predict_constant_feed(const PlanGeometry& geometry, const PlanSettings& settings,
                                             double feed_mm_per_min, double accel_mm_per_s2);

}  // namespace feedplan::planner
