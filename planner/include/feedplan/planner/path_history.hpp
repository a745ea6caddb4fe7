#pragma once
// The history of learning along one program's path: for every part cut so far (a cycle of plan → cut →
// learn), what the plan it was cut with predicted and what its force log measured, place by place. It
// travels in the plan report (path_learning.history) from part to part and is drawn by
// path_history_plot.hpp: whether learning closes in on the target, where it does not, and what each
// cycle cost in time.
//
// Places are the plan's samples (every plan of one program has the same ones). Values are kept to 0.1
// (mm/min, N): the report stays small, and no reading is better than that.

#include <cstddef>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! Cycles the history keeps: the newest ones (the report of a long run would otherwise grow without end).
inline constexpr std::size_t kPathHistoryCycles = 8;

//! One part cut and learned from.
struct PathHistoryCycle {
  int cycle = 1;                         //!< 1 for the first part learned from, then 2, 3, …
  double cycle_time_s = 0.0;             //!< the predicted cycle time of the plan it was cut with, s
  std::vector<double> feed_mm_per_min;   //!< per plan sample: the feed that plan predicted there
  std::vector<double> predicted_n;       //!< per plan sample: the force it predicted there
  std::vector<double> measured_n;        //!< per plan sample: the peak force measured there (0: none)
};

//! The entry for a part cut with `plan` whose log measured `measured_n` per plan sample (as many values as
//! plan.samples; 0 where nothing was measured), numbered one after the last of `history`.
PathHistoryCycle history_cycle(const PlanResult& plan, const std::vector<double>& measured_n,
                               const std::vector<PathHistoryCycle>& history);

//! `history` with `next` appended, keeping the newest kPathHistoryCycles.
std::vector<PathHistoryCycle> with_cycle(std::vector<PathHistoryCycle> history, PathHistoryCycle next);

}  // namespace feedplan::planner
