#pragma once
// Arcs in the XZ (G18) and YZ (G19) planes as straight pieces along the exact arc: a Move is a circle in
// XY, so an arc a CAM system writes as a lead-in or a ramp in another plane becomes chords. Internal to
// the gcode module.
//
// The plane's axes as LinuxCNC orders them (interp_convert.cc, convert_arc): G18 takes Z as the first
// axis and X as the second (centre offsets K and I), Y is the helix axis; G19 takes Y first and Z second
// (J and K), X is the helix axis. G3 turns counter-clockwise from the first axis towards the second, G2
// the other way — so a G2 in G18 turns counter-clockwise seen in the usual X-right, Z-up view.

#include <vector>

#include "feedplan/geometry/point.hpp"

namespace feedplan::gcode::detail {

//! The plane of an arc.
enum class ArcPlane { kXZ, kYZ };

//! The point `p` in the plane's coordinates: (first, second) axis.
geometry::Point2 in_plane(ArcPlane plane, const geometry::Point3& p);

//! The point with plane coordinates `q` and helix-axis coordinate `axis_mm`.
geometry::Point3 from_plane(ArcPlane plane, const geometry::Point2& q, double axis_mm);

//! The coordinate along the plane's helix axis (Y in XZ, X in YZ).
double helix_axis(ArcPlane plane, const geometry::Point3& p);

//! Longest piece: no chord deviates more than this from its arc, mm.
inline constexpr double kPlaneArcSagittaMm = 1e-3;
//! Longest piece: no chord spans more than this angle, rad (5°).
inline constexpr double kPlaneArcPieceRad = 5.0 * 3.14159265358979323846 / 180.0;

//! How many pieces plane_arc_points makes of the arc (as a double: a huge radius may need more than an int).
double plane_arc_piece_count(ArcPlane plane, const geometry::Point3& start, const geometry::Point3& end,
                             const geometry::Point2& center, double sweep_rad);

//! The ends of the straight pieces of the arc from `start` to `end` about `center` (plane
//! coordinates) sweeping `sweep_rad` (> 0) in direction `ccw` (in the plane's first→second sense):
//! as many equal angular pieces as make each chord deviate at most kPlaneArcSagittaMm from the arc and
//! span at most kPlaneArcPieceRad, whichever needs more. The radius goes linearly from the start's to
//! the end's (LinuxCNC drives a spiral when they differ within its tolerance), the helix axis linearly
//! with the angle; the last point is `end` exactly.
std::vector<geometry::Point3> plane_arc_points(ArcPlane plane, const geometry::Point3& start, const geometry::Point3& end,
                                               const geometry::Point2& center, bool ccw, double sweep_rad);

}  // namespace feedplan::gcode::detail
