#include "feedplan/geometry/tool_path.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "feedplan/core/angle.hpp"

namespace feedplan::geometry {

namespace {

double start_angle_rad(const Move& move) {
  return std::atan2(move.start.y_mm - move.center.y_mm, move.start.x_mm - move.center.x_mm);
}

}  // namespace

double arc_radius_mm(const Move& move) {
  if (move.kind != MoveKind::kArc) return 0.0;
  return std::hypot(move.start.x_mm - move.center.x_mm, move.start.y_mm - move.center.y_mm);
}

double xy_length_mm(const Move& move) {
  if (move.kind == MoveKind::kArc) return arc_radius_mm(move) * move.sweep_rad;
  return std::hypot(move.end.x_mm - move.start.x_mm, move.end.y_mm - move.start.y_mm);
}

double length_mm(const Move& move) {
  return std::hypot(xy_length_mm(move), move.end.z_mm - move.start.z_mm);
}

double length_mm(const ToolPath& path) {
  double total = 0.0;
  for (const auto& move : path.moves) total += length_mm(move);
  return total;
}

Point3 point_at(const Move& move, double fraction) {
  const double z = move.start.z_mm + fraction * (move.end.z_mm - move.start.z_mm);
  if (move.kind != MoveKind::kArc) {
    return {move.start.x_mm + fraction * (move.end.x_mm - move.start.x_mm),
            move.start.y_mm + fraction * (move.end.y_mm - move.start.y_mm), z};
  }
  const double radius = arc_radius_mm(move);
  const double angle = start_angle_rad(move) + (move.ccw ? 1.0 : -1.0) * fraction * move.sweep_rad;
  return {move.center.x_mm + radius * std::cos(angle), move.center.y_mm + radius * std::sin(angle), z};
}

double tangent_angle_rad(const Move& move, double fraction) {
  if (move.kind != MoveKind::kArc) {
    const double dx = move.end.x_mm - move.start.x_mm;
    const double dy = move.end.y_mm - move.start.y_mm;
    if (std::hypot(dx, dy) == 0.0) return std::numeric_limits<double>::quiet_NaN();
    return std::atan2(dy, dx);
  }
  const double sign = move.ccw ? 1.0 : -1.0;
  const double angle = start_angle_rad(move) + sign * fraction * move.sweep_rad;
  return angle + sign * 0.5 * kPi;
}

std::vector<std::string> consistency_defects(const ToolPath& path, double tolerance_mm) {
  std::vector<std::string> defects;
  auto finite = [](const Point3& p) {
    return std::isfinite(p.x_mm) && std::isfinite(p.y_mm) && std::isfinite(p.z_mm);
  };
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    const Move& m = path.moves[i];
    const std::string where = "move " + std::to_string(i);
    if (!finite(m.start) || !finite(m.end)) defects.push_back(where + ": non-finite coordinate");
    const bool part_ok = path.part_names.empty() ? m.part == 0
                                                 : (m.part >= 0 && static_cast<std::size_t>(m.part) < path.part_names.size());
    if (!part_ok) {
      defects.push_back(where + ": part index " + std::to_string(m.part) + " has no name");
    }
    if (i > 0) {
      const Point3& prev = path.moves[i - 1].end;
      const double gap = std::hypot(std::hypot(prev.x_mm - m.start.x_mm, prev.y_mm - m.start.y_mm), prev.z_mm - m.start.z_mm);
      if (gap > tolerance_mm) defects.push_back(where + ": starts " + std::to_string(gap) + " mm from the previous end");
    }
    if (m.kind == MoveKind::kArc) {
      const double r0 = arc_radius_mm(m);
      const double r1 = std::hypot(m.end.x_mm - m.center.x_mm, m.end.y_mm - m.center.y_mm);
      if (!(r0 > tolerance_mm)) defects.push_back(where + ": arc radius is zero");
      if (std::abs(r0 - r1) > tolerance_mm) defects.push_back(where + ": arc end is off its circle");
      if (!(m.sweep_rad > 0.0) || !std::isfinite(m.sweep_rad)) defects.push_back(where + ": arc sweep must be > 0");
      const Point3 computed_end = point_at(m, 1.0);
      if (std::hypot(computed_end.x_mm - m.end.x_mm, computed_end.y_mm - m.end.y_mm) > 10 * tolerance_mm) {
        defects.push_back(where + ": arc sweep does not reach its end point");
      }
    }
    if (m.axial_depth_mm < 0.0) defects.push_back(where + ": negative axial depth");
  }
  return defects;
}

}  // namespace feedplan::geometry
