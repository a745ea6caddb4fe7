#pragma once
// Moves for the geometry tests: a cutting arc from its centre, radius, start angle and sweep.

#include <cmath>

#include "feedplan/geometry/move.hpp"

namespace feedplan::geometry::testing {

//! A cutting arc at height z_mm (axial depth −z_mm): counter-clockwise (G3) or clockwise from `from_rad`.
inline Move arc(Point2 center, double radius_mm, double from_rad, double sweep_rad, bool ccw, double z_mm) {
  Move m;
  m.kind = MoveKind::kArc;
  m.center = center;
  m.ccw = ccw;
  m.sweep_rad = sweep_rad;
  const double to_rad = from_rad + (ccw ? sweep_rad : -sweep_rad);
  m.start = {center.x_mm + radius_mm * std::cos(from_rad), center.y_mm + radius_mm * std::sin(from_rad), z_mm};
  m.end = {center.x_mm + radius_mm * std::cos(to_rad), center.y_mm + radius_mm * std::sin(to_rad), z_mm};
  m.cutting = true;
  m.axial_depth_mm = -z_mm;
  return m;
}

}  // namespace feedplan::geometry::testing
