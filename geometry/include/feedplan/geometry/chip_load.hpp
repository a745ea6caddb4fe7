#pragma once
// The uncut chip the teeth hold at once: what a force scales with when the engagement differs from
// the straight cuts a response surface was fitted on — another axial depth, several layers with
// different engaged sets (a helix), an engaged arc at the front of the tool (an entry).
//
// With N helical teeth (helix angle β, radius r) turning at spindle angle Ω, tooth j's point at height z
// above the tip has the immersion φ_j(z) = Ω + j·2π/N − z·tan β / r (Altintas, Manufacturing
// Automation, ch. 2: the flute lags behind the tip by z·2 tan β / D). Where that point is engaged it
// cuts the chip f_z·sin φ (docs/method.md §5.1; 0 outside (0, π)). The chip load is the cross-section of
// chip in the cut at once per unit feed per tooth,
//   C(Ω) = Σ_j ∫ [φ_j(z) engaged at height z] · max(sin φ_j(z), 0) dz,   in mm (mm² of chip per mm of f_z),
// and peak_chip_load_mm is its largest value over Ω. Per layer of constant engaged set the integral is
// closed form, (cos a − cos b) / (tan β / r) over the immersions [a, b] the flute spans there; Ω is
// sampled at kChipLoadSteps points per tooth period.
//
// A straight down-milling cut of depth a and engagement α (engaged arc [π − α, π]) is the reference:
// straight_cut_chip_load_mm. A force model fitted on straight cuts at depth a_model transfers to
// another engagement with the same t_m through the ratio of their chip loads (planner/feed_limit.hpp).

#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::geometry {

//! Spindle angles sampled per tooth period for the peak.
inline constexpr int kChipLoadSteps = 128;

//! Peak chip load (mm; see the file comment) of `sample`'s engaged layers (profile.layers) for `tool`;
//! 0 when the sample has no layers (not engaged, or evaluated on one height only).
double peak_chip_load_mm(const EngagementProfile& profile, const EngagementSample& sample, const Tool& tool);

//! C(Ω) (mm) of `sample`'s engaged layers at the kChipLoadSteps spindle angles Ω = k·(2π/N)/kChipLoadSteps of
//! one tooth period (peak_chip_load_mm is its largest value): the shape of the cutting force over a tooth
//! period, as far as the force scales with the chip in the cut. Empty when the sample has no layers.
std::vector<double> chip_load_waveform_mm(const EngagementProfile& profile, const EngagementSample& sample,
                                          const Tool& tool);

//! Peak chip load (mm) of a straight down-milling cut of engagement `engagement_rad` (clamped to
//! [0, π]) and axial depth `depth_mm` with `tool`.
double straight_cut_chip_load_mm(double engagement_rad, double depth_mm, const Tool& tool);

}  // namespace feedplan::geometry
