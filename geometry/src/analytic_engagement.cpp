#include "feedplan/geometry/analytic_engagement.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/angle.hpp"

namespace feedplan::geometry {

namespace {

// cos α → α, with the clamp of docs/method.md §5.1 (below −1 the whole half circle is engaged).
double engagement_from_cos(double cos_engagement) {
  if (cos_engagement <= -1.0) return kPi;
  if (cos_engagement >= 1.0) return 0.0;
  return std::acos(cos_engagement);
}

}  // namespace

double straight_engagement_rad(double tool_radius_mm, double radial_depth_mm) {
  assert(tool_radius_mm > 0.0 && radial_depth_mm >= 0.0);
  return engagement_from_cos(1.0 - radial_depth_mm / tool_radius_mm);
}

double internal_arc_engagement_rad(double tool_radius_mm, double wall_radius_mm, double radial_depth_mm) {
  const double r = tool_radius_mm;
  const double R = wall_radius_mm;
  const double rd = radial_depth_mm;
  assert(r > 0.0 && R > r && rd >= 0.0 && rd <= R);
  // seed 003 Eq. 2, R = finished-wall radius (docs/method.md §5.1)
  return engagement_from_cos(((R - rd) * (R - rd) - (R - r) * (R - r) - r * r) / (2.0 * r * (R - r)));
}

double external_arc_engagement_rad(double tool_radius_mm, double wall_radius_mm, double radial_depth_mm) {
  const double r = tool_radius_mm;
  const double R = wall_radius_mm;
  const double rd = radial_depth_mm;
  assert(r > 0.0 && R >= 0.0 && rd >= 0.0);
  // External counterpart of seed 003 Eq. 2 (docs/method.md §5.1)
  return engagement_from_cos(((R + r) * (R + r) + r * r - (R + rd) * (R + rd)) / (2.0 * r * (R + r)));
}

double steady_chip_factor(double engagement_rad) {
  return std::sin(std::min(engagement_rad, 0.5 * kPi));
}

}  // namespace feedplan::geometry
