#include "feedplan/model/mechanistic_force.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "immersion_integral.hpp"
#include "immersion_table.hpp"

namespace feedplan::model {
namespace {

// Below this helix lag (rad/mm) a flute is straight: its immersion does not change with height.
constexpr double kStraightFluteLag = 1e-9;
// The golden-section search stops when the peak is bracketed this closely, rad.
constexpr double kPeakAngleToleranceRad = 1e-5;
// Sampled local maxima this far below the largest sample are not refined: sampling misses a peak by
// far less (a fraction of a percent at 64 samples per tooth period).
constexpr double kPeakCandidateRatio = 0.98;
// The same with runout, where the coarser scan misses a peak at a kink (a tooth entering) by more.
constexpr double kPeakCandidateRatioRunout = 0.9;

// What every evaluation on one engagement shares: the teeth's chip rules and the flute lag.
class Kernel {
 public:
  Kernel(const MechanisticModel& model, std::span<const EngagedSection> sections, const CutterGeometry& cutter,
         double feed_per_tooth_mm)
      : sections_(sections),
        pitch_rad_(kTwoPi / cutter.flutes),
        lag_rad_per_mm_(std::tan(deg_to_rad(model.helix_deg.value_or(cutter.helix_deg))) / cutter.radius_mm) {
    assert(cutter.flutes >= 1 && cutter.radius_mm > 0.0 && feed_per_tooth_mm > 0.0);
    assert(model.runout_mm.empty() || static_cast<int>(model.runout_mm.size()) == cutter.flutes);
    const int n = cutter.flutes;
    for (int j = 0; j < n; ++j) {
      ToothChip chip{feed_per_tooth_mm, {}, model.size_exponent, model.size_reference_chip_mm, model.size_min_chip_mm};
      if (!model.runout_mm.empty()) {
        for (int k = 1; k <= n; ++k) chip.runout_step_mm.push_back(model.runout_mm[j] - model.runout_mm[((j - k) % n + n) % n]);
      }
      teeth_.push_back(std::move(chip));
    }
    if (!teeth_.front().closed_form()) build_tables();
  }

  bool has_runout() const { return !teeth_.front().runout_step_mm.empty(); }
  double pitch_rad() const { return pitch_rad_; }

  // The sums of every tooth at spindle angle Ω.
  ElementSums at(double spindle_angle_rad) const {
    ElementSums sums;
    for (std::size_t j = 0; j < teeth_.size(); ++j) {
      const double tip_phi = spindle_angle_rad - static_cast<double>(j) * pitch_rad_;
      const ImmersionTable* table = tables_.empty() ? nullptr : &tables_[has_runout() ? j : 0];
      for (const EngagedSection& section : sections_) {
        if (!(section.top_mm > section.bottom_mm)) continue;
        add_flute(sums, teeth_[j], table, tip_phi, section);
      }
    }
    return sums;
  }

  // The sums averaged over a revolution: each tooth sweeps every immersion once.
  ElementSums mean() const {
    ElementSums sums;
    for (const ToothChip& chip : teeth_) {
      for (const EngagedSection& section : sections_) {
        if (!(section.top_mm > section.bottom_mm)) continue;
        const double weight = (section.top_mm - section.bottom_mm) / kTwoPi;
        for (const ImmersionArc& arc : section.arcs) add_immersion_integral(sums, chip, arc.entry_rad, arc.exit_rad, weight);
      }
    }
    return sums;
  }

 private:
  // With the size effect or runout: each distinct tooth's integrals tabulated over the arcs' range.
  void build_tables() {
    double lo = 1e300, hi = -1e300;
    for (const EngagedSection& section : sections_) {
      for (const ImmersionArc& arc : section.arcs) {
        lo = std::min(lo, arc.entry_rad);
        hi = std::max(hi, arc.exit_rad);
      }
    }
    if (!(hi > lo) || std::abs(lag_rad_per_mm_) < kStraightFluteLag) return;
    const std::size_t distinct = has_runout() ? teeth_.size() : 1;
    for (std::size_t j = 0; j < distinct; ++j) tables_.emplace_back(teeth_[j], lo, hi);
  }

