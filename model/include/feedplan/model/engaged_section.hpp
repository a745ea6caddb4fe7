#pragma once
// The engagement as the mechanistic force model sees it, with no geometry types: the cutter, and for
// each band of heights above the tool tip, the arcs of the tool circle that are in material.
//
// Angles are immersion angles φ as in Altintas (Manufacturing Automation, ch. 2), the convention of
// geometry::EngagedInterval: in the feed frame (x along the feed, y to its left, z up the tool axis),
// φ is measured clockwise seen from above — the sense in which an M3 spindle turns the teeth — from +y.
// φ = 0 is the left of the feed, π/2 the front, π the right; a full slot is [0, π], down (climb)
// milling with the material on the right ends at π, up milling starts at 0. Arcs may lie anywhere in
// [−π/2, 3π/2) (the range geometry reports them in); outside (0, π) a tooth without runout cuts no chip.

#include <span>

namespace feedplan::model {

//! One engaged arc of the tool circle, immersion angles in radians (entry_rad ≤ exit_rad).
struct ImmersionArc {
  double entry_rad = 0.0;  //!< where a tooth enters the material
  double exit_rad = 0.0;   //!< where it leaves
};

//! A band of heights above the tool tip over which the engaged arcs are the same.
struct EngagedSection {
  double bottom_mm = 0.0;               //!< lower end of the band, above the tool tip, mm
  double top_mm = 0.0;                  //!< upper end, above the tool tip, mm (≥ bottom_mm)
  std::span<const ImmersionArc> arcs;   //!< engaged arcs on the band (may be empty: nothing in cut)
};

//! The cutter's shape as the force kernel needs it.
struct CutterGeometry {
  double radius_mm = 5.0;   //!< nominal radius r, mm (> 0)
  int flutes = 4;           //!< number of teeth N (≥ 1)
  //! Helix angle β, deg, in (−90, 90): a flute point z above the tip lags the tip by z·tan β / r (a
  //! negative angle leads). 0 is a straight flute.
  double helix_deg = 30.0;
};

}  // namespace feedplan::model
