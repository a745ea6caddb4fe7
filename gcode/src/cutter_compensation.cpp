#include "cutter_compensation.hpp"

#include <cmath>

#include "feedplan/core/number_text.hpp"

namespace feedplan::gcode::detail {

using geometry::Move;
using geometry::MoveKind;
using geometry::Point2;
using geometry::Point3;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHalfPi = kPi / 2.0;
// LinuxCNC's TOLERANCE_CONCAVE_CORNER: corners turning less than this are neither convex nor concave, rad.
constexpr double kCornerToleranceRad = 0.01;
// LinuxCNC refuses to lengthen a waiting arc by more than this when a concave corner moves its end, rad.
constexpr double kArcGrowthLimitRad = 0.254;

Point2 direction(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }
Point2 plus(const Point2& p, double length, double angle_rad) {
  return {p.x_mm + length * std::cos(angle_rad), p.y_mm + length * std::sin(angle_rad)};
}
double angle_of(const Point2& from, const Point2& to) { return std::atan2(to.y_mm - from.y_mm, to.x_mm - from.x_mm); }
double distance(const Point2& a, const Point2& b) { return std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm); }
Point3 at_z(const Point2& p, double z_mm) { return {p.x_mm, p.y_mm, z_mm}; }

// The signed angle swept from `start` to `end` about `center`, `turns` > 0 counter-clockwise, < 0
// clockwise (LinuxCNC's find_turn: start == end is a full turn).
double signed_sweep_rad(const Point2& start, const Point2& center, int turns, const Point2& end) {
  double alpha = angle_of(center, start);
  double beta = angle_of(center, end);
  if (turns > 0) {
    if (beta <= alpha) beta += 2.0 * kPi;
    return beta - alpha + (turns - 1) * 2.0 * kPi;
  }
  if (alpha <= beta) alpha += 2.0 * kPi;
  return beta - alpha + (turns + 1) * 2.0 * kPi;
}

Move straight_move(bool rapid, const Point3& start, const Point3& end) {
  Move m;
  m.kind = rapid ? MoveKind::kRapid : MoveKind::kLine;
  m.start = start;
  m.end = end;
  return m;
}

Move arc_move(const Point3& start, const Point3& end, const Point2& center, int turns) {
  Move m;
  m.kind = MoveKind::kArc;
  m.start = start;
  m.end = end;
  m.center = center;
  m.ccw = turns > 0;
  m.sweep_rad = std::abs(signed_sweep_rad(geometry::xy(start), center, turns, geometry::xy(end)));
  return m;
}

int turns_of(const Move& arc) {
  const int whole = static_cast<int>(std::floor(arc.sweep_rad / (2.0 * kPi) - 1e-9)) + 1;
  return arc.ccw ? whole : -whole;
}

// The tool runs inside an arc of direction `ccw` (LinuxCNC's TOOL_INSIDE_ARC).
bool tool_inside(CompSide side, bool ccw) { return (side == CompSide::kLeft) == ccw; }

std::string mm(double value) { return six_digit_number_text(value) + " mm"; }

// Where the previous move must end at a concave corner, or why the tool cannot get there.
struct Corner {
  Point2 point;
  std::string problem;
};

// Line after line: the tool backs up along the previous offset line (direction `back_rad`) until it
// meets the next one; `beta` is the turn of the path less a right angle (LinuxCNC's retreat).
Corner line_line_corner(const Point2& tool, double radius_mm, double beta, double back_rad) {
  const double half_corner_rad = (beta + kPi) / 2.0;
  if (half_corner_rad == 0.0) return {{}, "a zero-degree inside corner cannot be compensated"};
  return {plus(tool, radius_mm / std::tan(half_corner_rad), back_rad), ""};
}

