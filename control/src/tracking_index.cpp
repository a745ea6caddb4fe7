#include "feedplan/control/tracking_index.hpp"

#include <cassert>
#include <cmath>

namespace feedplan::control {

double period_absolute_area(std::span<const double> a, std::span<const double> b, double period_s) {
  assert(a.size() == b.size() && a.size() >= 2);
  const double h = period_s / static_cast<double>(a.size() - 1);
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < a.size(); ++i) area += 0.5 * h * (std::abs(a[i] - b[i]) + std::abs(a[i + 1] - b[i + 1]));
  return area;
}

double tracking_index(std::span<const double> areas_newest_first, double forgetting_factor) {
  assert(forgetting_factor > 0.0 && forgetting_factor <= 1.0);
  double index = 0.0, weight = 1.0;
  for (double area : areas_newest_first) {
    index += weight * area;
    weight *= forgetting_factor;
  }
  return index;
}

}  // namespace feedplan::control
