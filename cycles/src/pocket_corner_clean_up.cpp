#include "pocket_corner_clean_up.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace feedplan::cycles::detail {
namespace {

// Pitch per radial depth left: a loop's first quarter, where neither the link from the last loop nor
// the loop itself has cleared behind the tool yet, engages more than the steady front the pitch
// p = R_d is laid out for (60.2° instead of 55° in the sample pocket, by the exact engagement);
// 0.8·R_d keeps it below 55° there (52.9°).
constexpr double kPitchPerRadialDepth = 0.8;

}  // namespace

double internal_arc_radial_depth_mm(double tool_radius_mm, double wall_radius_mm, double engagement_rad) {
  assert(wall_radius_mm > tool_radius_mm && tool_radius_mm > 0);
  const double r = tool_radius_mm;
  const double rho = wall_radius_mm - r;
  // docs/method.md §5.1: (R − R_d)² = ρ² + r² + 2 r ρ cos α.
  return wall_radius_mm - std::sqrt(rho * rho + r * r + 2.0 * r * rho * std::cos(engagement_rad));
}

CornerCleanUp plan_corner_clean_up(const std::vector<geometry::Point2>& corners,
                                   const std::vector<geometry::Point2>& slot_ends, double rough_radius_mm,
                                   double corner_radius_mm, double tool_radius_mm, double pitch_mm,
                                   double engagement_rad) {
  assert(corners.size() == slot_ends.size());
  CornerCleanUp plan;
  const double left = internal_arc_radial_depth_mm(tool_radius_mm, corner_radius_mm, engagement_rad);
  plan.reach_mm = corner_radius_mm - left;
  plan.loop_radius_mm = plan.reach_mm - tool_radius_mm;
  // The trochoid generator needs loops larger than the pitch: at most half the loop radius, as the slots.
  plan.pitch_mm = std::min({pitch_mm, kPitchPerRadialDepth * left, 0.5 * plan.loop_radius_mm});
  // The first loop centre lies this far from the slot end: its disc of radius R_q is already roughed.
  const double clear_mm = std::max(rough_radius_mm - plan.reach_mm, 0.0);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const geometry::Point2 o = slot_ends[i];
    const geometry::Point2 q = corners[i];
    const double length_mm = std::hypot(q.x_mm - o.x_mm, q.y_mm - o.y_mm);
    if (length_mm <= clear_mm + 1e-9) continue;
    const double t = clear_mm / length_mm;
    plan.trochoids.push_back({{o.x_mm + t * (q.x_mm - o.x_mm), o.y_mm + t * (q.y_mm - o.y_mm)}, q});
  }
  return plan;
}

}  // namespace feedplan::cycles::detail
