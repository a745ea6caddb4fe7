#include "track_cover.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "feedplan/core/angle.hpp"

namespace feedplan::sim::detail {

namespace {

using Interval = std::pair<double, double>;

// Whether the union of `pieces` covers [lo, hi] with gaps no wider than `tolerance`.
bool union_covers(std::vector<Interval> pieces, double lo, double hi, double tolerance) {
  std::sort(pieces.begin(), pieces.end());
  double reached = lo;
  bool started = false;  // some piece reaches from lo (a point needs one too)
  for (const auto& [a, b] : pieces) {
    if (a > reached + tolerance) break;
    if (b < reached) continue;
    reached = b;
    started = true;
    if (reached >= hi - tolerance) return true;
  }
  return started && reached >= hi - tolerance;
}

double angle_about(const geometry::Point2& center, const geometry::Point3& p) {
  double angle = std::atan2(p.y_mm - center.y_mm, p.x_mm - center.x_mm);
  if (angle < 0.0) angle += kTwoPi;
  return angle;
}

// The counter-clockwise angular span, seen from `center`, of an arc whose track runs round `center`
// (its own centre, or one within a tolerance of it): start angle in [0, 2π) and length ≤ 2π.
Interval arc_span(const geometry::Move& move, const geometry::Point2& center) {
  const double from = angle_about(center, move.ccw ? move.start : move.end);
  const double to = angle_about(center, move.ccw ? move.end : move.start);
  // The turn from `from` to `to` nearest to the arc's own sweep (equal to it about its own centre).
  const double length = move.sweep_rad + std::remainder(to - from - move.sweep_rad, kTwoPi);
  return {from, std::clamp(length, 0.0, kTwoPi)};
}

Interval arc_span(const geometry::Move& move) { return arc_span(move, move.center); }

// A span [start, start + length] as pieces of [0, 2π).
void add_unwrapped(std::vector<Interval>& pieces, const Interval& span) {
  const auto& [start, length] = span;
  if (start + length <= kTwoPi) {
    pieces.emplace_back(start, start + length);
  } else {
    pieces.emplace_back(start, kTwoPi);
    pieces.emplace_back(0.0, start + length - kTwoPi);
  }
}

// Whether the pieces cover the span, angles within `tolerance_rad`.
bool covers_span(const std::vector<Interval>& pieces, const Interval& span, double tolerance_rad) {
  std::vector<Interval> wanted;
  add_unwrapped(wanted, span);
  return std::all_of(wanted.begin(), wanted.end(), [&](const Interval& w) {
    return union_covers(pieces, w.first, w.second, tolerance_rad);
  });
}

// How far the XY track of `arc` strays from the circle of `radius_mm` about `center`, mm: the largest
// |distance from the centre − radius| over the track. The distance is extreme at the arc's ends and
// where the arc crosses the line through both centres.
double distance_from_circle_mm(const geometry::Move& arc, const geometry::Point2& center, double radius_mm) {
  auto off = [&](double x, double y) { return std::abs(std::hypot(x - center.x_mm, y - center.y_mm) - radius_mm); };
  double largest = std::max(off(arc.start.x_mm, arc.start.y_mm), off(arc.end.x_mm, arc.end.y_mm));
  const double dx = arc.center.x_mm - center.x_mm;
  const double dy = arc.center.y_mm - center.y_mm;
  if (dx == 0.0 && dy == 0.0) return largest;
  std::vector<Interval> pieces;
  add_unwrapped(pieces, arc_span(arc));
  const double radius = geometry::arc_radius_mm(arc);
  const double away = std::atan2(dy, dx);  // from `center` through the arc's centre
  for (const double angle : {away, away + kPi}) {
    const double wrapped = std::fmod(angle + kTwoPi, kTwoPi);  // in [0, 2π)
    if (!covers_span(pieces, {wrapped, 0.0}, 0.0)) continue;
    largest = std::max(largest, off(arc.center.x_mm + radius * std::cos(wrapped), arc.center.y_mm + radius * std::sin(wrapped)));
  }
  return largest;
}

// Whether the track of `other` runs along the circle of `arc` within `tolerance_mm` (arcs only).
bool on_circle_of(const geometry::Move& arc, const geometry::Move& other, double tolerance_mm) {
  if (other.kind != geometry::MoveKind::kArc) return false;
  return distance_from_circle_mm(other, arc.center, geometry::arc_radius_mm(arc)) <= tolerance_mm;
}

bool has_xy_travel(const geometry::Move& move) { return geometry::xy_length_mm(move) > 1e-9; }

// Distance from (x, y) to the move's XY segment, mm.
double distance_to_segment(const geometry::Move& move, double x, double y) {
  const double dx = move.end.x_mm - move.start.x_mm;
  const double dy = move.end.y_mm - move.start.y_mm;
  const double length2 = dx * dx + dy * dy;
  const double t = length2 > 0.0 ? std::clamp(((x - move.start.x_mm) * dx + (y - move.start.y_mm) * dy) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(x - (move.start.x_mm + t * dx), y - (move.start.y_mm + t * dy));
}

// Whether the point (x, y) lies on the arc's XY track.
bool point_on_arc(const geometry::Move& arc, double x, double y, double tolerance_mm) {
  const double radius = geometry::arc_radius_mm(arc);
  if (std::abs(std::hypot(x - arc.center.x_mm, y - arc.center.y_mm) - radius) > tolerance_mm) return false;
  double angle = std::atan2(y - arc.center.y_mm, x - arc.center.x_mm);
  if (angle < 0.0) angle += kTwoPi;
  std::vector<Interval> pieces;
  add_unwrapped(pieces, arc_span(arc));
  const double tolerance_rad = tolerance_mm / std::max(radius, tolerance_mm);
  return covers_span(pieces, {angle, 0.0}, tolerance_rad);
}

}  // namespace

TrackCover::TrackCover(const geometry::ToolPath& path, double z_lo_mm, double tolerance_mm)
    : path_(path), z_lo_mm_(z_lo_mm), tolerance_mm_(tolerance_mm) {}

bool TrackCover::is_low(std::size_t j) const {
  const geometry::Move& move = path_.moves[j];
  return std::max(move.start.z_mm, move.end.z_mm) <= z_lo_mm_;
}

std::optional<std::size_t> TrackCover::covered_after(std::size_t k) const {
  const geometry::Move& move = path_.moves[k];
  if (move.kind == geometry::MoveKind::kArc) return arc_covered_after(k);
  return has_xy_travel(move) ? segment_covered_after(k) : point_covered_after(k);
}

// Arcs along the same circle (their tracks within the tolerance of it, whatever their own centres),
// their angular spans seen from its centre together over the arc's.
std::optional<std::size_t> TrackCover::arc_covered_after(std::size_t k) const {
  const geometry::Move& arc = path_.moves[k];
  const Interval span = arc_span(arc);
  const double tolerance_rad = tolerance_mm_ / std::max(geometry::arc_radius_mm(arc), tolerance_mm_);
  std::vector<Interval> pieces;
  for (std::size_t j = 0; j < path_.moves.size(); ++j) {
    if (j == k || !is_low(j) || !on_circle_of(arc, path_.moves[j], tolerance_mm_)) continue;
    add_unwrapped(pieces, arc_span(path_.moves[j], arc.center));
    if (covers_span(pieces, span, tolerance_rad)) return j + 1;
  }
  return std::nullopt;
}

// Segments on the same line, their extents together over the segment's.
std::optional<std::size_t> TrackCover::segment_covered_after(std::size_t k) const {
  const geometry::Move& segment = path_.moves[k];
  const double length = std::hypot(segment.end.x_mm - segment.start.x_mm, segment.end.y_mm - segment.start.y_mm);
  const double ux = (segment.end.x_mm - segment.start.x_mm) / length;
  const double uy = (segment.end.y_mm - segment.start.y_mm) / length;
  auto along = [&](const geometry::Point3& q) { return (q.x_mm - segment.start.x_mm) * ux + (q.y_mm - segment.start.y_mm) * uy; };
  auto across = [&](const geometry::Point3& q) { return std::abs(-(q.x_mm - segment.start.x_mm) * uy + (q.y_mm - segment.start.y_mm) * ux); };
  std::vector<Interval> pieces;
  for (std::size_t j = 0; j < path_.moves.size(); ++j) {
    const geometry::Move& other = path_.moves[j];
    if (j == k || !is_low(j) || other.kind == geometry::MoveKind::kArc || !has_xy_travel(other)) continue;
    if (across(other.start) > tolerance_mm_ || across(other.end) > tolerance_mm_) continue;
    pieces.emplace_back(std::min(along(other.start), along(other.end)), std::max(along(other.start), along(other.end)));
    if (union_covers(pieces, 0.0, length, tolerance_mm_)) return j + 1;
  }
  return std::nullopt;
}

// A point (a move without XY travel) on any low move's track.
std::optional<std::size_t> TrackCover::point_covered_after(std::size_t k) const {
  const double x = path_.moves[k].start.x_mm;
  const double y = path_.moves[k].start.y_mm;
  for (std::size_t j = 0; j < path_.moves.size(); ++j) {
    if (j == k || !is_low(j)) continue;
    const geometry::Move& other = path_.moves[j];
    const bool on_track = other.kind == geometry::MoveKind::kArc ? point_on_arc(other, x, y, tolerance_mm_)
                                                                 : distance_to_segment(other, x, y) <= tolerance_mm_;
    if (on_track) return j + 1;
  }
  return std::nullopt;
}

}  // namespace feedplan::sim::detail