// Line after an arc (the compensated `prev`): where the line's offset meets the arc's offset circle, the
// intersection on the side LinuxCNC takes. `corner` is the programmed corner, `next` the line's end.
Corner arc_line_corner(const Move& prev, CompSide side, double radius_mm, const Point2& corner, const Point2& next) {
  const double old_radius = distance(prev.center, geometry::xy(prev.end));
  const double base_dir = angle_of(corner, next);
  const double normal = prev.ccw ? base_dir + kHalfPi : base_dir - kHalfPi;
  const bool inside = tool_inside(side, prev.ccw);
  const double programmed_radius = inside ? old_radius + radius_mm : old_radius - radius_mm;
  const double d = programmed_radius * std::cos(normal - angle_of(corner, prev.center));
  const double l = (inside ? d - radius_mm : d + radius_mm) / old_radius;
  if (l > 1.0 || l < -1.0) {
    return {{}, "the arc before this line and the line make a corner the tool cannot fit in without gouging "
                "(LinuxCNC refuses it too)"};
  }
  const bool plus_acos = inside ? !prev.ccw : prev.ccw;
  return {plus(prev.center, old_radius, (plus_acos ? std::acos(l) : -std::acos(l)) + normal + kPi), ""};
}

// An arc (about `center`, radius `arc_radius`, tool `inside` it or not) after a line whose direction is
// `theta`, turning by `beta`: where the line's offset meets the arc's offset circle.
Corner line_arc_corner(double theta, double beta, const Point2& center, double arc_radius, bool ccw, bool inside,
                       double radius_mm) {
  const double across = arc_radius * std::sin(beta - kHalfPi);
  const double from_center = inside ? arc_radius - radius_mm : arc_radius + radius_mm;
  const double l = (inside ? across + radius_mm : across - radius_mm) / from_center;
  if (l > 1.0 || l < -1.0) {
    return {{}, "the arc in this concave corner cannot be reached by the tool without gouging (LinuxCNC refuses it "
                "too)"};
  }
  double angle = 0.0;
  if (inside) {
    angle = ccw ? theta + std::asin(l) : theta - std::asin(l);
  } else {
    angle = ccw ? theta + kPi - std::asin(l) : theta + kPi + std::asin(l);
  }
  return {plus(center, from_center, angle), ""};
}

// An arc after an arc (the compensated `prev`): where the two offset circles meet, on LinuxCNC's side.
Corner arc_arc_corner(const Move& prev, CompSide side, const Point2& center, double arc_radius, bool ccw, bool inside,
                      double radius_mm) {
  const double old_radius = distance(prev.center, geometry::xy(prev.end));
  const double new_radius = inside ? arc_radius - radius_mm : arc_radius + radius_mm;
  const double centers_mm = distance(prev.center, center);
  if (old_radius == 0.0 || centers_mm == 0.0) {
    return {{}, "an arc after an arc about the same centre cannot be compensated (LinuxCNC refuses it too)"};
  }
  const double a = (old_radius * old_radius + centers_mm * centers_mm - new_radius * new_radius) /
                   (2.0 * old_radius * centers_mm);
  if (a > 1.0 || a < -1.0) {
    return {{}, "the two arcs make a corner the tool cannot fit in without gouging (LinuxCNC refuses it too)"};
  }
  const double pullback = std::acos(a);
  const double centers_dir = angle_of(prev.center, center);
  const bool add = tool_inside(side, prev.ccw) ? ccw : !ccw;
  return {plus(prev.center, old_radius, add ? centers_dir + pullback : centers_dir - pullback), ""};
}

}  // namespace

CutterCompensation::CutterCompensation(CompSide side, double radius_mm, const Point3& tool_position,
                                       const Point3& programmed)
    : side_(side), radius_mm_(radius_mm), tool_(tool_position), programmed_(programmed),
      queue_start_(geometry::xy(tool_position)) {}

void CutterCompensation::emit(const Move& move, int tag, std::vector<CompMove>& done) { done.push_back({move, tag}); }

void CutterCompensation::enqueue(const Move& move, const Point2& line_direction, double original_sweep_rad, int tag) {
  queue_.push_back({{move, tag}, line_direction, original_sweep_rad});
}

void CutterCompensation::flush(std::vector<CompMove>& done) {
  for (const Waiting& w : queue_) done.push_back(w.move);
  queue_.clear();
  queue_start_ = geometry::xy(tool_);
}

