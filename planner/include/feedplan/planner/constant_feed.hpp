#pragma once
// The constant-feed program: the cycle's own moves with one F on every feed move — what a CAM programmer
// runs without a planner, and the baseline a planned program is compared with on the machine (or the
// virtual one). The plan's own estimate of that baseline (the one F with the plan's peak force, its cycle
// time) is PlanSummary::baseline (feed_plan.hpp).

#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::planner {

//! The constant-feed program for `path`: the same moves in the same order (part names kept), one block
//! per move with F = `feed_mm_per_min` on every feed move (lines and arcs, cutting or not) and F = 0 on
//! rapids, the spindle turning clockwise (M3) at `spindle_rpm` throughout. Needs a feed the machine can
//! run (in its [min, max] feed range; the caller checks, the value is not changed here) and
//! `spindle_rpm` > 0. Never fails; an empty path gives an empty program.
geometry::Program constant_feed_program(const geometry::ToolPath& path, double feed_mm_per_min, double spindle_rpm);

}  // namespace feedplan::planner
