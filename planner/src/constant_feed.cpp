#include "feedplan/planner/constant_feed.hpp"

#include <algorithm>
#include <cassert>

#include "feedplan/planner/feed_prediction.hpp"

namespace feedplan::planner {

geometry::Program constant_feed_program(const geometry::ToolPath& path, double feed_mm_per_min, double spindle_rpm) {
  geometry::Program program;
  program.path = path;
  for (const geometry::Move& move : path.moves) {
    geometry::BlockCommand block;
    block.feed_mm_per_min = move.kind == geometry::MoveKind::kRapid ? 0.0 : feed_mm_per_min;
    block.spindle_rpm = spindle_rpm;
    block.spindle = geometry::SpindleDirection::kClockwise;
    program.blocks.push_back(block);
  }
  return program;
}

ConstantFeedPrediction predict_constant_feed(const PlanGeometry& geometry, const PlanSettings& settings,
                                             double feed_mm_per_min, double accel_mm_per_s2) {
  assert(feed_mm_per_min > 0.0);
  ConstantFeedPrediction out;
  out.feed_mm_per_min = feed_mm_per_min;
  if (geometry.engagement.samples.size() < 2) return out;
  const FeedPrediction run = predict_feeds(
      geometry, settings, std::vector<double>(geometry.path.moves.size(), feed_mm_per_min), accel_mm_per_s2);
  out.cycle_time_s = run.cycle_time_s;
  out.cutting_time_s = run.cutting_time_s;
  out.peak_force_n = run.peak_force_n;
  return out;
}

}  // namespace feedplan::planner
