#pragma once
// The engagement of one path sample as the mechanistic force model reads it (model/engaged_section.hpp):
// each engaged layer the geometry found (geometry::EngagementLayer, every layer between the tip and the
// stock top) becomes a band of heights above the tip with its engaged arcs, in the same immersion
// convention. A sample evaluated at one height only (no layers) gives one band from the tip up to its
// axial depth with the sample's own arcs.

#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/model/engaged_section.hpp"

namespace feedplan::planner {

//! The bands of one sample, with the arcs they point into (keep the object alive while using `sections`;
//! it is not copyable, since the bands point into its own arcs).
class SampleSections {
 public:
  SampleSections(const geometry::EngagementProfile& profile, const geometry::EngagementSample& sample);
  SampleSections(const SampleSections&) = delete;
  SampleSections& operator=(const SampleSections&) = delete;

  const std::vector<model::EngagedSection>& sections() const { return sections_; }

  //! Reads the arcs in a frame turned by `turn_rad` counter-clockwise from the feed direction (immersions
  //! + turn_rad, kept inside the kernel's [−π/2, 3π/2)): tooth_chord.hpp. 0 restores the sample's own.
  void turn(double turn_rad);

 private:
  std::vector<model::ImmersionArc> arcs_;
  std::vector<model::ImmersionArc> feed_frame_arcs_;
  std::vector<model::EngagedSection> sections_;
};

//! The cutter of `tool` as the force kernel needs it (radius, flutes, helix).
model::CutterGeometry cutter_geometry(const geometry::Tool& tool);

}  // namespace feedplan::planner
