#pragma once
// The checks of a CycleSpec that do not depend on its cycle geometry (tool, cutting conditions,
// machine limits, clearance, stock). validate(CycleSpec) runs them after the geometry's own checks;
// the YAML reader runs them alone when the cycle name is unknown. Internal to the cycles module.

#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/tool.hpp"
#include "problems.hpp"

namespace feedplan::cycles::detail {

//! Problems with everything in `spec` except `spec.geometry` and the tool (which each generator's
//! validate checks).
std::vector<InputProblem> validate_common(const CycleSpec& spec);

//! What tool.max_plunge_feed_per_tooth_mm means, for its problems.
inline constexpr const char* kPlungeFeedPerToothMeaning =
    "the largest feed per tooth along −Z while the tool descends into material, mm, at most the tool diameter "
    "(leave it out for the default 0.0025 × diameter)";

//! The values tool.max_plunge_feed_per_tooth_mm may take when it is given: (0, D], D the tool diameter
//! (> 0 while the diameter itself is not a finite number > 0, which is reported on its own).
Range plunge_feed_per_tooth_range(const geometry::Tool& tool);

}  // namespace feedplan::cycles::detail
