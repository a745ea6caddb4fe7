#pragma once
// Rectangular pocket with rounded corners, cut with the canned cycles of seed 003 Fig. 3 in this
// order: helical boring, spiral expansion, trochoidal slots, corner rounding (a clean-up of each
// corner and semi-finishing contours), wall finishing.
//
// Notation: W, H the pocket's size along X and Y, L = max(W, H) the long and S = min(W, H) the short
// side, C the centre, a the finishing allowance, D = 2r the tool diameter, R_c the corner radius,
// α_max = 55° the engagement the corner rounding and the wall pass are laid out for (closed forms of
// docs/method.md §5.1). The long axis is X when W ≥ H, otherwise Y.
//   (a) boring: a helical boring at C to the full depth, hole diameter D_h = 1.6·D, or 2·R_s when
//       that is smaller (then there is no spiral);
//   (b) spiral: expands the bore to R_s = S/2 − a (tool-centre radius R_s − r);
//   (c) slots: two trochoid slots from C along the long axis, first towards +, then towards −, loop
//       radius R_t = R_s − r (so a slot is as wide as the spiral), last loop centres O± at
//       ±(L − S)/2 — the slot ends reach L/2 − a. Skipped when the pocket is square (L = S). The
//       trochoid pitch is reduced to R_t / 2 if needed to keep loops larger than the pitch;
//   (d) corners: the round slot ends leave most material in the corners (6.5 mm in the sample), which
//       the wall pass's corner arc (radius ρ = R_c − r) cannot take with a bounded engagement. Each
//       corner gets a trochoid along the line from its slot end centre O to its corner centre Q,
//       starting where its loops leave the roughed stadium, ending at Q, loop radius R_q − r and pitch
//       R_c − R_q (at most the trochoid pitch and half the loop radius), with R_c − R_q the radial
//       depth at which the wall pass's corner arc engages α_max (internal-arc form). A disc of radius
//       R_q < R_c about any point of O–Q lies inside the finished outline, so nothing is overcut;
//   (e) semi-finishing: between the stadium and the corner loops, the walls still hold more than a
//       (up to 2.9 mm in the sample); closed contours at offsets from the thickest stock T down to a,
//       in steps of at most r(1 − cos α_max), each like the wall pass (below) but `offset` further in,
//       corner arcs concentric with the finished corners (radius R_c − r − offset, at least 0.1·r);
//   (f) walls: the finishing contour at offset r from the finished walls — four straight walls and
//       four corner arcs of radius R_c − r about the corner centres — counter-clockwise (climb); it
//       takes a on the walls and R_c − R_q in the corners.
// Pockets wider than the corners can be finished from (more than 2r of material left) are rejected
// by validate.
//
// Motion steps (z_c = top − depth; every sub-cycle starts and ends at the clearance height):
//   1. boring: the motion of generate_helical_boring (parts "boring: ...");
//   2. spiral: rapid at the clearance height above C, then the motion of generate_spiral ("spiral: ...");
//   3. slots: for each slot, rapid at the clearance height above its first loop, then the motion of
//      generate_trochoid ("slot +x: ...", "slot -x: ..." or +y/-y);
//   4. corners: for each corner that needs it, in the wall pass's order, the motion of
//      generate_trochoid ("corner 1: ...", ..., "corner 4: ...");
//   5. semi-finishing: for each contour, outermost first, the motion of steps 6–8 on that contour
//      ("semi-finish 1: ...", ...); the semicircle of step 6 runs in air where the contour lies inside
//      the roughed stadium;
//   6. walls, entry: rapid above C, down to the feed plane, feed in air down to z_c; a semicircle
//      of diameter S/2 − r from C to the middle E of the first long wall (the wall at −Y when the long
//      axis is X, at +X when it is Y), tangent to the wall at E — in air until the tool reaches the
//      roughed surface, cutting from there ("walls: lead-in");
//   7. walls: from E along wall 1, corner 1, wall 2, ..., corner 4, and the rest of wall 1 back to E
//      ("walls: wall 1", "walls: corner 1", ..., "walls: wall 1 end"), cutting;
//   8. walls, exit: feed in air from E back to C; rapid up to the clearance height.
//
// Implied stock: a solid block, the pocket's rectangle grown by 2·D on each side; z from
// top − (depth + 5) to top. Direction::kCw runs every sub-cycle mirrored (their own kCw) and the wall
// pass mirrored about the long axis.

#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cycles {

//! Checks a pocket: the tool, a finite centre, positive finite sizes and depth, a corner radius in
//! (r, S/2], a finishing allowance in (0, r), pitches in (0, D), a short side of at least
//! D + 2a + 0.1·D (room for the tool, the allowance on both walls and the centre bore), and a short
//! side small enough that no material more than 2r from the walls is left in the corners. Fields are
//! named "pocket.<field>" and "tool.<field>".
std::vector<InputProblem> validate(const PocketSpec& spec, const geometry::Tool& tool);

//! Generates the pocket described above below `z.top_z_mm` as one ToolPath, with its implied stock
//! (the solid block before any sub-cycle). Throws InputError with validate's problems when the input
//! is invalid.
Cycle generate_pocket(const PocketSpec& spec, const geometry::Tool& tool, const ZLevels& z = {});

}  // namespace feedplan::cycles
