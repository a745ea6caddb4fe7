#include "pocket_wall_stock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "feedplan/core/angle.hpp"

namespace feedplan::cycles::detail {
namespace {

struct Capsule {
  double ax, ay, bx, by, radius;
};

double distance_to_capsule(const Capsule& c, double px, double py) {
  const double dx = c.bx - c.ax, dy = c.by - c.ay;
  const double length2 = dx * dx + dy * dy;
  const double t = length2 > 0 ? std::clamp(((px - c.ax) * dx + (py - c.ay) * dy) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(px - c.ax - t * dx, py - c.ay - t * dy) - c.radius;
}

// Smallest t in [0, t_max] where p + t·n enters the capsule, or +inf. The distance to a convex set is
// convex along a line: a ternary search finds its minimum, a bisection the entry before it.
double entry_along_ray(const Capsule& c, double px, double py, double nx, double ny, double t_max) {
  const auto g = [&](double t) { return distance_to_capsule(c, px + t * nx, py + t * ny); };
  if (g(0) <= 0) return 0;
  double lo = 0, hi = t_max;
  for (int i = 0; i < 100; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (g(m1) < g(m2)) {
      hi = m2;
    } else {
      lo = m1;
    }
  }
  const double t_min = 0.5 * (lo + hi);
  if (g(t_min) > 0) return std::numeric_limits<double>::infinity();
  lo = 0, hi = t_min;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (g(mid) > 0) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return hi;
}

}  // namespace

double thickest_wall_stock_mm(const QuarterPocket& p, double step_mm) {
  const double qx = p.half_long_mm - p.corner_radius_mm, qy = p.half_short_mm - p.corner_radius_mm;
  const Capsule stadium{-p.slot_end_mm, 0, p.slot_end_mm, 0, p.rough_radius_mm};
  const Capsule clean_up{p.clean_up_start_x_mm, p.clean_up_start_y_mm, qx, qy, p.clean_up_reach_mm};
  const double t_max = p.half_long_mm + p.half_short_mm;
  double thickest = 0;
  const auto measure = [&](double x, double y, double nx, double ny) {
    double t = entry_along_ray(stadium, x, y, nx, ny, t_max);
    if (p.clean_up_reach_mm > 0) t = std::min(t, entry_along_ray(clean_up, x, y, nx, ny, t_max));
    thickest = std::max(thickest, t);
  };
  const auto count = [&](double length_mm) { return std::max(1, static_cast<int>(std::ceil(length_mm / step_mm))); };
  const int n_long = count(qx), n_short = count(qy), n_arc = count(0.5 * kPi * p.corner_radius_mm);
  for (int i = 0; i <= n_long; ++i) measure(qx * i / n_long, p.half_short_mm, 0, -1);
  for (int i = 0; i <= n_short; ++i) measure(p.half_long_mm, qy * i / n_short, -1, 0);
  for (int i = 0; i <= n_arc; ++i) {
    const double theta = 0.5 * kPi * i / n_arc;
    measure(qx + p.corner_radius_mm * std::cos(theta), qy + p.corner_radius_mm * std::sin(theta), -std::cos(theta),
            -std::sin(theta));
  }
  return thickest;
}

}  // namespace feedplan::cycles::detail
