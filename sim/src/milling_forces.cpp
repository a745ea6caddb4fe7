#include "feedplan/sim/milling_forces.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/angle.hpp"

namespace feedplan::sim {

namespace {

// Immersion angle φ = ψ + π/2 − θ wrapped into [−π/2, 3π/2), the range of EngagedInterval.
double immersion_of(double feed_direction_rad, double world_angle_rad) {
  double phi = feed_direction_rad + 0.5 * kPi - world_angle_rad;
  phi = std::fmod(phi + 0.5 * kPi, kTwoPi);
  if (phi < 0.0) phi += kTwoPi;
  return phi - 0.5 * kPi;
}

bool engaged_at(std::span<const geometry::EngagedInterval> arcs, double phi) {
  for (const auto& arc : arcs) {
    if (phi > arc.entry_rad && phi < arc.exit_rad) return true;
  }
  return false;
}

double size_factor(const CuttingCoefficients& k, double h_mm) {
  if (k.size_exponent == 0.0) return 1.0;
  return std::pow(std::max(h_mm, k.size_min_chip_mm) / k.size_reference_chip_mm, -k.size_exponent);
}

}  // namespace

Force3 milling_force(const CutterGeometry& cutter, const CuttingCoefficients& coefficients, const CutterState& state,
                     std::span<const ForceSlice> slices) {
  assert(cutter.flutes > 0 && cutter.radius_mm > 0.0);
  assert(!state.displacement_since_tooth_mm.empty());
  const int n = cutter.flutes;
  const bool runout = !cutter.runout_mm.empty();
  assert(!runout || static_cast<int>(cutter.runout_mm.size()) == n);
  const std::size_t previous_teeth = runout ? std::min<std::size_t>(n, state.displacement_since_tooth_mm.size()) : 1;
  const double pitch_rad = kTwoPi / n;
  const double lag_per_mm = 2.0 * std::tan(deg_to_rad(cutter.helix_deg)) / (2.0 * cutter.radius_mm);

  Force3 force;
  for (const auto& slice : slices) {
    if (slice.engaged.empty() || slice.thickness_mm <= 0.0) continue;
    const double dz = slice.thickness_mm;
    for (int j = 0; j < n; ++j) {
      const double theta = -state.spindle_angle_rad + j * pitch_rad + slice.height_above_tip_mm * lag_per_mm;
      const double phi = immersion_of(state.feed_direction_rad, theta);
      if (!engaged_at(slice.engaged, phi)) continue;
      const double c = std::cos(theta);
      const double s = std::sin(theta);
      double h = 1e300;
      for (std::size_t k = 1; k <= previous_teeth; ++k) {
        const auto& d = state.displacement_since_tooth_mm[k - 1];
        double reach = d.x_mm * c + d.y_mm * s;
        if (runout) reach += cutter.runout_mm[j] - cutter.runout_mm[((j - static_cast<int>(k)) % n + n) % n];
        h = std::min(h, reach);
      }
      if (!(h > 0.0)) continue;
      const double scale = size_factor(coefficients, h);
      const double ft = (coefficients.ktc_n_per_mm2 * scale * h + coefficients.kte_n_per_mm) * dz;
      const double fr = (coefficients.krc_n_per_mm2 * scale * h + coefficients.kre_n_per_mm) * dz;
      const double fa = (coefficients.kac_n_per_mm2 * scale * h + coefficients.kae_n_per_mm) * dz;
      force.fx_n += -ft * s - fr * c;
      force.fy_n += ft * c - fr * s;
      force.fz_n += fa;
    }
  }
  return force;
}

}  // namespace feedplan::sim
