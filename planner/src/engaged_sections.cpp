#include "feedplan/planner/engaged_sections.hpp"

#include <algorithm>
#include <numbers>
#include <span>

namespace feedplan::planner {

namespace {

// The arcs of intervals [begin, begin + count) of the profile, appended to `arcs`.
void append_arcs(const geometry::EngagementProfile& profile, int begin, int count,
                 std::vector<model::ImmersionArc>& arcs) {
  for (int k = 0; k < count; ++k) {
    const geometry::EngagedInterval& interval = profile.intervals[static_cast<std::size_t>(begin + k)];
    arcs.push_back({interval.entry_rad, interval.exit_rad});
  }
}

}  // namespace

SampleSections::SampleSections(const geometry::EngagementProfile& profile, const geometry::EngagementSample& sample) {
  const double tip_mm = sample.position.z_mm;
  if (sample.layer_count > 0) {
    std::size_t total = 0;
    for (int k = 0; k < sample.layer_count; ++k) {
      total += static_cast<std::size_t>(profile.layers[static_cast<std::size_t>(sample.layer_begin + k)].interval_count);
    }
    arcs_.reserve(total);  // the bands point into arcs_: no reallocation after the first band
    for (int k = 0; k < sample.layer_count; ++k) {
      const geometry::EngagementLayer& layer = profile.layers[static_cast<std::size_t>(sample.layer_begin + k)];
      const std::size_t first = arcs_.size();
      append_arcs(profile, layer.interval_begin, layer.interval_count, arcs_);
      sections_.push_back({std::max(layer.bottom_z_mm - tip_mm, 0.0), std::max(layer.top_z_mm - tip_mm, 0.0),
                           std::span<const model::ImmersionArc>(arcs_.data() + first, arcs_.size() - first)});
    }
    return;
  }
  if (sample.interval_count == 0 || !(sample.axial_depth_mm > 0.0)) return;
  arcs_.reserve(static_cast<std::size_t>(sample.interval_count));
  append_arcs(profile, sample.interval_begin, sample.interval_count, arcs_);
  sections_.push_back({0.0, sample.axial_depth_mm, std::span<const model::ImmersionArc>(arcs_.data(), arcs_.size())});
}

void SampleSections::turn(double turn_rad) {
  if (feed_frame_arcs_.empty()) feed_frame_arcs_ = arcs_;
  constexpr double kLowest = -0.5 * std::numbers::pi, kHighest = 1.5 * std::numbers::pi;
  for (std::size_t i = 0; i < arcs_.size(); ++i) {  // in place: the sections point into arcs_
    arcs_[i].entry_rad = std::clamp(feed_frame_arcs_[i].entry_rad + turn_rad, kLowest, kHighest);
    arcs_[i].exit_rad = std::clamp(feed_frame_arcs_[i].exit_rad + turn_rad, kLowest, kHighest);
  }
}

model::CutterGeometry cutter_geometry(const geometry::Tool& tool) {
  return {tool.radius_mm(), tool.flutes, tool.helix_deg};
}

}  // namespace feedplan::planner
