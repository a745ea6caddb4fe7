#include "feedplan/geometry/chip_load.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "feedplan/core/angle.hpp"

namespace feedplan::geometry {

namespace {

// Below this lag (rad/mm) the flute is straight: a point's immersion does not change with height.
constexpr double kStraightFluteLag = 1e-9;

// One band of heights above the tip with its engaged immersion intervals.
struct LoadLayer {
  double low_mm;   // above the tip
  double high_mm;
  std::span<const EngagedInterval> arcs;
};

// An end of an integration range with its cosine (computed without trigonometry in the inner loop).
struct Bound {
  double value;
  double cos;
};

// ∫ max(sin u, 0) du over [a, b] ∩ arcs (shifted by whole turns to meet [a, b]); `arc_cos` holds the
// cosines of the arcs' ends clipped to [0, π].
double chip_integral(Bound a, Bound b, std::span<const EngagedInterval> arcs, std::span<const Bound> arc_ends) {
  double total = 0.0;
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    const Bound lo_arc = arc_ends[2 * i];
    const Bound hi_arc = arc_ends[2 * i + 1];
    if (!(hi_arc.value > lo_arc.value)) continue;
    // Shifts k·2π that bring the arc over [a, b]; cos is the same on every turn.
    const int k_first = static_cast<int>(std::floor((a.value - hi_arc.value) / kTwoPi));
    const int k_last = static_cast<int>(std::ceil((b.value - lo_arc.value) / kTwoPi));
    for (int k = k_first; k <= k_last; ++k) {
      const double shift = k * kTwoPi;
      const Bound& lo = a.value > lo_arc.value + shift ? a : lo_arc;
      const Bound& hi = b.value < hi_arc.value + shift ? b : hi_arc;
      const double lo_value = &lo == &a ? a.value : lo_arc.value + shift;
      const double hi_value = &hi == &b ? b.value : hi_arc.value + shift;
      if (hi_value > lo_value) total += lo.cos - hi.cos;
    }
  }
  return total;
}

// True when immersion φ (any turn) lies in one of the arcs; then its chip factor max(sin φ, 0).
double chip_at(double phi, std::span<const EngagedInterval> arcs) {
  const double wrapped = phi - kTwoPi * std::floor((phi + 0.5 * kPi) / kTwoPi);  // into [−π/2, 3π/2)
  for (const EngagedInterval& arc : arcs) {
    if (wrapped >= arc.entry_rad && wrapped <= arc.exit_rad) return std::max(std::sin(wrapped), 0.0);
  }
  return 0.0;
}

// One layer prepared for the inner loop: cos/sin of the lag at its ends, the cosines of its arcs' ends.
struct PreparedLayer {
  const LoadLayer* layer;
  double cos_low, sin_low, cos_high, sin_high;  // of lag · height
  std::vector<Bound> arc_ends;
};

std::vector<PreparedLayer> prepare(std::span<const LoadLayer> layers, double lag) {
  std::vector<PreparedLayer> prepared;
  for (const LoadLayer& layer : layers) {
    PreparedLayer p{&layer, std::cos(lag * layer.low_mm), std::sin(lag * layer.low_mm), std::cos(lag * layer.high_mm),
                    std::sin(lag * layer.high_mm), {}};
    for (const EngagedInterval& arc : layer.arcs) {
      const double lo = std::max(arc.entry_rad, 0.0);
      const double hi = std::min(arc.exit_rad, kPi);
      p.arc_ends.push_back({lo, std::cos(lo)});
      p.arc_ends.push_back({hi, std::cos(hi)});
    }
    prepared.push_back(std::move(p));
  }
  return prepared;
}

// C(Ω) for the tooth at tip immersion φ0 (with its cos and sin) over all layers.
double tooth_load(double phi0, double c0, double s0, double lag, std::span<const PreparedLayer> layers) {
  double load = 0.0;
  for (const PreparedLayer& p : layers) {
    const LoadLayer& layer = *p.layer;
    if (lag < kStraightFluteLag) {
      load += (layer.high_mm - layer.low_mm) * chip_at(phi0, layer.arcs);
    } else {
      // cos(φ0 − λz) = cos φ0 cos λz + sin φ0 sin λz
      const Bound a{phi0 - lag * layer.high_mm, c0 * p.cos_high + s0 * p.sin_high};
      const Bound b{phi0 - lag * layer.low_mm, c0 * p.cos_low + s0 * p.sin_low};
      load += chip_integral(a, b, layer.arcs, p.arc_ends) / lag;
    }
  }
  return load;
}

// The tip immersions the peak is sampled at, φ = 2π·k/(kChipLoadSteps·N) for k = step + j·kChipLoadSteps,
// with their cosines and sines: the same for every call with N teeth, so computed once per N.
struct ToothAngles {
  std::vector<double> phi, cos, sin;
};

const ToothAngles& tooth_angles(int flutes) {
  thread_local std::vector<ToothAngles> tables;
  if (static_cast<std::size_t>(flutes) >= tables.size()) tables.resize(static_cast<std::size_t>(flutes) + 1);
  ToothAngles& t = tables[static_cast<std::size_t>(flutes)];
  if (t.phi.empty()) {
    const double period = kTwoPi / flutes;
    for (int j = 0; j < flutes; ++j) {
      for (int step = 0; step < kChipLoadSteps; ++step) {
        const double phi0 = period * step / kChipLoadSteps + j * period;
        t.phi.push_back(phi0);
        t.cos.push_back(std::cos(phi0));
        t.sin.push_back(std::sin(phi0));
      }
    }
  }
  return t;
}

// C(Ω) at the kChipLoadSteps spindle angles of one tooth period (empty without layers or a usable tool).
std::vector<double> load_waveform(std::span<const LoadLayer> layers, const Tool& tool) {
  if (layers.empty() || tool.flutes < 1 || !(tool.diameter_mm > 0.0)) return {};
  const double lag = std::abs(std::tan(deg_to_rad(tool.helix_deg))) / tool.radius_mm();
  const std::vector<PreparedLayer> prepared = prepare(layers, lag);
  const ToothAngles& angles = tooth_angles(tool.flutes);
  std::vector<double> waveform(kChipLoadSteps, 0.0);
  for (int step = 0; step < kChipLoadSteps; ++step) {
    double load = 0.0;
    for (int j = 0; j < tool.flutes; ++j) {
      const auto k = static_cast<std::size_t>(step + j * kChipLoadSteps);
      load += tooth_load(angles.phi[k], angles.cos[k], angles.sin[k], lag, prepared);
    }
    waveform[static_cast<std::size_t>(step)] = load;
  }
  return waveform;
}

double peak_load(std::span<const LoadLayer> layers, const Tool& tool) {
  const std::vector<double> waveform = load_waveform(layers, tool);
  return waveform.empty() ? 0.0 : std::max(0.0, *std::max_element(waveform.begin(), waveform.end()));
}

std::vector<LoadLayer> sample_layers(const EngagementProfile& profile, const EngagementSample& sample) {
  std::vector<LoadLayer> layers;
  for (int k = 0; k < sample.layer_count; ++k) {
    const EngagementLayer& layer = profile.layers[static_cast<std::size_t>(sample.layer_begin + k)];
    layers.push_back({layer.bottom_z_mm - sample.position.z_mm, layer.top_z_mm - sample.position.z_mm,
                      {profile.intervals.data() + layer.interval_begin, static_cast<std::size_t>(layer.interval_count)}});
  }
  return layers;
}

}  // namespace

double peak_chip_load_mm(const EngagementProfile& profile, const EngagementSample& sample, const Tool& tool) {
  return peak_load(sample_layers(profile, sample), tool);
}

std::vector<double> chip_load_waveform_mm(const EngagementProfile& profile, const EngagementSample& sample,
                                          const Tool& tool) {
  return load_waveform(sample_layers(profile, sample), tool);
}

double straight_cut_chip_load_mm(double engagement_rad, double depth_mm, const Tool& tool) {
  const double alpha = std::clamp(engagement_rad, 0.0, kPi);
  const EngagedInterval arc{kPi - alpha, kPi};
  const LoadLayer layer{0.0, std::max(depth_mm, 0.0), {&arc, 1}};
  return peak_load({&layer, 1}, tool);
}

}  // namespace feedplan::geometry
