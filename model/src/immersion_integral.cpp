#include "immersion_integral.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/core/angle.hpp"
#include "feedplan/model/mechanistic_force.hpp"

namespace feedplan::model {

double ToothChip::chip_mm(double sin_phi) const {
  if (runout_step_mm.empty()) return feed_per_tooth_mm * sin_phi;
  double h = feed_per_tooth_mm * sin_phi + runout_step_mm[0];
  for (std::size_t k = 1; k < runout_step_mm.size(); ++k) {
    h = std::min(h, static_cast<double>(k + 1) * feed_per_tooth_mm * sin_phi + runout_step_mm[k]);
  }
  return h;
}

double ToothChip::size_factor(double chip_mm) const {
  if (size_exponent == 0.0) return 1.0;
  return std::pow(std::max(chip_mm, size_min_chip_mm) / size_reference_chip_mm, -size_exponent);
}

namespace {

// Closed-form sums with h = f_z sin φ over [lo, hi] ⊂ one [2πm, 2πm + π] (where sin φ ≥ 0).
void add_closed_form(ElementSums& sums, double feed_mm, double lo, double hi, double weight) {
  const double s_lo = std::sin(lo), s_hi = std::sin(hi);
  const double c_lo = std::cos(lo), c_hi = std::cos(hi);
  const double sin_cos = 0.5 * (s_hi * s_hi - s_lo * s_lo);                            // ∫ sin φ cos φ
  const double sin_sq = 0.5 * (hi - lo) - 0.5 * (s_hi * c_hi - s_lo * c_lo);          // ∫ sin² φ
  const double cos_int = s_hi - s_lo;                                                  // ∫ cos φ
  const double sin_int = c_lo - c_hi;                                                  // ∫ sin φ
  sums.a += weight * feed_mm * sin_cos;
  sums.b += weight * feed_mm * sin_sq;
  sums.c += weight * cos_int;
  sums.s += weight * sin_int;
  sums.h += weight * feed_mm * sin_int;
  sums.l += weight * (hi - lo);
}

// The element at φ (sine s, cosine c) with its chip h > 0, times weight.
void add_cut_element(ElementSums& sums, const ToothChip& chip, double s, double c, double h, double weight) {
  const double sh = chip.size_factor(h) * h;
  sums.a += weight * sh * c;
  sums.b += weight * sh * s;
  sums.c += weight * c;
  sums.s += weight * s;
  sums.h += weight * sh;
  sums.l += weight;
}

// Midpoint rule (add_cell) on cells of at most kChipCellRad.
void add_on_cells(ElementSums& sums, const ToothChip& chip, double lo, double hi, double weight) {
  const int cells = std::max(1, static_cast<int>(std::ceil((hi - lo) / kChipCellRad)));
  const double width = (hi - lo) / cells;
  double h_left = chip.chip_mm(std::sin(lo));
  for (int i = 0; i < cells; ++i) {
    const double left = lo + i * width;
    const double h_right = chip.chip_mm(std::sin(left + width));
    add_cell(sums, chip, left, left + width, h_left, h_right, weight);
    h_left = h_right;
  }
}

}  // namespace

void add_cell(ElementSums& sums, const ToothChip& chip, double left_rad, double right_rad, double h_left_mm,
              double h_right_mm, double weight) {
  const double width = right_rad - left_rad;
  double a = left_rad, b = right_rad;
  if (h_left_mm > 0.0 && h_right_mm <= 0.0) {
    b = left_rad + width * h_left_mm / (h_left_mm - h_right_mm);
  } else if (h_left_mm <= 0.0 && h_right_mm > 0.0) {
    a = left_rad + width * h_left_mm / (h_left_mm - h_right_mm);
  } else if (h_left_mm <= 0.0 && h_right_mm <= 0.0) {
    return;  // a bump above 0 inside one cell is below the rule's resolution
  }
  if (!(b > a)) return;
  const double mid = 0.5 * (a + b);
  const double s = std::sin(mid), c = std::cos(mid);
  const double h = chip.chip_mm(s);
  if (h > 0.0) add_cut_element(sums, chip, s, c, h, weight * (b - a));
}

void add_immersion_integral(ElementSums& sums, const ToothChip& chip, double lo_rad, double hi_rad, double weight) {
  if (!(hi_rad > lo_rad)) return;
  if (!chip.closed_form()) {
    add_on_cells(sums, chip, lo_rad, hi_rad, weight);
    return;
  }
  // Only the half turns [2πm, 2πm + π] carry a chip.
  const int m_first = static_cast<int>(std::floor(lo_rad / kTwoPi));
  const int m_last = static_cast<int>(std::floor(hi_rad / kTwoPi));
  for (int m = m_first; m <= m_last; ++m) {
    const double lo = std::max(lo_rad, m * kTwoPi);
    const double hi = std::min(hi_rad, m * kTwoPi + kPi);
    if (hi > lo) add_closed_form(sums, chip.feed_per_tooth_mm, lo, hi, weight);
  }
}

void add_element(ElementSums& sums, const ToothChip& chip, double phi_rad, double weight) {
  add_element(sums, chip, std::sin(phi_rad), std::cos(phi_rad), weight);
}

void add_element(ElementSums& sums, const ToothChip& chip, double sin_phi, double cos_phi, double weight) {
  const double h = chip.chip_mm(sin_phi);
  if (h > 0.0) add_cut_element(sums, chip, sin_phi, cos_phi, h, weight);
}

}  // namespace feedplan::model
