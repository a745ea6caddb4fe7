#pragma once
// Spiral internal-cylinder expansion (seed 003 Fig. 12, Table 3): a pre-drilled bore of radius R_init
// about O grows to R_fin.
//
// The tool centre's distance from O grows from ρ0 = R_init − r (the tool touching the bore wall) to
// ρ1 = R_fin − r in n = ceil((ρ1 − ρ0) / p) turns of pitch p' = (ρ1 − ρ0) / n ≤ p (a note says so when
// p' < p). Each turn is two exact semicircles, tangent where they join: turn k + 1 (k = 0..n−1) is
//   - a half-turn about O of radius ρ0 + k·p' from angle 0 to π, then
//   - a half-turn about O' = O + (p'/2, 0) of radius ρ0 + k·p' + p'/2 from angle π to 2π, which ends
//     at O + (ρ0 + (k + 1)·p', 0);
// so the radius about O after each full turn is ρ0 + (k + 1)·p'. The first half of turn 1 runs along
// the bore wall and cuts nothing; the engagement then rises gradually (seed 003 Fig. 13).
//
// Motion steps:
//   1. (entry) start at the clearance height above O; rapid down to the feed plane; feed down in air
//      to z = top − A_d at O (inside the bore); feed in air to O + (ρ0, 0);
//   2. (spiral turn 1..n) the n turns, counter-clockwise;
//   3. (finishing circle) one full circle of radius ρ1 about O;
//   4. (exit) feed in air back to O; rapid up to the clearance height.
// Cutting moves (steps 2, 3) carry axial_depth_mm = A_d.
//
// Implied stock: a square block of half-size R_fin + 2·D about O with a circular hole of radius
// R_init (the bore); z from top − (A_d + 5) to top. Direction::kCw mirrors the cycle about the X axis
// through O.

#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cycles {

//! Checks a spiral: the tool, a positive finite axial depth, a finite centre, an initial radius
//! larger than the tool radius (the tool must fit in the bore), a final radius larger than the
//! initial one, and a pitch in (0, tool diameter). Fields are named "spiral.<field>", "tool.<field>"
//! and "axial_depth_mm".
std::vector<InputProblem> validate(const SpiralSpec& spec, const geometry::Tool& tool, double axial_depth_mm);

//! Generates the spiral described above at depth `axial_depth_mm` below `z.top_z_mm`, with its
//! implied stock. Throws InputError with validate's problems when the input is invalid.
Cycle generate_spiral(const SpiralSpec& spec, const geometry::Tool& tool, double axial_depth_mm,
                      const ZLevels& z = {});

}  // namespace feedplan::cycles
