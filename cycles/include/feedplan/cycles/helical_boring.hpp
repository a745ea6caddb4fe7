#pragma once
// Helical boring into solid material: the first cycle of seed 003 Fig. 3.
//
// The tool centre runs on the circle of radius ρ = (D_h − D) / 2 about O, down a helix of pitch p.
// With D_h ≤ 2D the tool covers the centre, so no core is left.
//
// Motion steps:
//   1. (entry) start at the clearance height above O + (ρ, 0); rapid down to the feed plane; feed in
//      air down to the stock top;
//   2. (helix turn 1..m) m = ceil(depth / p) counter-clockwise helix turns, one move per turn, each
//      descending p; the last turn is partial (sweep 2π·(depth − (m − 1)·p) / p) when depth / p is not
//      an integer, so the helix ends exactly at top − depth;
//   3. (bottom circle) one full circle at top − depth that cleans up the ramp;
//   4. (exit) feed in air to O; rapid up to the clearance height.
// Helix turns and the bottom circle are cutting moves with axial_depth_mm = p.
//
// Engagement on a helix is evaluated on the layer one pitch deep that the previous turn left
// (docs/method.md §5.2, geometry::compute_engagement); cutting with the end of the tool while it ramps is
// not modelled.
//
// Implied stock: a solid square block of half-size D_h / 2 + 2·D about O; z from top − (depth + 5) to
// top. Direction::kCw mirrors the cycle about the X axis through O.

#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cycles {

//! Checks a helical boring: the tool, a finite centre, a hole diameter in (D, 2D] (a larger hole
//! leaves an uncut core), a pitch in (0, D) and a positive depth. Fields are named
//! "helical_boring.<field>" and "tool.<field>".
std::vector<InputProblem> validate(const HelicalBoringSpec& spec, const geometry::Tool& tool);

//! Generates the helical boring described above below `z.top_z_mm`, with its implied stock. Throws
//! InputError with validate's problems when the input is invalid.
Cycle generate_helical_boring(const HelicalBoringSpec& spec, const geometry::Tool& tool, const ZLevels& z = {});

}  // namespace feedplan::cycles
