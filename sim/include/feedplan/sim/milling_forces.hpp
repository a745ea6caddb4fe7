#pragma once
// Mechanistic milling forces at one instant (Altintas, Manufacturing Automation, ch. 2; docs/method.md
// §6.1): a flat end mill with N helical flutes, cut into axial slices, each tooth element loaded by
// the chip it cuts now. This is the virtual machine's physics; it shares nothing with the
// response-surface model it is meant to judge.

#include <span>
#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/point.hpp"
#include "feedplan/sim/cutting_coefficients.hpp"

namespace feedplan::sim {

//! The cutter as the force model sees it.
struct CutterGeometry {
  double radius_mm = 5.0;   //!< nominal radius, mm
  int flutes = 4;           //!< number of teeth N
  double helix_deg = 30.0;  //!< helix angle β, deg
  //! Radial runout per tooth (tooth j cuts at radius_mm + runout_mm[j]), mm; empty: none.
  std::vector<double> runout_mm;
};

//! One axial slice of the tool in the material at this instant.
struct ForceSlice {
  double height_above_tip_mm = 0.0;  //!< middle of the slice above the tool tip, mm (sets the helix lag)
  double thickness_mm = 0.0;         //!< slice thickness dz, mm
  //! Engaged arcs of the tool circle on this slice's layer, immersion angles relative to the feed
  //! direction (geometry::EngagedInterval: clockwise from the left of the feed, [−π/2, 3π/2)).
  std::span<const geometry::EngagedInterval> engaged;
};

//! Force on the tool, N, in machine axes, and the torque its tangential components load the spindle with.
struct Force3 {
  double fx_n = 0.0;
  double fy_n = 0.0;
  double fz_n = 0.0;
  //! Torque about the tool axis against the rotation, N·mm: every element's tangential force dF_t times the
  //! radius its tooth cuts at (with runout, r + runout of that tooth). Spindle power = torque × ω.
  double torque_nmm = 0.0;
};

//! The state of the cutter needed for the chip thickness.
struct CutterState {
  //! Spindle angle Ω turned so far, rad (teeth turn clockwise seen from above, M3); tooth j at the
  //! tip points along world angle θ_j = −Ω + j·2π/N, and at height z along θ_j + z·2 tan β / D.
  double spindle_angle_rad = 0.0;
  double feed_direction_rad = 0.0;  //!< direction of XY travel, counter-clockwise from +X, rad
  //! XY displacement of the tool centre since the k-th previous tooth passage (Ω − k·2π/N), for
  //! k = 1.. (index k − 1), mm. Only k = 1 is needed without runout; with runout, up to N.
  std::span<const geometry::Point2> displacement_since_tooth_mm;
};

//! Force on the tool from every engaged tooth element of every slice.
//!
//! The chip at a tooth point q (world angle θ, unit vector e) is the distance by which q reaches
//! beyond the circle cut by the previous tooth, to first order in f_z / r: h = d₁·e, with d₁ the
//! centre displacement since the previous tooth passed θ — exactly f_z sin φ on a straight cut, the
//! chip the Altintas closed forms assume. The second-order term (f_z cos φ)² / 2r, which that
//! circle-to-circle distance adds, is left out so the closed forms are an exact oracle; it is a
//! scallop-height effect, below 1 % of f_z for f_z ≤ 0.02 r. With runout, h = min over the previous
//! teeth k of (d_k·e + r_j − r_{j−k}) (a tooth that cuts deep leaves less for the next ones). The
//! element is in the cut when q lies in the engaged arcs of its layer and h > 0; then
//! dF_t = (K_tc h + K_te) dz, dF_r = (K_rc h + K_re) dz, dF_a = (K_ac h + K_ae) dz, with the cutting
//! coefficients scaled by (h / h_ref)^(−m_c) when the size effect is on, and
//! F = −dF_t·(sin θ, −cos θ) − dF_r·(cos θ, sin θ), F_z = dF_a (docs/method.md §6.1 with feed along +x), and the
//! spindle torque Σ dF_t · r_j.
Force3 milling_force(const CutterGeometry& cutter, const CuttingCoefficients& coefficients, const CutterState& state,
                     std::span<const ForceSlice> slices);

}  // namespace feedplan::sim
