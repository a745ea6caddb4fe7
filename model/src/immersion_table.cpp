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
  // The sines and cosines of the nodes and midpoints by rotation through half a step (drift ~1e-13
  // over a table), and each node's chip computed once for the two steps it bounds.
  const double rot_cos = std::cos(0.5 * step_rad_), rot_sin = std::sin(0.5 * step_rad_);
  double sin_at = std::sin(lo_rad), cos_at = std::cos(lo_rad);
  auto rotate = [&] {
    const double next_sin = sin_at * rot_cos + cos_at * rot_sin;
    cos_at = cos_at * rot_cos - sin_at * rot_sin;
    sin_at = next_sin;
  };
  double h_left = chip.chip_mm(sin_at);
  for (int i = 0; i < steps; ++i) {
    rotate();
    const double mid_sin = sin_at, mid_cos = cos_at;
    rotate();
    const double left = lo_rad + i * step_rad_, right = lo_rad + (i + 1) * step_rad_;
    const double h_right = chip.chip_mm(sin_at);
    ElementSums next = running_[i];
    if (h_left > 0.0 && h_right > 0.0) {
      add_element(next, chip, mid_sin, mid_cos, right - left);
    } else {
      add_cell(next, chip, left, right, h_left, h_right, 1.0);
    }
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
