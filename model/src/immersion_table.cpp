#include "immersion_table.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace feedplan::model {

ImmersionTable::ImmersionTable(const ToothChip& chip, double lo_rad, double hi_rad) : lo_rad_(lo_rad) {
  assert(hi_rad > lo_rad);
  const int steps = std::max(1, static_cast<int>(std::ceil((hi_rad - lo_rad) / kTableStepRad)));
  step_rad_ = (hi_rad - lo_rad) / steps;
  running_.resize(static_cast<std::size_t>(steps) + 1);
  // Each node's chip is computed once and shared by the two steps it bounds.
  double h_left = chip.chip_mm(std::sin(lo_rad));
  for (int i = 0; i < steps; ++i) {
    const double left = lo_rad + i * step_rad_, right = lo_rad + (i + 1) * step_rad_;
    const double h_right = chip.chip_mm(std::sin(right));
    ElementSums next = running_[i];
    add_cell(next, chip, left, right, h_left, h_right, 1.0);
    running_[i + 1] = next;
    h_left = h_right;
  }
}

ElementSums ImmersionTable::running_at(double phi_rad) const {
  const double x = (phi_rad - lo_rad_) / step_rad_;
  const int last = static_cast<int>(running_.size()) - 1;
  assert(x > -1e-6 && x < last + 1e-6);
  const int i = std::clamp(static_cast<int>(std::floor(x)), 0, last - 1);
  const double t = std::clamp(x - i, 0.0, 1.0);
  const ElementSums& a = running_[i];
  const ElementSums& b = running_[i + 1];
  return {a.a + t * (b.a - a.a), a.b + t * (b.b - a.b), a.c + t * (b.c - a.c),
          a.s + t * (b.s - a.s), a.h + t * (b.h - a.h), a.l + t * (b.l - a.l)};
}

void ImmersionTable::add_integral(ElementSums& sums, double lo_rad, double hi_rad, double weight) const {
  if (!(hi_rad > lo_rad)) return;
  const ElementSums lo = running_at(lo_rad);
  const ElementSums hi = running_at(hi_rad);
  sums.a += weight * (hi.a - lo.a);
  sums.b += weight * (hi.b - lo.b);
  sums.c += weight * (hi.c - lo.c);
  sums.s += weight * (hi.s - lo.s);
  sums.h += weight * (hi.h - lo.h);
  sums.l += weight * (hi.l - lo.l);
}

}  // namespace feedplan::model
