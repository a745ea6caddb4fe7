#include "plane_arc.hpp"

#include <algorithm>
#include <cmath>

namespace feedplan::gcode::detail {

using geometry::Point2;
using geometry::Point3;

Point2 in_plane(ArcPlane plane, const Point3& p) {
  return plane == ArcPlane::kXZ ? Point2{p.z_mm, p.x_mm} : Point2{p.y_mm, p.z_mm};
}

Point3 from_plane(ArcPlane plane, const Point2& q, double axis_mm) {
  return plane == ArcPlane::kXZ ? Point3{q.y_mm, axis_mm, q.x_mm} : Point3{axis_mm, q.x_mm, q.y_mm};
}

double helix_axis(ArcPlane plane, const Point3& p) { return plane == ArcPlane::kXZ ? p.y_mm : p.x_mm; }

double plane_arc_piece_count(ArcPlane plane, const Point3& start, const Point3& end, const Point2& center,
                             double sweep_rad) {
  const Point2 s = in_plane(plane, start);
  const Point2 e = in_plane(plane, end);
  const double r_max = std::max(std::hypot(s.x_mm - center.x_mm, s.y_mm - center.y_mm),
                                std::hypot(e.x_mm - center.x_mm, e.y_mm - center.y_mm));
  // A chord of angle φ on radius r deviates r·(1 − cos(φ/2)) from its arc.
  double piece_rad = kPlaneArcPieceRad;
  if (r_max > kPlaneArcSagittaMm) piece_rad = std::min(piece_rad, 2.0 * std::acos(1.0 - kPlaneArcSagittaMm / r_max));
  return std::max(1.0, std::ceil(sweep_rad / piece_rad - 1e-9));
}

std::vector<Point3> plane_arc_points(ArcPlane plane, const Point3& start, const Point3& end, const Point2& center,
                                     bool ccw, double sweep_rad) {
  const Point2 s = in_plane(plane, start);
  const Point2 e = in_plane(plane, end);
  const double r0 = std::hypot(s.x_mm - center.x_mm, s.y_mm - center.y_mm);
  const double r1 = std::hypot(e.x_mm - center.x_mm, e.y_mm - center.y_mm);
  const int pieces = static_cast<int>(plane_arc_piece_count(plane, start, end, center, sweep_rad));
  const double a0 = std::atan2(s.y_mm - center.y_mm, s.x_mm - center.x_mm);
  const double direction = ccw ? 1.0 : -1.0;
  const double axis0 = helix_axis(plane, start);
  const double axis1 = helix_axis(plane, end);
  std::vector<Point3> points;
  points.reserve(static_cast<std::size_t>(pieces));
  for (int k = 1; k < pieces; ++k) {
    const double t = static_cast<double>(k) / pieces;
    const double angle = a0 + direction * sweep_rad * t;
    const double r = r0 + (r1 - r0) * t;
    points.push_back(from_plane(plane, {center.x_mm + r * std::cos(angle), center.y_mm + r * std::sin(angle)},
                                axis0 + (axis1 - axis0) * t));
  }
  points.push_back(end);
  return points;
}

}  // namespace feedplan::gcode::detail
