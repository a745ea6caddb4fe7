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

// φ wrapped into [−π/2, 3π/2) as immersion_of does, cheaply when φ is within a turn of that range
// (a tooth pitch or a helix lag away from a wrapped angle).
double wrapped_immersion(double phi) {
  if (phi < -0.5 * kPi) {
    phi += kTwoPi;
  } else if (phi >= 1.5 * kPi) {
    phi -= kTwoPi;
  }
  if (phi >= -0.5 * kPi && phi < 1.5 * kPi) return phi;
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

// The part of the immersions [φ − w, φ + w] that lies in the arcs: a slice's flute spans that range over its
// height (w = half the slice's helix lag), and the slice cuts with that part of its height, at the part's
// centre. Counting a slice whole or not at all by its midpoint made the force jump by a slice each time a
// flute crossed an arc's end, and the per-revolution peak pick the upper jumps (+2.5 % on a 20° arc with
// 0.25 mm slices of a 30° helix). With w = 0 (straight flutes) it is the midpoint test.
struct EngagedPart {
  double fraction = 0.0;  // of the slice's height, in [0, 1]
  double centre_rad = 0.0;  // immersion at the middle of the engaged part
};

EngagedPart engaged_part(std::span<const geometry::EngagedInterval> arcs, double phi, double half_width_rad) {
  if (!(half_width_rad > 0.0)) return {engaged_at(arcs, phi) ? 1.0 : 0.0, phi};
  const double lo = phi - half_width_rad, hi = phi + half_width_rad;
  double inside = 0.0, moment = 0.0;
  for (const auto& arc : arcs) {
    const double a = std::max(lo, arc.entry_rad), b = std::min(hi, arc.exit_rad);
    if (b <= a) continue;
    inside += b - a;
    moment += 0.5 * (b * b - a * a);
  }
  if (inside <= 0.0) return {};
  return {std::min(1.0, inside / (hi - lo)), moment / inside};
}

double size_factor(const CuttingCoefficients& k, double h_mm) {
  if (k.size_exponent == 0.0) return 1.0;
  return std::pow(std::max(h_mm, k.size_min_chip_mm) / k.size_reference_chip_mm, -k.size_exponent);
}

// What every slice's teeth share at this instant.
struct Teeth {
  int count = 0;
  double pitch_rad = 0.0;
  double cos_pitch = 1.0;
  double sin_pitch = 0.0;
  double lag_per_mm = 0.0;  // helix lag of the flutes per mm above the tip, rad
  double theta0_rad = 0.0;  // world angle of tooth 0 at the tip, −Ω within one turn
  double phi0_rad = 0.0;    // its immersion
  std::size_t previous_teeth = 1;  // tooth passages the chip depends on
};

// The cosine and sine of tooth 0's world angle θ₀ + lag on successive slices: the first from std::cos
// and std::sin, each next one turned from the one before through the lag between them. Slices lie a
// layer apart, so one turn's cosine and sine serve them all: a lag step within kSameTurnRad of the
// last one reuses it (the angle is then off by that much at most, and the next step makes up for it).
class ToothZeroAngle {
 public:
  explicit ToothZeroAngle(double theta0_rad) : theta0_rad_(theta0_rad) {}

  void move_to(double lag_rad) {
    if (!started_) {
      c_ = std::cos(theta0_rad_ + lag_rad);
      s_ = std::sin(theta0_rad_ + lag_rad);
      lag_rad_ = lag_rad;
      started_ = true;
      return;
    }
    const double step = lag_rad - lag_rad_;
    if (std::abs(step - step_rad_) > kSameTurnRad) {
      step_rad_ = step;
      cos_step_ = std::cos(step);
      sin_step_ = std::sin(step);
    }
    const double next_c = c_ * cos_step_ - s_ * sin_step_;
    s_ = s_ * cos_step_ + c_ * sin_step_;
    c_ = next_c;
    lag_rad_ += step_rad_;
  }
  double cos() const { return c_; }
  double sin() const { return s_; }

 private:
  static constexpr double kSameTurnRad = 1e-12;
  double theta0_rad_;
  bool started_ = false;
  double lag_rad_ = 0.0;   // the lag c_ and s_ are at
  double c_ = 1.0;
  double s_ = 0.0;
  double step_rad_ = 0.0;  // the last turn, and its cosine and sine
  double cos_step_ = 1.0;
  double sin_step_ = 0.0;
};

// The chip of tooth j at a point along (c, s): by how far it reaches beyond the circles the previous
// teeth cut, mm (≤ 0: it cuts nothing).
double chip_mm(const CutterGeometry& cutter, const CutterState& state, const Teeth& teeth, int j, double c, double s) {
  const int n = teeth.count;
  double h = 1e300;
  for (std::size_t k = 1; k <= teeth.previous_teeth; ++k) {
    const auto& d = state.displacement_since_tooth_mm[k - 1];
    double reach = d.x_mm * c + d.y_mm * s;
    if (!cutter.runout_mm.empty()) {
      reach += cutter.runout_mm[j] - cutter.runout_mm[((j - static_cast<int>(k)) % n + n) % n];
    }
    h = std::min(h, reach);
  }
  return h;
}

// The force of every engaged tooth element of one slice, added to `force`. Tooth j's world angle is
// θ₀ + lag + j·pitch and its immersion φ₀ − lag − j·pitch; the cosine and sine of its angle follow
// from tooth 0's (`tooth0`, at this slice's lag) by rotations through the pitch.
void add_slice_force(Force3& force, const CutterGeometry& cutter, const CuttingCoefficients& k,
                     const CutterState& state, const Teeth& teeth, const ForceSlice& slice, double lag,
                     const ToothZeroAngle& tooth0) {
  const double half_lag_rad = 0.5 * std::abs(slice.thickness_mm * teeth.lag_per_mm);
  int at_tooth = 0;  // the tooth whose angle c, s hold
  double c = tooth0.cos();
  double s = tooth0.sin();
  for (int j = 0; j < teeth.count; ++j) {
    const double phi = wrapped_immersion(teeth.phi0_rad - lag - j * teeth.pitch_rad);
    const EngagedPart part = engaged_part(slice.engaged, phi, half_lag_rad);
    if (part.fraction == 0.0) continue;
    const double dz = part.fraction * slice.thickness_mm;
    for (; at_tooth < j; ++at_tooth) {
      const double next_c = c * teeth.cos_pitch - s * teeth.sin_pitch;
      s = s * teeth.cos_pitch + c * teeth.sin_pitch;
      c = next_c;
    }
    double c_part = c, s_part = s;
    if (part.fraction < 1.0) {  // the world angle falls as the immersion rises
      const double turn = phi - part.centre_rad;
      c_part = c * std::cos(turn) - s * std::sin(turn);
      s_part = s * std::cos(turn) + c * std::sin(turn);
    }
    const double h = chip_mm(cutter, state, teeth, j, c_part, s_part);
    if (!(h > 0.0)) continue;
    const double scale = size_factor(k, h);
    const double ft = (k.ktc_n_per_mm2 * scale * h + k.kte_n_per_mm) * dz;
    const double fr = (k.krc_n_per_mm2 * scale * h + k.kre_n_per_mm) * dz;
    const double fa = (k.kac_n_per_mm2 * scale * h + k.kae_n_per_mm) * dz;
    force.fx_n += -ft * s_part - fr * c_part;
    force.fy_n += ft * c_part - fr * s_part;
    force.fz_n += fa;
    force.torque_nmm += ft * (cutter.runout_mm.empty() ? cutter.radius_mm : cutter.radius_mm + cutter.runout_mm[j]);
  }
}

}  // namespace

