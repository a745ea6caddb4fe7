#pragma once
// Internal to the planner: cutting the command profile into blocks of constant F (feed_plan.hpp step 3).

#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner::detail {

//! What the split needs besides the profile.
struct BlockSplitSettings {
  PlanMode mode = PlanMode::kSafe;          //!< min (safe) or mean (regulate) of the profile per block
  double merge_tolerance = 0.02;            //!< relative spread merged into one block
  double feed_resolution_mm_per_min = 1.0;  //!< F rounded down to a multiple of this, mm/min
  double block_time_min_s = 0.002;          //!< shortest block, s (whole moves may be shorter)
  //! Blocks lasting less than this are counted as short (the machine's block time; the controller-friendly
  //! rule's longer shortest block is a choice, not a limit of the machine), s.
  double short_block_s = 0.002;
  double min_feed_mm_per_min = 10.0;        //!< no F below this, mm/min
  double accel_mm_per_s2 = 6500.0;          //!< for the pass over neighbouring blocks, mm/s²
  //! The controller-friendly rule (PlanOptions::feed_step > 0): each move cut into the blocks of least time
  //! under the profile among those whose blocks all last at least block_time_min_s (a move that lasts
  //! less is one block), instead of the merge-tolerance rule.
  bool least_time = false;
  //! With least_time: every F (after the acceleration pass too) rounded down onto the levels
  //! level_top_mm_per_min·(1 + level_step)^−k; 0: the feed resolution only.
  double level_step = 0.0;
  double level_top_mm_per_min = 0.0;
};

//! Splits every move into blocks. `s_mm` and `command_mm_per_min` have one value per sample (node);
//! move_first_sample[m] is the first sample of move m and move_first_sample.back() the last sample, so
//! that move m spans nodes [move_first_sample[m], move_first_sample[m + 1]]. Rapids become one block
//! with F = 0. Returns the blocks in path order with move_index, first/last sample, F and length set.
std::vector<PlannedBlock> split_blocks(const geometry::ToolPath& path, const std::vector<double>& s_mm,
                                       const std::vector<double>& command_mm_per_min,
                                       const std::vector<int>& move_first_sample, const BlockSplitSettings& settings,
                                       int& short_blocks);

}  // namespace feedplan::planner::detail