// Moves the XY end of every waiting move to `end` (they all end there: a move and the plunges after it),
// refusing a line that would run backwards or an arc that would grow by more than LinuxCNC allows, then
// sends them to `done`.
std::string CutterCompensation::move_ends_and_flush(const Point2& end, std::vector<CompMove>& done) {
  for (Waiting& w : queue_) {
    Move& m = w.move.move;
    if (m.kind == MoveKind::kArc) {
      const double sweep = signed_sweep_rad(queue_start_, m.center, turns_of(m), end);
      if (w.original_sweep_rad != 0.0 && std::abs(sweep) > std::abs(w.original_sweep_rad) + kArcGrowthLimitRad) {
        return "the arc before this concave corner cannot be reached by the tool without gouging (LinuxCNC "
               "refuses it too)";
      }
    } else {
      const double dot = w.direction.x_mm * (end.x_mm - queue_start_.x_mm) + w.direction.y_mm * (end.y_mm - queue_start_.y_mm);
      if (dot < 0.0) {
        return std::string("the ") + (m.kind == MoveKind::kRapid ? "rapid" : "straight move") +
               " before this concave corner is shorter than the tool must back up to fit the corner, so the tool "
               "would gouge (LinuxCNC refuses it too); use a smaller tool or a longer move";
      }
    }
  }
  Point2 start = queue_start_;
  for (Waiting& w : queue_) {
    Move& m = w.move.move;
    const int turns = m.kind == MoveKind::kArc ? turns_of(m) : 0;
    m.start.x_mm = start.x_mm;
    m.start.y_mm = start.y_mm;
    m.end.x_mm = end.x_mm;
    m.end.y_mm = end.y_mm;
    if (m.kind == MoveKind::kArc) m.sweep_rad = std::abs(signed_sweep_rad(start, m.center, turns, end));
    start = end;
  }
  tool_.x_mm = end.x_mm;
  tool_.y_mm = end.y_mm;
  flush(done);
  return "";
}

// Convex corner: the tool goes round the programmed corner `corner` on an arc of the tool radius to
// `corner_end` (LinuxCNC: clockwise under G41); a rapid goes straight there. The corner is final at once.
void CutterCompensation::round_convex_corner(bool rapid, const Point2& corner_end, int tag, std::vector<CompMove>& done) {
  const Point3 end = at_z(corner_end, tool_.z_mm);
  if (rapid) {
    emit(straight_move(true, tool_, end), tag, done);
  } else {
    emit(arc_move(tool_, end, geometry::xy(programmed_), side_ == CompSide::kLeft ? -1 : 1), tag, done);
  }
  tool_ = end;
  queue_start_ = corner_end;
}

std::string CutterCompensation::straight(bool rapid, const Point3& end, int tag, std::vector<CompMove>& done) {
  const Point2 c = geometry::xy(tool_);
  const Point2 p = geometry::xy(end);
  const double r = radius_mm_;
  const double side_turn = side_ == CompSide::kLeft ? kHalfPi : -kHalfPi;
  if (first_move_) {
    // The entry move: ends a radius from the programmed end, square to the entry direction.
    if (distance(c, p) <= r) {
      return "the entry move after G41/G42 is " + mm(distance(c, p)) + " long in XY, not longer than the tool radius " +
             mm(r) + " (LinuxCNC refuses it too); start compensation farther from the path";
    }
    const double alpha = angle_of(c, p) + side_turn;
    const Point2 e = plus(p, r, alpha);
    queue_start_ = c;
    enqueue(straight_move(rapid, tool_, at_z(e, end.z_mm)), direction(alpha), 0.0, tag);
    first_move_ = false;
    tool_ = at_z(e, end.z_mm);
    programmed_ = end;
    return "";
  }
  const Point2 op = geometry::xy(programmed_);
  if (p.x_mm == op.x_mm && p.y_mm == op.y_mm) {
    // No XY motion: the tool keeps its XY; the move waits with the one before it.
    enqueue(straight_move(rapid, tool_, at_z(c, end.z_mm)), {0.0, 0.0}, 0.0, tag);
    tool_.z_mm = end.z_mm;
    programmed_ = end;
    return "";
  }
  double theta = angle_of(op, c);  // from the programmed corner to the tool
  double alpha = angle_of(op, p);  // the programmed direction
  double beta = 0.0;               // how far the path turns away from the tool side, less a right angle
  if (side_ == CompSide::kLeft) {
    if (theta < alpha) theta += 2.0 * kPi;
    beta = theta - alpha - kHalfPi;
  } else {
    if (alpha < theta) alpha += 2.0 * kPi;
    beta = alpha - theta - kHalfPi;
  }
  const double gamma = side_turn;
  const Point2 e = plus(p, r, alpha + gamma);
  const Point2 mid = plus(op, r, alpha + gamma);
  const bool front_arc = !queue_.empty() && queue_.front().move.move.kind == MoveKind::kArc;
  const bool concave = beta < -kCornerToleranceRad || beta > kPi + kCornerToleranceRad ||
                       (beta > kPi - kCornerToleranceRad && front_arc &&
                        !tool_inside(side_, queue_.front().move.move.ccw));
  if (!concave && beta > kCornerToleranceRad) {
    if (std::string problem = move_ends_and_flush(c, done); !problem.empty()) return problem;
    round_convex_corner(rapid, mid, tag, done);
  } else if (concave) {
    const Corner corner = front_arc ? arc_line_corner(queue_.front().move.move, side_, r, op, p)
                                    : line_line_corner(c, r, beta, theta + gamma);
    if (!corner.problem.empty()) return corner.problem;
    if (std::string problem = move_ends_and_flush(corner.point, done); !problem.empty()) return problem;
  } else {
    flush(done);
  }
  enqueue(straight_move(rapid, tool_, at_z(e, end.z_mm)), {p.x_mm - op.x_mm, p.y_mm - op.y_mm}, 0.0, tag);
  tool_ = at_z(e, end.z_mm);
  programmed_ = end;
  return "";
}

