#pragma once
// What the controller model and the force model predict for a program run at given feeds: one F per move,
// as a program from another system carries them (feedplan optimize compares its input with the plan this
// way, operation by operation), or one F on every feed move (constant_feed.hpp).

#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! The prediction along the path's engagement samples.
struct FeedPrediction {
  double cycle_time_s = 0.0;     //!< predicted cycle time, s
  double cutting_time_s = 0.0;   //!< of which on cutting moves, s
  double peak_force_n = 0.0;     //!< largest force the model predicts at the speed run, N
  std::vector<double> time_s;    //!< time at each sample from the start, s
  std::vector<double> force_n;   //!< force the model predicts at each sample, N (0 where not engaged)
};

//! The controller model of feed_plan.hpp (look-ahead at `accel_mm_per_s2`, exact stops, v² ≤ a·R on arcs
//! with the machine's acceleration, rapids at the rapid rate) running `geometry`'s path with the F of
//! `move_feed_mm_per_min` (one per move of the path, mm/min; rapids' values are not read), and the force
//! `settings.model` (or settings.mechanistic) predicts along it, with settings.force_correction when given.
//! Needs what plan() needs (valid settings) and a feed > 0 for every feed move.
FeedPrediction predict_feeds(const PlanGeometry& geometry, const PlanSettings& settings,
                             const std::vector<double>& move_feed_mm_per_min, double accel_mm_per_s2);

}  // namespace feedplan::planner
