#pragma once
// Trochoidal slotting (seed 003 Fig. 7, Table 2).
//
// Slot axis u = (end − start) / |end − start|, left normal v. With n = ceil(|end − start| / p) the
// loop centres are c_k = start + k·p'·u, k = 0..n, p' = |end − start| / n ≤ p (a note says so when
// p' < p), so there are n + 1 loops; seed 003's Table 2 (start [0, 0], end [9, 0], p 1) has 10. Loop k
// starts at b_k = c_k − R_t·v, runs one full counter-clockwise circle (sweep 2π) about c_k back to b_k,
// and steps straight to b_{k+1}; the step is tangent to both circles, so the path has no corners. The
// tool edge reaches R_t + r from the axis: the slot is 2(R_t + r) wide. Material is on the right of
// the feed (climb milling, M3): the front of the slot is cut at the +u side of each circle.
//
// Motion steps:
//   1. (entry) start at the clearance height above b_0; rapid down to the feed plane;
//   2. (entry) feed down in air to z = top − A_d at b_0, which is outside the stock;
//   3. (loop 1) full circle about c_0;
//   4. (loop k + 1, k = 1..n) straight step b_{k−1} → b_k, then the full circle about c_k;
//   5. (exit) feed in air from b_n to the loop centre c_n; rapid up to the clearance height.
// Cutting moves carry axial_depth_mm = A_d; loops are cutting moves, steps 1, 2 and 5 are not.
//
// Implied stock: a block from an entry face perpendicular to u at c_0 + (R_t + r − p')·u — so loop 1
// cuts a cap one pitch deep, like every later loop — to c_n + (R_t + 3r)·u, and ±(R_t + 3r) across
// the axis; z from top − (A_d + 5) to top. Direction::kCw mirrors path and stock about the slot axis
// (loops start at c_k + R_t·v and turn clockwise).

#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cycles {

//! Checks a trochoid: the tool (validate_tool), a positive finite axial depth, finite start and end
//! that differ, pitch in (0, tool diameter) — a pitch of a diameter or more leaves uncut material
//! between loops — and a loop radius > pitch (smaller loops make the step between loops cut solid
//! material). Fields are named "trochoid.<field>", "tool.<field>" and "axial_depth_mm".
std::vector<InputProblem> validate(const TrochoidSpec& spec, const geometry::Tool& tool, double axial_depth_mm);

//! Generates the trochoid described above at depth `axial_depth_mm` below `z.top_z_mm`, with its
//! implied stock. Throws InputError with validate's problems when the input is invalid.
Cycle generate_trochoid(const TrochoidSpec& spec, const geometry::Tool& tool, double axial_depth_mm,
                        const ZLevels& z = {});

}  // namespace feedplan::cycles