  // One tooth's flute over one section: the immersions it spans there, met with the arcs on any turn.
  void add_flute(ElementSums& sums, const ToothChip& chip, const ImmersionTable* table, double tip_phi,
                 const EngagedSection& section) const {
    if (std::abs(lag_rad_per_mm_) < kStraightFluteLag) {
      for (const ImmersionArc& arc : section.arcs) {
        const double shift = kTwoPi * std::floor((tip_phi - arc.entry_rad) / kTwoPi);
        if (tip_phi - shift <= arc.exit_rad) {
          add_element(sums, chip, tip_phi, section.top_mm - section.bottom_mm);
          return;
        }
      }
      return;
    }
    const double at_bottom = tip_phi - lag_rad_per_mm_ * section.bottom_mm;
    const double at_top = tip_phi - lag_rad_per_mm_ * section.top_mm;
    const double lo = std::min(at_bottom, at_top), hi = std::max(at_bottom, at_top);
    const double weight = 1.0 / std::abs(lag_rad_per_mm_);  // dz = dφ / |lag|
    for (const ImmersionArc& arc : section.arcs) {
      const int k_first = static_cast<int>(std::ceil((lo - arc.exit_rad) / kTwoPi));
      const int k_last = static_cast<int>(std::floor((hi - arc.entry_rad) / kTwoPi));
      for (int k = k_first; k <= k_last; ++k) {
        // The part of the arc the flute spans, on the arc's own turn.
        const double from = std::max(lo - k * kTwoPi, arc.entry_rad), to = std::min(hi - k * kTwoPi, arc.exit_rad);
        if (table != nullptr) {
          table->add_integral(sums, from, to, weight);
        } else {
          add_immersion_integral(sums, chip, from, to, weight);
        }
      }
    }
  }

