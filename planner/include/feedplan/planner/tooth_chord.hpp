#pragma once
// The tool centre's displacement over the last tooth period, as the chip sees it. A tooth cuts the material
// the previous tooth left: at a point of the tool circle with outward normal n the chip is (c(t) − c(t − T))·n,
// with c the tool centre and T the tooth period — the chord of the path over the last f_z of travel, not the
// tangent. On a straight cut the two agree and the chip is f_z·sin φ; on a path turning with curvature κ the
// chord lags the tangent by κ·f_z/2, so the chip is f_z·sin(φ + δ) with δ the chord's angle from the feed
// direction (counter-clockwise, rad). Where the engaged arc is narrow and sits near φ = π (a trochoid's or a
// spiral's outside, down milling) this changes the chip by cot(α)·δ: +5 % at a 10° engagement for f_z 0.1 mm
// on a 10 mm loop, +20 % where a spiral leaves its material at a fast feed.
//
// The force kernel then reads the sample's arcs in the chord's frame (immersions + δ) with the chord's
// length as the feed per tooth; the magnitude of the XY force, which the peak is, does not depend on the frame.

#include "feedplan/geometry/engagement.hpp"

namespace feedplan::planner {

//! The chord over the last tooth period at a sample.
struct ToothChord {
  double length_mm = 0.0;  //!< XY length of the chord, mm: the feed per tooth the chip sees
  double angle_rad = 0.0;  //!< δ: the chord's direction from the sample's feed direction, counter-clockwise, rad
};

//! The chord from the tool centre `path_per_tooth_mm` of path length before `sample` to the sample, from the
//! profile's sample positions (linear between samples, which lie ds apart along the path). Where the path
//! does not reach that far back (the start), the chord is taken along the feed direction with the XY length
//! path_per_tooth_mm · xy_speed_ratio. Needs path_per_tooth_mm ≥ 0.
ToothChord tooth_chord(const geometry::EngagementProfile& profile, const geometry::EngagementSample& sample,
                       double path_per_tooth_mm);

}  // namespace feedplan::planner
