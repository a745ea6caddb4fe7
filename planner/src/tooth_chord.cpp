#include "feedplan/planner/tooth_chord.hpp"

#include <algorithm>
#include <cmath>

namespace feedplan::planner {

ToothChord tooth_chord(const geometry::EngagementProfile& profile, const geometry::EngagementSample& sample,
                       double path_per_tooth_mm) {
  ToothChord straight{path_per_tooth_mm * sample.xy_speed_ratio, 0.0};
  const auto& samples = profile.samples;
  const double back_s = sample.s_mm - path_per_tooth_mm;
  if (!(path_per_tooth_mm > 0.0) || samples.empty() || back_s < samples.front().s_mm) return straight;
  // The last sample at or before back_s, and the position between it and the next.
  auto after = std::upper_bound(samples.begin(), samples.end(), back_s,
                                [](double s, const geometry::EngagementSample& e) { return s < e.s_mm; });
  const auto before = std::prev(after);
  double x = before->position.x_mm, y = before->position.y_mm;
  if (after != samples.end() && after->s_mm > before->s_mm) {
    const double w = (back_s - before->s_mm) / (after->s_mm - before->s_mm);
    x += w * (after->position.x_mm - before->position.x_mm);
    y += w * (after->position.y_mm - before->position.y_mm);
  }
  const double dx = sample.position.x_mm - x, dy = sample.position.y_mm - y;
  const double length_mm = std::hypot(dx, dy);
  // A chord much shorter than the XY travel is a path that turned back within a tooth (a plunge, a reversal):
  // its direction means nothing there, and the chip is that of the straight cut.
  if (!(length_mm > 0.5 * straight.length_mm)) return straight;
  const double c = std::cos(sample.feed_direction_rad), s = std::sin(sample.feed_direction_rad);
  return {length_mm, std::atan2(c * dy - s * dx, c * dx + s * dy)};
}

}  // namespace feedplan::planner