Force3 milling_force(const CutterGeometry& cutter, const CuttingCoefficients& coefficients, const CutterState& state,
                     std::span<const ForceSlice> slices) {
  assert(cutter.flutes > 0 && cutter.radius_mm > 0.0);
  assert(!state.displacement_since_tooth_mm.empty());
  const bool runout = !cutter.runout_mm.empty();
  assert(!runout || static_cast<int>(cutter.runout_mm.size()) == cutter.flutes);
  Teeth teeth;
  teeth.count = cutter.flutes;
  teeth.pitch_rad = kTwoPi / cutter.flutes;
  teeth.cos_pitch = std::cos(teeth.pitch_rad);
  teeth.sin_pitch = std::sin(teeth.pitch_rad);
  teeth.lag_per_mm = 2.0 * std::tan(deg_to_rad(cutter.helix_deg)) / (2.0 * cutter.radius_mm);
  // Reduced once here rather than per element: Ω grows by 2π every revolution.
  teeth.theta0_rad = -std::fmod(state.spindle_angle_rad, kTwoPi);
  teeth.phi0_rad = immersion_of(state.feed_direction_rad, teeth.theta0_rad);
  teeth.previous_teeth = runout ? std::min<std::size_t>(cutter.flutes, state.displacement_since_tooth_mm.size()) : 1;

  Force3 force;
  ToothZeroAngle tooth0(teeth.theta0_rad);
  for (const auto& slice : slices) {
    if (slice.engaged.empty() || slice.thickness_mm <= 0.0) continue;
    const double lag = slice.height_above_tip_mm * teeth.lag_per_mm;
    tooth0.move_to(lag);
    add_slice_force(force, cutter, coefficients, state, teeth, slice, lag, tooth0);
  }
  return force;
}

}  // namespace feedplan::sim
