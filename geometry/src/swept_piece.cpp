#include "swept_piece.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::geometry::detail {

namespace {

// Height tolerance: a piece at the evaluation height counts as below it.
constexpr double kHeightToleranceMm = 1e-9;
// Below this distance two centres coincide.
constexpr double kCoincidentMm = 1e-12;

// Bounding box and the derived directions of a piece whose a, b (and arc fields) are set.
void finish_piece(SweptPiece& piece) {
  if (piece.is_arc) {
    piece.start_normal_rad = piece.start_angle_rad + 0.5 * kPi;
    piece.end_normal_rad = piece.start_angle_rad + piece.sweep_rad - 0.5 * kPi;
    piece.start_normal = unit_at(piece.start_normal_rad);
    piece.end_normal = unit_at(piece.end_normal_rad);
  } else {
    const Vec2 d = piece.b - piece.a;
    piece.length_mm = norm(d);
    piece.unit = piece.length_mm > 0.0 ? (1.0 / piece.length_mm) * d : Vec2{1.0, 0.0};
    piece.direction_rad = angle_of(piece.unit);
  }
  piece.box_min = {std::min(piece.a.x, piece.b.x), std::min(piece.a.y, piece.b.y)};
  piece.box_max = {std::max(piece.a.x, piece.b.x), std::max(piece.a.y, piece.b.y)};
  if (!piece.is_arc) return;
  // Add the axis extremes the arc passes (angles 0, π/2, π, 3π/2).
  for (int k = 0; k < 4; ++k) {
    const double axis = k * 0.5 * kPi;
    const double offset = wrap_two_pi(axis - piece.start_angle_rad);
    if (offset <= piece.sweep_rad) {
      const Vec2 q = piece.center + piece.radius_mm * unit_at(axis);
      piece.box_min = {std::min(piece.box_min.x, q.x), std::min(piece.box_min.y, q.y)};
      piece.box_max = {std::max(piece.box_max.x, q.x), std::max(piece.box_max.y, q.y)};
    }
  }
}

// Angles θ with |p + r e(θ) − c| < radius: a disc of the given radius about c.
void append_disc(Vec2 c, double disc_radius, Vec2 p, double r, AngleIntervals& cuts) {
  const Vec2 pc = c - p;
  const double d = norm(pc);
  if (d < kCoincidentMm) {
    if (r < disc_radius) cuts.push_back({0.0, kTwoPi});
    return;
  }
  // |q − c|² = d² + r² − 2 r d cos(θ − angle(c − p)) < R²
  const double threshold = (d * d + r * r - disc_radius * disc_radius) / (2.0 * r * d);
  if (threshold >= 1.0 - kCosTangencyTolerance) return;  // disjoint or tangent: skip the atan2
  for (const auto& interval : AngleSet::cos_above(angle_of(pc), threshold).intervals()) cuts.push_back(interval);
}

// Angles θ with n·(p + r e(θ) − origin) > 0 for the unit normal n at angle normal_angle.
AngleSet half_plane(Vec2 origin, Vec2 normal, double normal_angle, Vec2 p, double r) {
  const double offset = dot(normal, p - origin);
  return AngleSet::cos_above(normal_angle, -offset / r);
}

}  // namespace

void split_move(const Move& move, double sweep_radius_mm, double max_piece_length_mm,
                std::vector<SweptPiece>& pieces, std::vector<double>* fractions) {
  const double length = xy_length_mm(move);
  int count = std::max(1, static_cast<int>(std::ceil(length / max_piece_length_mm)));
  if (move.kind == MoveKind::kArc) count = std::max(count, static_cast<int>(std::ceil(move.sweep_rad / (0.5 * kPi) - 1e-12)));
  if (fractions) fractions->clear();
  const double sign = move.ccw ? 1.0 : -1.0;
  const Vec2 start = to_vec(move.start);
  const double radius = arc_radius_mm(move);
  const double angle0 = angle_of(start - to_vec(move.center));
  for (int i = 0; i < count; ++i) {
    const double f0 = static_cast<double>(i) / count;
    const double f1 = static_cast<double>(i + 1) / count;
    if (fractions) fractions->push_back(f0);
    SweptPiece piece;
    piece.sweep_radius_mm = sweep_radius_mm;
    const Point3 p0 = point_at(move, f0);
    const Point3 p1 = i + 1 == count ? move.end : point_at(move, f1);
    piece.a = to_vec(p0);
    piece.b = to_vec(p1);
    piece.z_a_mm = p0.z_mm;
    piece.z_b_mm = p1.z_mm;
    if (move.kind == MoveKind::kArc) {
      piece.is_arc = true;
      piece.center = to_vec(move.center);
      piece.radius_mm = radius;
      piece.sweep_rad = (f1 - f0) * move.sweep_rad;
      piece.start_angle_rad = angle0 + sign * f0 * move.sweep_rad;
      if (!move.ccw) {
        // Store clockwise arcs counter-clockwise: from b to a.
        piece.start_angle_rad -= piece.sweep_rad;
        std::swap(piece.a, piece.b);
        std::swap(piece.z_a_mm, piece.z_b_mm);
      }
      piece.start_angle_rad = wrap_two_pi(piece.start_angle_rad);
    }
    finish_piece(piece);
    pieces.push_back(piece);
  }
  if (fractions) fractions->push_back(1.0);
}

