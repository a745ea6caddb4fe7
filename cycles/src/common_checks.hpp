#pragma once
// The checks of a CycleSpec that do not depend on its cycle geometry (tool, cutting conditions,
// machine limits, clearance, stock). validate(CycleSpec) runs them after the geometry's own checks;
// the YAML reader runs them alone when the cycle name is unknown. Internal to the cycles module.

#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/spec.hpp"

namespace feedplan::cycles::detail {

//! Problems with everything in `spec` except `spec.geometry` and the tool (which each generator's
//! validate checks).
std::vector<InputProblem> validate_common(const CycleSpec& spec);

}  // namespace feedplan::cycles::detail
