#include "feedplan/planner/constant_feed.hpp"

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

}  // namespace feedplan::planner
