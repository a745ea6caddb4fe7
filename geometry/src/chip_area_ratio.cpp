#include "feedplan/geometry/chip_area_ratio.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/core/angle.hpp"

namespace feedplan::geometry {

double chip_factor(const EngagedInterval* begin, const EngagedInterval* end) {
  double best = 0.0;
  for (const auto* i = begin; i != end; ++i) {
    if (i->entry_rad <= 0.5 * kPi && i->exit_rad >= 0.5 * kPi) return 1.0;
    best = std::max({best, std::sin(i->entry_rad), std::sin(i->exit_rad)});
  }
  return best;
}

double chip_area_ratio(const EngagedInterval* begin, const EngagedInterval* end) {
  double engaged_rad = 0.0;
  double area = 0.0;  // ∫ max(sin φ, 0) dφ
  for (const auto* i = begin; i != end; ++i) {
    engaged_rad += i->exit_rad - i->entry_rad;
    // sin φ > 0 on (0, π) (and on (2π, 3π), outside the reported range [−π/2, 3π/2)).
    const double a = std::max(i->entry_rad, 0.0);
    const double b = std::min(i->exit_rad, kPi);
    if (b > a) area += std::cos(a) - std::cos(b);
  }
  const double k = chip_factor(begin, end);
  if (!(engaged_rad > 0.0) || !(k > 1e-9) || !(area > 0.0)) return 1.0;
  const double straight_area = 1.0 - std::cos(std::min(engaged_rad, kPi));
  const double straight_chip_factor = std::sin(std::min(engaged_rad, 0.5 * kPi));
  if (!(straight_area > 0.0)) return 1.0;
  return std::max(1.0, area * straight_chip_factor / (k * straight_area));
}

}  // namespace feedplan::geometry
