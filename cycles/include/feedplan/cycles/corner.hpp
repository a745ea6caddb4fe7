#pragma once
// Corner rounding (seed 003 Fig. 5): the finishing pass along two straight walls that meet in an
// internal (concave) corner rounded to the finished radius R.
//
// Wall 1 runs through the corner point K in the entry heading d1; the travel turns left by
// δ = 180° − corner angle onto wall 2 (direction d2). The material is on the right of the feed (climb
// milling, M3); n1, n2 are the left normals (towards the free side). The finished corner arc of
// radius R has its centre Q on the bisector, R / sin(γ/2) from K (γ the corner angle), and touches
// the walls at T1 = K − R·cot(γ/2)·d1 and T2 = K + R·cot(γ/2)·d2. Each straight wall runs
// `wall_length_mm` from its tangent point: wall 1 from s1 = T1 − L_w·d1, wall 2 to e2 = T2 + L_w·d2.
// The tool centre follows the walls at offset r and the corner on an arc of radius R − r about Q.
//
// Motion steps (ℓ = lead, r = tool radius, z_c = top − A_d):
//   1. (approach) start at the clearance height above s1 − ℓ·d1 + r·n1; rapid down to the feed plane;
//      feed down in air to z_c; feed in air along wall 1 until the tool's leading edge reaches the
//      stock's entry face (centre at s1 − r·d1 + r·n1);
//   2. (wall 1) straight cut to T1 + r·n1;
//   3. (corner) counter-clockwise arc about Q, radius R − r, sweep δ, to T2 + r·n2;
//   4. (wall 2) straight cut until the tool's trailing edge leaves the stock's exit face (centre at
//      e2 + r·d2 + r·n2);
//   5. (departure) feed in air to e2 + ℓ·d2 + r·n2; rapid up to the clearance height.
// Steps 2–4 are cutting moves with axial_depth_mm = A_d.
//
// Implied stock (seed 003 Fig. 1b; docs/method.md §5.1): a block from the entry face through s1 to the
// exit face through e2, perpendicular to the walls, reaching 2·D behind the walls into the material,
// minus one earlier pass of the same tool recorded in Stock::removed: the same centre path R_d further
// from the walls (lines at r + R_d, corner arc of radius R − r − R_d about Q, or, when that is not
// positive, the two offset lines meeting in a sharp corner), extended through lead-in and lead-out.
// So the surface left before this pass is R_d deep on the walls and concentric with the finished
// corner — the analytic engagement of docs/method.md §5.1 holds in the steady parts. z from
// top − (A_d + 5) to top. Direction::kCw mirrors path and stock about wall 1's line.

#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cycles {

//! Checks a corner: the tool, a positive finite axial depth, a finite corner point and heading, a
//! corner angle in (0, 180) deg, a corner radius > tool radius (the tool cannot cut a smaller one),
//! a radial depth in (0, D], a positive wall length, a lead > tool radius (the tool must plunge clear
//! of the stock), and an implied stock that is a valid polygon (very sharp corners need longer walls).
//! Fields are named "corner.<field>", "tool.<field>" and "axial_depth_mm".
std::vector<InputProblem> validate(const CornerSpec& spec, const geometry::Tool& tool, double axial_depth_mm);

//! Generates the corner rounding described above at depth `axial_depth_mm` below `z.top_z_mm`, with
//! its implied stock. Throws InputError with validate's problems when the input is invalid.
Cycle generate_corner(const CornerSpec& spec, const geometry::Tool& tool, double axial_depth_mm,
                      const ZLevels& z = {});

}  // namespace feedplan::cycles
