#include "stock_section.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/core/angle.hpp"

namespace feedplan::geometry::detail {

namespace {

// Angles θ where p + r e(θ) is inside the contour.
AngleIntervals inside_angles(const Contour& contour, Vec2 p, double r) {
  AngleIntervals result;
  if (contour.is_circle()) {
    const Vec2 pc = to_vec(contour.center) - p;
    const double d = norm(pc);
    const double radius = contour.radius_mm;
    if (d < 1e-12) {
      if (r < radius) result.push_back({0.0, kTwoPi});
      return result;
    }
    for (const auto& i : AngleSet::cos_above(angle_of(pc), (d * d + r * r - radius * radius) / (2.0 * r * d)).intervals()) {
      result.push_back(i);
    }
    return result;
  }
  // Polygon: crossing angles of the circle with every edge, then classify each arc between
  // consecutive crossings by its midpoint.
  boost::container::small_vector<double, 16> crossings;
  const auto& v = contour.vertices;
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = to_vec(v[i]);
    const Vec2 b = to_vec(v[(i + 1) % n]);
    const Vec2 d = b - a;
    const Vec2 f = a - p;
    // |f + t d|² = r², t ∈ [0, 1]
    const double qa = dot(d, d);
    const double qb = 2.0 * dot(f, d);
    const double qc = dot(f, f) - r * r;
    const double disc = qb * qb - 4.0 * qa * qc;
    if (qa <= 0.0 || disc <= 0.0) continue;
    const double root = std::sqrt(disc);
    for (double t : {(-qb - root) / (2.0 * qa), (-qb + root) / (2.0 * qa)}) {
      if (t >= 0.0 && t <= 1.0) crossings.push_back(wrap_two_pi(angle_of(f + t * d)));
    }
  }
  if (crossings.empty()) {
    // Wholly inside or wholly outside, possibly touching the boundary at tangent points (a circle
    // tangent to an edge at θ = 0 is the common case: the tool beside a block face). Classify by a
    // point at a generic angle, never one of the round angles a tangency tends to sit at.
    constexpr double kGenericAngleRad = 1.2345678;
    if (inside_contour(contour, p + r * unit_at(kGenericAngleRad))) result.push_back({0.0, kTwoPi});
    return result;
  }
  std::sort(crossings.begin(), crossings.end());
  crossings.push_back(crossings.front() + kTwoPi);
  AngleIntervals raw;
  for (std::size_t i = 0; i + 1 < crossings.size(); ++i) {
    const double lo = crossings[i];
    const double hi = crossings[i + 1];
    if (hi - lo <= 0.0) continue;
    if (!inside_contour(contour, p + r * unit_at(0.5 * (lo + hi)))) continue;
    if (hi <= kTwoPi) {
      raw.push_back({lo, hi});
    } else {
      raw.push_back({lo, kTwoPi});
      raw.push_back({0.0, hi - kTwoPi});
    }
  }
  std::sort(raw.begin(), raw.end(), [](const AngleInterval& x, const AngleInterval& y) { return x.lo < y.lo; });
  for (const auto& i : raw) {
    if (!result.empty() && i.lo <= result.back().hi) result.back().hi = std::max(result.back().hi, i.hi);
    else result.push_back(i);
  }
  return result;
}

}  // namespace

bool inside_contour(const Contour& contour, Vec2 q) {
  if (contour.is_circle()) return norm(q - to_vec(contour.center)) < contour.radius_mm;
  bool inside = false;
  const auto& v = contour.vertices;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    const double yi = v[i].y_mm, yj = v[j].y_mm;
    if ((yi > q.y) != (yj > q.y)) {
      const double x = v[j].x_mm + (q.y - yj) * (v[i].x_mm - v[j].x_mm) / (yi - yj);
      if (q.x < x) inside = !inside;
    }
  }
  return inside;
}

AngleIntervals initial_material(const Stock& stock, Vec2 p, double r, double height_mm) {
  AngleIntervals result;
  if (height_mm < stock.z_bottom_mm || height_mm > stock.z_top_mm) return result;
  for (const auto& region : stock.regions) {
    AngleIntervals inside = inside_angles(region.outer, p, r);
    if (inside.empty()) continue;
    if (!region.holes.empty()) {
      AngleIntervals holes;
      for (const auto& hole : region.holes) {
        for (const auto& i : inside_angles(hole, p, r)) holes.push_back(i);
      }
      inside = subtract_union(inside, holes, 0.0);
    }
    for (const auto& i : inside) result.push_back(i);
  }
  // Regions do not overlap, so the pieces are disjoint; keep them sorted.
  std::sort(result.begin(), result.end(), [](const AngleInterval& x, const AngleInterval& y) { return x.lo < y.lo; });
  return result;
}

}  // namespace feedplan::geometry::detail
