#include "move_chain.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::geometry::detail {

namespace {

// Points and centres closer than this are the same, mm; directions and pitches agree to this, relative.
// Blocks a planner splits a move into meet exactly up to rounding (1e-12 mm); a CAM's polyline has
// corners many orders of magnitude larger.
constexpr double kSamePointMm = 1e-9;
constexpr double kSameDirection = 1e-9;

double distance_mm(const Point3& a, const Point3& b) {
  return std::sqrt((a.x_mm - b.x_mm) * (a.x_mm - b.x_mm) + (a.y_mm - b.y_mm) * (a.y_mm - b.y_mm) +
                   (a.z_mm - b.z_mm) * (a.z_mm - b.z_mm));
}

bool same_line(const Move& move, const Move& next) {
  const double ax = move.end.x_mm - move.start.x_mm, ay = move.end.y_mm - move.start.y_mm,
               az = move.end.z_mm - move.start.z_mm;
  const double bx = next.end.x_mm - next.start.x_mm, by = next.end.y_mm - next.start.y_mm,
               bz = next.end.z_mm - next.start.z_mm;
  const double na = std::sqrt(ax * ax + ay * ay + az * az), nb = std::sqrt(bx * bx + by * by + bz * bz);
  if (!(na > 0.0 && nb > 0.0)) return false;
  const double cx = ay * bz - az * by, cy = az * bx - ax * bz, cz = ax * by - ay * bx;
  return ax * bx + ay * by + az * bz > 0.0 && std::sqrt(cx * cx + cy * cy + cz * cz) <= kSameDirection * na * nb;
}

bool same_circle(const Move& move, const Move& next) {
  if (move.ccw != next.ccw || !(move.sweep_rad > 0.0 && next.sweep_rad > 0.0)) return false;
  if (std::hypot(move.center.x_mm - next.center.x_mm, move.center.y_mm - next.center.y_mm) > kSamePointMm) return false;
  if (std::abs(arc_radius_mm(move) - arc_radius_mm(next)) > kSamePointMm) return false;
  const double pitch = (move.end.z_mm - move.start.z_mm) / move.sweep_rad;
  const double next_pitch = (next.end.z_mm - next.start.z_mm) / next.sweep_rad;
  return std::abs(pitch - next_pitch) <= kSameDirection * std::max({1.0, std::abs(pitch), std::abs(next_pitch)});
}

// The measure fractions of a move are linear in: length for lines, sweep for arcs.
double measure(const Move& move) { return move.kind == MoveKind::kArc ? move.sweep_rad : length_mm(move); }

}  // namespace

bool continues(const Move& move, const Move& next) {
  if (move.kind != next.kind || move.cutting != next.cutting || move.part != next.part ||
      move.axial_depth_mm != next.axial_depth_mm) {
    return false;
  }
  if (distance_mm(move.end, next.start) > kSamePointMm) return false;
  return move.kind == MoveKind::kArc ? same_circle(move, next) : same_line(move, next);
}

MoveChains join_continuations(const std::vector<Move>& moves) {
  MoveChains chains;
  chains.places.resize(moves.size());
  std::size_t first = 0;
  while (first < moves.size()) {
    std::size_t last = first;
    while (last + 1 < moves.size() && continues(moves[last], moves[last + 1])) ++last;
    Move joined = moves[first];
    joined.end = moves[last].end;
    double total = 0.0;
    for (std::size_t i = first; i <= last; ++i) total += measure(moves[i]);
    if (joined.kind == MoveKind::kArc) joined.sweep_rad = total;
    const std::size_t chain = chains.joined.size();
    double start = 0.0;
    for (std::size_t i = first; i <= last; ++i) {
      const double share = last == first || !(total > 0.0) ? 1.0 : measure(moves[i]) / total;
      chains.places[i] = {chain, last == first ? 0.0 : start, share};
      start += share;
    }
    chains.joined.push_back(joined);
    first = last + 1;
  }
  return chains;
}

}  // namespace feedplan::geometry::detail
