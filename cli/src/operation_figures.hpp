#pragma once
// The figures `feedplan optimize` reports per operation of the program (program_operations.hpp): its
// predicted time and largest predicted force at the input's own feeds and at the re-fed ones.

#include <cstddef>
#include <vector>

#include "tool_runs.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/feed_prediction.hpp"

namespace feedplan::cli {

//! One operation's time and largest predicted force, at the input's feeds and at the plan's.
struct OperationFigures {
  double input_s = 0.0;       //!< predicted time at the input's feeds, s
  double refed_s = 0.0;       //!< predicted time at the re-fed feeds, s
  double input_peak_n = 0.0;  //!< largest predicted force at the input's feeds, N
  double refed_peak_n = 0.0;  //!< largest predicted force at the re-fed feeds, N
  bool planned = false;       //!< its moves were planned
  bool drilling = false;      //!< it holds drilling cycles, whose feeds are kept
};

//! Adds the samples of tool run `run` (its plan `result` and `input`, its moves at the input's feeds) to the
//! figures of the operations their moves belong to (`operation_of_move`, indexed by program move): each
//! interval between two samples counts for the operation of the move of its first sample, so the times of
//! all operations add up to the runs' cycle times.
void add_operation_figures(const ToolRun& run, const planner::PlanResult& result, const planner::FeedPrediction& input,
                           const std::vector<std::size_t>& operation_of_move, std::vector<OperationFigures>& figures);

}  // namespace feedplan::cli
