#include "feedplan/geometry/engagement_csv.hpp"

#include <cstdio>

#include "feedplan/core/angle.hpp"

namespace feedplan::geometry {

std::string engagement_csv(const EngagementProfile& profile) {
  std::string text = kEngagementCsvHeader;
  text += '\n';
  text.reserve(text.size() + profile.samples.size() * 140);
  char line[512];
  for (const auto& s : profile.samples) {
    std::snprintf(line, sizeof line, "%.4f,%.4f,%.4f,%.4f,%d,%d,%d,%.4f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,", s.s_mm,
                  s.position.x_mm, s.position.y_mm, s.position.z_mm, s.cutting ? 1 : 0, s.part, s.move_index,
                  rad_to_deg(s.feed_direction_rad), rad_to_deg(s.engagement_rad), rad_to_deg(s.entry_rad),
                  rad_to_deg(s.exit_rad), s.chip_factor, s.contact_length_mm, s.axial_depth_mm);
    text += line;
    for (int k = 0; k < s.interval_count; ++k) {
      const auto& iv = profile.intervals[s.interval_begin + k];
      std::snprintf(line, sizeof line, "%s%.6f:%.6f", k ? " " : "", rad_to_deg(iv.entry_rad), rad_to_deg(iv.exit_rad));
      text += line;
    }
    text += '\n';
  }
  return text;
}

}  // namespace feedplan::geometry
