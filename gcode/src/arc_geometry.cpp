#include "arc_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "problem_log.hpp"

namespace feedplan::gcode::detail {

using geometry::Point2;

namespace {

constexpr double kSamePointMm = 1e-9;   // start and end closer than this are one point (full circle)
constexpr double kZeroRadiusMm = 1e-6;  // consistency_defects' tolerance: smaller radii are no circle

double distance_mm(const Point2& a, const Point2& b) { return std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm); }

double angle_rad(const Point2& center, const Point2& p) { return std::atan2(p.y_mm - center.y_mm, p.x_mm - center.x_mm); }

// The point of the perpendicular bisector of start and end nearest to `center` (the centre of a
// circle through both ends that moves the least); nullopt when start and end are one point.
std::optional<Point2> bisector_projection(const Point2& start, const Point2& end, const Point2& center) {
  const double chord = distance_mm(start, end);
  if (chord <= kSamePointMm) return std::nullopt;
  const Point2 unit{(end.x_mm - start.x_mm) / chord, (end.y_mm - start.y_mm) / chord};
  const Point2 middle{0.5 * (start.x_mm + end.x_mm), 0.5 * (start.y_mm + end.y_mm)};
  const double along = (center.x_mm - middle.x_mm) * unit.x_mm + (center.y_mm - middle.y_mm) * unit.y_mm;
  return Point2{center.x_mm - along * unit.x_mm, center.y_mm - along * unit.y_mm};
}

// Start, end and centre of an arc.
struct ArcPoints {
  Point2 start;
  Point2 end;
  Point2 center;
};

// The swept angle of `moved`, an arc a little off `programmed`, whose swept angle is `programmed_sweep_rad`:
// the programmed one plus the turn of the end and minus the turn of the start, each seen from its
// own centre. Taking the programmed sweep keeps full circles and P turns whole when start and end
// move apart by rounding.
double moved_sweep_rad(double programmed_sweep_rad, bool ccw, const ArcPoints& programmed, const ArcPoints& moved) {
  const double end_turn = std::remainder(angle_rad(moved.center, moved.end) - angle_rad(programmed.center, programmed.end), kTwoPi);
  const double start_turn =
      std::remainder(angle_rad(moved.center, moved.start) - angle_rad(programmed.center, programmed.start), kTwoPi);
  const double sweep = programmed_sweep_rad + (ccw ? 1.0 : -1.0) * (end_turn - start_turn);
  return sweep > 0.0 ? sweep : sweep + kTwoPi;
}

}  // namespace

double sweep_rad(const Point2& start, const Point2& end, const Point2& center, bool ccw, int turns) {
  double base = kTwoPi;
  if (distance_mm(start, end) > kSamePointMm) {
    const double a0 = std::atan2(start.y_mm - center.y_mm, start.x_mm - center.x_mm);
    const double a1 = std::atan2(end.y_mm - center.y_mm, end.x_mm - center.x_mm);
    base = std::fmod(ccw ? a1 - a0 : a0 - a1, kTwoPi);
    if (base <= 0.0) base += kTwoPi;
  }
  return base + (turns - 1) * kTwoPi;
}

ArcCircle arc_from_center(const Point2& programmed_start, const Point2& start, const Point2& end, const Point2& center,
                          bool ccw, int turns, double tolerance_mm) {
  ArcCircle arc;
  arc.center = center;
  arc.end = end;
  const double start_radius = distance_mm(programmed_start, center);
  const double end_radius = distance_mm(end, center);
  if (start_radius <= kZeroRadiusMm) {
    arc.problem = "zero radius: the centre (I, J) is the start point";
    return arc;
  }
  const double difference = std::abs(start_radius - end_radius);
  if (difference > tolerance_mm) {
    arc.problem = "end point is " + six_digit_number_text(difference) + " mm off the circle: radius " +
                  six_digit_number_text(start_radius) + " mm at the start, " + six_digit_number_text(end_radius) +
                  " mm at the end (centre X" + six_digit_number_text(center.x_mm) + " Y" + six_digit_number_text(center.y_mm) +
                  " mm; allowed difference " + six_digit_number_text(tolerance_mm) +
                  " mm, ReaderOptions::arc_radius_tolerance_mm)";
    return arc;
  }
  const double radius = distance_mm(start, center);
  const double end_shift = std::abs(radius - end_radius);
  const std::optional<Point2> on_bisector = bisector_projection(start, end, center);
  const double center_shift = on_bisector ? distance_mm(*on_bisector, center) : 0.0;
  if (on_bisector && (center_shift <= end_shift || end_shift > tolerance_mm || end_radius <= kZeroRadiusMm)) {
    arc.center = *on_bisector;
    arc.center_shift_mm = center_shift;
  } else if (end_shift > 0.0) {
    arc.end = {center.x_mm + (end.x_mm - center.x_mm) * radius / end_radius,
               center.y_mm + (end.y_mm - center.y_mm) * radius / end_radius};
    arc.end_shift_mm = end_shift;
  }
  arc.sweep_rad = moved_sweep_rad(sweep_rad(programmed_start, end, center, ccw, turns), ccw,
                                  {programmed_start, end, center}, {start, arc.end, arc.center});
  return arc;
}

ArcCircle arc_from_radius(const Point2& start, const Point2& end, double radius_mm, bool ccw, int turns,
                          double tolerance_mm) {
  ArcCircle arc;
  arc.end = end;
  const double chord = distance_mm(start, end);
  if (chord <= kSamePointMm) {
    arc.problem = "start and end are the same point: R cannot describe a full circle; use I and J";
    return arc;
  }
  const double half_chord = 0.5 * chord;
  const double abs_radius = std::abs(radius_mm);
  if (half_chord - abs_radius > tolerance_mm) {
    arc.problem = "radius " + six_digit_number_text(abs_radius) + " mm is shorter than half the chord (" +
                  six_digit_number_text(half_chord) + " mm): the end point cannot be reached (allowed shortfall " +
                  six_digit_number_text(tolerance_mm) + " mm, ReaderOptions::arc_radius_tolerance_mm)";
    return arc;
  }
  // LinuxCNC arc_data_r: the centre lies on the bisector, right of the chord for a short clockwise
  // arc and for a long counter-clockwise one, left otherwise.
  // A chord within a relative 1e-12 of the diameter is a half circle (LinuxCNC's TINY): the square
  // root would otherwise turn rounding in the end points into a visible centre offset.
  const double offset = half_chord / abs_radius > 1.0 - 1e-12
                            ? 0.0
                            : std::sqrt(abs_radius * abs_radius - half_chord * half_chord);
  const bool right = ccw == (radius_mm < 0.0);
  const double chord_angle = std::atan2(end.y_mm - start.y_mm, end.x_mm - start.x_mm);
  const double theta = chord_angle + (right ? -0.5 : 0.5) * kPi;
  arc.center = {0.5 * (start.x_mm + end.x_mm) + offset * std::cos(theta),
                0.5 * (start.y_mm + end.y_mm) + offset * std::sin(theta)};
  if (std::max(abs_radius, half_chord) <= kZeroRadiusMm) {
    arc.problem = "zero radius";
    return arc;
  }
  arc.sweep_rad = sweep_rad(start, end, arc.center, ccw, turns);
  return arc;
}

}  // namespace feedplan::gcode::detail
