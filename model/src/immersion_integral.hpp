#pragma once
// Integrals of one tooth's element forces over a range of immersions (mechanistic_force.hpp): the six
// sums the force is linear in, in closed form when the chip is f_z·sin φ, on cells otherwise.

#include <vector>

namespace feedplan::model {

//! ∫ over the cut of s·h·cos φ, s·h·sin φ, cos φ, sin φ, s·h and 1, per unit of the weight (dz / dφ);
//! the force is F_x = −K_tc a − K_rc b − K_te c − K_re s, F_y = K_tc b − K_rc a + K_te s − K_re c,
//! F_z = K_ac h + K_ae l.
struct ElementSums {
  double a = 0.0;  //!< ∫ s·h·cos φ, mm²
  double b = 0.0;  //!< ∫ s·h·sin φ, mm²
  double c = 0.0;  //!< ∫ cos φ, mm
  double s = 0.0;  //!< ∫ sin φ, mm
  double h = 0.0;  //!< ∫ s·h, mm²
  double l = 0.0;  //!< ∫ 1: length of edge in the cut, mm
};

//! The chip rule of one tooth: h(φ) = min_k (k·f_z·sin φ + Δr_k), Δr_k = r_j − r_{j−k}, with the size
//! factor s(h) = (max(h, h_min) / h_ref)^(−m).
struct ToothChip {
  double feed_per_tooth_mm = 0.0;
  std::vector<double> runout_step_mm;  //!< Δr_k for k = 1 … N; empty: no runout, h = f_z sin φ
  double size_exponent = 0.0;
  double size_reference_chip_mm = 0.1;
  double size_min_chip_mm = 0.005;

  //! True when h = f_z sin φ and s ≡ 1: the sums are closed form.
  bool closed_form() const { return runout_step_mm.empty() && size_exponent == 0.0; }
  //! The chip at an immersion with this sine, mm (≤ 0: no cut).
  double chip_mm(double sin_phi) const;
  //! s(h) for a chip h > 0.
  double size_factor(double chip_mm) const;
};

//! Adds weight × the integrals over immersions [lo_rad, hi_rad] (lo ≤ hi, any turn) to `sums`.
void add_immersion_integral(ElementSums& sums, const ToothChip& chip, double lo_rad, double hi_rad, double weight);

//! Adds weight × one cell [left_rad, right_rad] by the midpoint rule, given the chip at its ends: a
//! cell where h changes sign is integrated over its part with h > 0 only, the root placed by linear
//! interpolation of h between the ends. add_immersion_integral's cells of the size effect and runout.
void add_cell(ElementSums& sums, const ToothChip& chip, double left_rad, double right_rad, double h_left_mm,
              double h_right_mm, double weight);

//! Adds weight × the element at immersion `phi_rad` to `sums` (a straight flute: the same immersion
//! over the whole section; weight is its height).
void add_element(ElementSums& sums, const ToothChip& chip, double phi_rad, double weight);

//! The same at the immersion with sine `sin_phi` and cosine `cos_phi`.
void add_element(ElementSums& sums, const ToothChip& chip, double sin_phi, double cos_phi, double weight);

}  // namespace feedplan::model
