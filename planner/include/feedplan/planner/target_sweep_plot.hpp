#pragma once
// The time-versus-target curve (target_sweep.hpp) as one self-contained SVG: two panels over the target, N —
//   1. predicted cycle time, s;
//   2. largest predicted per-revolution peak, N, with the line peak = target dashed.
// Each planned target is a marker on a polyline; a target the model cannot meet everywhere (status "target not
// met") is drawn as a hollow red marker, and the smallest target met everywhere that its plan reports as a
// dashed vertical line (the force floor's consequence). Element ids for tools and tests: <g id="panel-time">,
// "panel-peak"; the series <polyline class="cycle-time"> and "max-peak", markers <circle class="planned"> or
// "not-met", the floor <line class="floor">.

#include <string>
#include <vector>

#include "feedplan/planner/target_sweep.hpp"

namespace feedplan::planner {

//! The SVG text of `rows` (at least one, in increasing target), titled `title` (XML-escaped).
std::string target_sweep_svg(const std::vector<TargetSweepRow>& rows, const std::string& title);

}  // namespace feedplan::planner
