#pragma once
// One tooth's element integrals tabulated against the immersion, for the size effect and runout: the
// running integral G(φ) of the six sums (immersion_integral.hpp) on nodes kTableStepRad apart, so that
// the integral over any immersion range is G(hi) − G(lo). Built once per feed and engagement, it
// replaces the cells of every spindle angle and flute by two look-ups.
//
// Each node-to-node step is integrated as add_immersion_integral does (midpoint rule, the part with
// h > 0 where h changes sign); between nodes G is interpolated linearly, which is exact for a constant
// integrand and off by at most step² / 8 · |dg/dφ| otherwise — 1e-5 rad² × |dg/dφ| at 0.5°, about 1e-5
// of a tooth's force for an integrand like sin φ over a typical engaged range.

#include <vector>

#include "immersion_integral.hpp"

namespace feedplan::model {

//! Node spacing of the table, rad (0.5°).
inline constexpr double kTableStepRad = 3.14159265358979323846 / 360.0;

class ImmersionTable {
 public:
  //! The table of `chip` over [lo_rad, hi_rad] (lo < hi).
  ImmersionTable(const ToothChip& chip, double lo_rad, double hi_rad);

  //! Adds weight × the integrals over [lo_rad, hi_rad] to `sums`; both ends must lie in the table's range
  //! (asserted, to a rounding tolerance).
  void add_integral(ElementSums& sums, double lo_rad, double hi_rad, double weight) const;

 private:
  ElementSums running_at(double phi_rad) const;

  double lo_rad_;
  double step_rad_;
  std::vector<ElementSums> running_;  // G at the nodes lo + i·step
};

}  // namespace feedplan::model