  std::span<const EngagedSection> sections_;
  std::vector<ToothChip> teeth_;
  std::vector<ImmersionTable> tables_;  // per tooth with runout, one shared without; empty in closed form
  double pitch_rad_;
  double lag_rad_per_mm_;
};

ForceRegressors to_regressors(const ElementSums& s) {
  ForceRegressors r;
  r.rows[0] = {-s.a, -s.b, 0.0, -s.c, -s.s, 0.0};
  r.rows[1] = {s.b, -s.a, 0.0, s.s, -s.c, 0.0};
  r.rows[2] = {0.0, 0.0, s.h, 0.0, 0.0, s.l};
  return r;
}

MechanisticForce to_force(const ElementSums& sums, const std::array<double, 6>& k) {
  const ForceRegressors r = to_regressors(sums);
  MechanisticForce f;
  for (int i = 0; i < 6; ++i) {
    f.fx_n += r.rows[0][i] * k[i];
    f.fy_n += r.rows[1][i] * k[i];
    f.fz_n += r.rows[2][i] * k[i];
  }
  return f;
}

// |F_xy| at spindle angle Ω: to_force's F_x and F_y written out (forces are far from overflow).
double xy_force_n(const Kernel& kernel, const std::array<double, 6>& k, double spindle_angle_rad) {
  const ElementSums s = kernel.at(spindle_angle_rad);
  const double fx_n = -(k[kKtc] * s.a + k[kKrc] * s.b + k[kKte] * s.c + k[kKre] * s.s);
  const double fy_n = k[kKtc] * s.b - k[kKrc] * s.a + k[kKte] * s.s - k[kKre] * s.c;
  return std::sqrt(fx_n * fx_n + fy_n * fy_n);
}

// Golden-section search for the largest |F_xy| on [lo, hi], to kPeakAngleTolerance; `best` is the sample
// at `best_angle_rad` that bracketed it.
MechanisticPeak refined_peak(const Kernel& kernel, const std::array<double, 6>& k, double lo, double hi,
                             MechanisticPeak best) {
  constexpr double kInvPhi = 0.6180339887498949;
  double x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  double f1 = xy_force_n(kernel, k, x1), f2 = xy_force_n(kernel, k, x2);
  while (hi - lo > kPeakAngleToleranceRad) {
    if (f1 > f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - kInvPhi * (hi - lo);
      f1 = xy_force_n(kernel, k, x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + kInvPhi * (hi - lo);
      f2 = xy_force_n(kernel, k, x2);
    }
  }
  if (f1 > best.force_n) best = {f1, x1};
  if (f2 > best.force_n) best = {f2, x2};
  return best;
}

}  // namespace

std::array<double, 6> coefficients(const MechanisticModel& model) {
  return {model.ktc_n_per_mm2, model.krc_n_per_mm2, model.kac_n_per_mm2,
          model.kte_n_per_mm,  model.kre_n_per_mm,  model.kae_n_per_mm};
}

std::vector<InputProblem> validate(const MechanisticModel& model, const CutterGeometry& cutter,
                                   const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.add_all(validate(model, field_prefix));
  problems.positive("cutter.radius_mm", cutter.radius_mm);
  if (cutter.flutes < 1) problems.add_value("cutter.flutes", std::to_string(cutter.flutes), "must be ≥ 1");
  if (!(std::abs(cutter.helix_deg) < 90.0)) {
    problems.add_value("cutter.helix_deg", shortest_number_text(cutter.helix_deg), "must be in (−90, 90)");
  }
  if (!model.runout_mm.empty() && cutter.flutes >= 1 && model.runout_mm.size() != static_cast<std::size_t>(cutter.flutes)) {
    problems.add(field_prefix + "runout_mm", "has " + std::to_string(model.runout_mm.size()) +
                                                 " values: must be empty or one per flute (" +
                                                 std::to_string(cutter.flutes) + ")");
  }
  return problems.take();
}

ForceRegressors regressors(const MechanisticModel& model, std::span<const EngagedSection> sections,
                           const CutterGeometry& cutter, double feed_per_tooth_mm, double spindle_angle_rad) {
  return to_regressors(Kernel(model, sections, cutter, feed_per_tooth_mm).at(spindle_angle_rad));
}

std::vector<ForceRegressors> regressors_at_angles(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                                  const CutterGeometry& cutter, double feed_per_tooth_mm,
                                                  std::span<const double> spindle_angles_rad) {
  const Kernel kernel(model, sections, cutter, feed_per_tooth_mm);
  std::vector<ForceRegressors> out;
  out.reserve(spindle_angles_rad.size());
  for (const double angle : spindle_angles_rad) out.push_back(to_regressors(kernel.at(angle)));
  return out;
}

MechanisticForce predicted_force(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                 const CutterGeometry& cutter, double feed_per_tooth_mm, double spindle_angle_rad) {
  return to_force(Kernel(model, sections, cutter, feed_per_tooth_mm).at(spindle_angle_rad), coefficients(model));
}

MechanisticPeak predicted_peak(const MechanisticModel& model, std::span<const EngagedSection> sections,
                               const CutterGeometry& cutter, double feed_per_tooth_mm) {
  const Kernel kernel(model, sections, cutter, feed_per_tooth_mm);
  const std::array<double, 6> k = coefficients(model);
  const bool runout = kernel.has_runout();
  const int steps_per_period = runout ? kPeakStepsPerToothPeriodRunout : kPeakStepsPerToothPeriod;
  const int count = steps_per_period * (runout ? cutter.flutes : 1);
  const double step = kernel.pitch_rad() / steps_per_period;
  std::vector<double> force(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) force[i] = xy_force_n(kernel, k, i * step);
  // Local maxima of the periodic samples, largest first.
  std::vector<int> maxima;
  for (int i = 0; i < count; ++i) {
    const double before = force[(i + count - 1) % count], after = force[(i + 1) % count];
    if (force[i] >= before && force[i] >= after && force[i] > 0.0) maxima.push_back(i);
  }
  std::sort(maxima.begin(), maxima.end(), [&](int a, int b) { return force[a] > force[b]; });
  const std::size_t candidates =
      static_cast<std::size_t>(runout ? std::max(kPeakCandidates, cutter.flutes) : kPeakCandidates);
  const double ratio = runout ? kPeakCandidateRatioRunout : kPeakCandidateRatio;
  MechanisticPeak peak;
  for (std::size_t c = 0; c < maxima.size() && c < candidates; ++c) {
    const int i = maxima[c];
    if (force[i] < ratio * force[maxima.front()]) break;
    const MechanisticPeak refined = refined_peak(kernel, k, (i - 1) * step, (i + 1) * step, {force[i], i * step});
    if (refined.force_n > peak.force_n) peak = refined;
  }
  return peak;
}

double predicted_peak_force_n(const MechanisticModel& model, std::span<const EngagedSection> sections,
                              const CutterGeometry& cutter, double feed_per_tooth_mm) {
  return predicted_peak(model, sections, cutter, feed_per_tooth_mm).force_n;
}

MechanisticForce predicted_mean_force(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                      const CutterGeometry& cutter, double feed_per_tooth_mm) {
  return to_force(Kernel(model, sections, cutter, feed_per_tooth_mm).mean(), coefficients(model));
}

}  // namespace feedplan::model