SweptPiece sub_piece(const SweptPiece& piece, double f0, double f1) {
  SweptPiece sub = piece;
  const double dz = piece.z_b_mm - piece.z_a_mm;
  sub.z_a_mm = piece.z_a_mm + f0 * dz;
  sub.z_b_mm = piece.z_a_mm + f1 * dz;
  if (piece.is_arc) {
    sub.start_angle_rad = piece.start_angle_rad + f0 * piece.sweep_rad;
    sub.sweep_rad = (f1 - f0) * piece.sweep_rad;
    sub.a = piece.center + piece.radius_mm * unit_at(sub.start_angle_rad);
    sub.b = piece.center + piece.radius_mm * unit_at(sub.start_angle_rad + sub.sweep_rad);
    sub.start_angle_rad = wrap_two_pi(sub.start_angle_rad);
  } else {
    const Vec2 d = piece.b - piece.a;
    sub.a = piece.a + f0 * d;
    sub.b = piece.a + f1 * d;
  }
  finish_piece(sub);
  return sub;
}

double distance_to_path_mm(const SweptPiece& piece, Vec2 p) {
  if (!piece.is_arc) {
    const Vec2 d = piece.b - piece.a;
    const double length_sq = dot(d, d);
    double t = length_sq > 0.0 ? dot(p - piece.a, d) / length_sq : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return norm(p - (piece.a + t * d));
  }
  // Inside the wedge of the arc (sweep ≤ π/2): the nearest point is on the arc.
  const Vec2 pc = p - piece.center;
  if (cross(piece.a - piece.center, pc) >= 0.0 && cross(pc, piece.b - piece.center) >= 0.0) {
    return std::abs(norm(pc) - piece.radius_mm);
  }
  return std::min(norm(p - piece.a), norm(p - piece.b));
}

bool append_excluded(const SweptPiece& whole, Vec2 p, double r, double height_mm, bool start_disc, bool end_disc,
                     AngleIntervals& cuts) {
  assert(r > 0.0);
  const double rs = whole.sweep_radius_mm;
  // Clip to the part whose tip is at or below the evaluation height (z is linear along the piece).
  SweptPiece clipped;
  const SweptPiece* piece = &whole;
  const bool a_below = whole.z_a_mm <= height_mm + kHeightToleranceMm;
  const bool b_below = whole.z_b_mm <= height_mm + kHeightToleranceMm;
  if (!a_below && !b_below) return false;
  bool keep_end_disc = end_disc;
  bool keep_start_disc = start_disc;
  if (a_below != b_below) {
    const double t = (height_mm - whole.z_a_mm) / (whole.z_b_mm - whole.z_a_mm);
    if (a_below) {
      clipped = sub_piece(whole, 0.0, t);
      keep_end_disc = true;
    } else {
      clipped = sub_piece(whole, t, 1.0);
      keep_start_disc = true;
    }
    piece = &clipped;
  }

  // Out of reach: no point of the tool circle is within rs of the centre path.
  if (distance_to_path_mm(*piece, p) >= r + rs) return false;

  const std::size_t before = cuts.size();
  if (keep_start_disc) append_disc(piece->a, rs, p, r, cuts);
  if (keep_end_disc) append_disc(piece->b, rs, p, r, cuts);

  AngleSet body = AngleSet::full();
  if (!piece->is_arc) {
    const double length = piece->length_mm;
    if (length <= kCoincidentMm) return cuts.size() > before;
    const double u_angle = piece->direction_rad;
    const double n_angle = u_angle + 0.5 * kPi;
    const Vec2 u = piece->unit;
    const Vec2 n{-u.y, u.x};
    const double t = dot(p - piece->a, u);
    const double s = dot(p - piece->a, n);
    // 0 < u·(q − a) < length and −rs < n·(q − a) < rs, with q = p + r e(θ).
    body = AngleSet::cos_above(u_angle, -t / r);
    body.intersect_with(AngleSet::cos_above(u_angle + kPi, (t - length) / r));
    if (body.is_empty()) return cuts.size() > before;
    body.intersect_with(AngleSet::cos_above(n_angle, -(rs + s) / r));
    body.intersect_with(AngleSet::cos_above(n_angle + kPi, -(rs - s) / r));
  } else {
    const double rho = piece->radius_mm;
    const Vec2 pc = p - piece->center;
    const double d = norm(pc);
    // Wedge: angle about the centre within [start, start + sweep] (sweep ≤ π/2: two half-planes).
    body = half_plane(piece->center, piece->start_normal, piece->start_normal_rad, p, r);
    body.intersect_with(half_plane(piece->center, piece->end_normal, piece->end_normal_rad, p, r));
    if (body.is_empty()) return cuts.size() > before;
    // Annulus rho − rs < |q − c| < rho + rs; |q − c|² = d² + r² + 2 r d cos(θ − angle(p − c)).
    if (d < kCoincidentMm) {
      if (!(r < rho + rs && r > rho - rs)) body = AngleSet::empty();
    } else {
      const double pc_angle = angle_of(pc);
      const double outer = rho + rs;
      body.intersect_with(AngleSet::cos_above(pc_angle + kPi, (d * d + r * r - outer * outer) / (2.0 * r * d)));
      const double inner = rho - rs;
      if (inner > 0.0) {
        body.intersect_with(AngleSet::cos_above(pc_angle, (inner * inner - d * d - r * r) / (2.0 * r * d)));
      }
    }
  }
  for (const auto& interval : body.intervals()) cuts.push_back(interval);
  return cuts.size() > before;
}

}  // namespace feedplan::geometry::detail