std::string CutterCompensation::arc(const ProgrammedArc& arc, int tag, std::vector<CompMove>& done) {
  if (first_move_) {
    return "an arc as the entry move after G41/G42: the reader compensates from a straight entry move (G0 or G1) "
           "on; program one before the arc";
  }
  const double r = radius_mm_;
  const Point2 op = geometry::xy(programmed_);
  const Point2 c = geometry::xy(tool_);
  const Point2 center = arc.center;
  const Point2 e = geometry::xy(arc.end);
  const int turns = arc.ccw ? arc.turns : -arc.turns;
  const double arc_radius = distance(center, e);
  const bool left = side_ == CompSide::kLeft;
  const double theta = angle_of(op, c) + (left ? -kHalfPi : kHalfPi);  // direction of the path before
  double delta = angle_of(op, center);
  const double alpha = arc.ccw ? delta - kHalfPi : delta + kHalfPi;   // direction the arc starts in
  double beta = left ? theta - alpha : alpha - theta;
  if (beta > 1.5 * kPi) beta -= 2.0 * kPi;
  if (beta < -kHalfPi) beta += 2.0 * kPi;
  const bool inside = tool_inside(side_, arc.ccw);
  double gamma = 0.0;
  if (inside) {
    gamma = angle_of(e, center);
    if (arc_radius <= r) {
      return "the tool radius " + mm(r) + " is not smaller than the radius " + mm(arc_radius) +
             " of the arc it runs inside (LinuxCNC refuses it too)";
    }
  } else {
    gamma = angle_of(center, e);
    delta += kPi;
  }
  const Point2 new_end = plus(e, r, gamma);
  const bool front_arc = !queue_.empty() && queue_.front().move.move.kind == MoveKind::kArc;
  if (beta < -kCornerToleranceRad || beta > kPi + kCornerToleranceRad ||
      (std::abs(beta - kPi) < kCornerToleranceRad && !inside)) {
    const Corner corner = front_arc ? arc_arc_corner(queue_.front().move.move, side_, center, arc_radius, arc.ccw, inside, r)
                                    : line_arc_corner(theta, beta, center, arc_radius, arc.ccw, inside, r);
    if (!corner.problem.empty()) return corner.problem;
    if (std::string problem = move_ends_and_flush(corner.point, done); !problem.empty()) return problem;
  } else if (beta > kCornerToleranceRad) {
    flush(done);
    round_convex_corner(false, plus(op, r, delta), tag, done);
  } else {
    flush(done);
  }
  const double original_sweep = signed_sweep_rad(op, center, turns, e);
  enqueue(arc_move(tool_, at_z(new_end, arc.end.z_mm), center, turns), {0.0, 0.0}, original_sweep, tag);
  tool_ = at_z(new_end, arc.end.z_mm);
  programmed_ = arc.end;
  return "";
}

void CutterCompensation::finish(std::vector<CompMove>& done) { flush(done); }

}  // namespace feedplan::gcode::detail
