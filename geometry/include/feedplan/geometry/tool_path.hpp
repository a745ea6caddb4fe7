#pragma once
// The path of the tool centre that a cycle generator emits: moves in order, each labelled with the
// cycle part it belongs to.

#include <string>
#include <vector>

#include "feedplan/geometry/move.hpp"

namespace feedplan::geometry {

//! The ordered moves of one or more cycles.
struct ToolPath {
  std::vector<Move> moves;              //!< in execution order; each starts where the previous ends
  std::vector<std::string> part_names;  //!< names of cycle parts ("approach", "loop 3", "spiral"), by Move::part
};

//! Radius of an arc's XY circle, mm (0 for lines and rapids).
double arc_radius_mm(const Move& move);

//! Length of the move's XY projection, mm.
double xy_length_mm(const Move& move);

//! Length of the move in space (what a feed rate F is measured along), mm.
double length_mm(const Move& move);

//! Total length of the path in space, mm.
double length_mm(const ToolPath& path);

//! Tool tip position at `fraction` ∈ [0, 1] of the move (by length).
Point3 point_at(const Move& move, double fraction);

//! Direction of XY travel at `fraction` of the move, radians counter-clockwise from +X. For a pure
//! z move (no XY travel) returns NaN.
double tangent_angle_rad(const Move& move, double fraction);

//! Checks the path's internal consistency (continuity within `tolerance_mm`, arc end points on
//! their circle, positive sweeps, valid part indices). Returns a description of each defect; empty
//! when the path is consistent. Generators and readers call this before handing a path on.
std::vector<std::string> consistency_defects(const ToolPath& path, double tolerance_mm = 1e-6);

}  // namespace feedplan::geometry
