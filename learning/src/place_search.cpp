#include "place_search.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning::detail {

double PlaceModel::force_n(double chip_mm) const {
  return transfer_factor * model::predict(*model, chip_mm, contact_length_mm).force_n;
}

double PlaceModel::force_exponent(double chip_mm) const {
  constexpr double kStep = 1.1;
  const double at = force_n(chip_mm);
  const double above = force_n(chip_mm * kStep);
  return at > 0.0 && above > 0.0 ? std::log(above / at) / std::log(kStep) : 0.0;
}

double PlaceModel::correction_at(double chip_mm, double target_force_n) const {
  const double predicted = force_n(chip_mm);
  return predicted > 0.0 ? target_force_n / predicted : 0.0;
}

PlaceBracket bracket_with(const PlaceBracket& bracket, const PathMeasurement& now, double target_force_n) {
  PlaceBracket out = bracket;
  if (!(now.force_n > 0.0) || !(now.chip_mm > 0.0)) return out;
  if (now.force_n <= target_force_n) {
    if (!out.has_below() || now.chip_mm >= out.below_chip_mm) {
      out.below_chip_mm = now.chip_mm;
      out.below_force_n = now.force_n;
    }
    if (out.has_above() && out.above_chip_mm <= now.chip_mm) out.above_chip_mm = out.above_force_n = 0.0;
  } else {
    if (!out.has_above() || now.chip_mm <= out.above_chip_mm) {
      out.above_chip_mm = now.chip_mm;
      out.above_force_n = now.force_n;
    }
    if (out.has_below() && out.below_chip_mm >= now.chip_mm) out.below_chip_mm = out.below_force_n = 0.0;
  }
  return out;
}

namespace {

// The chip at which a force through two measurements (t_a, F_a) and (t_b, F_b) meets the target, on the
// more cautious of two secants: the thinner of the roots of F = α + β ln t_m and of F = K t_m^q; 0 when the
// force does not rise with the chip. A cutting force F = α + β t_m^p (an edge force α ≥ 0, a size effect
// 1 − p) is convex in ln t_m, and so is ln F (its slope in ln t_m, p (1 − α / F), grows with F). Between the
// two measurements (a bracket) both curves lie on or above the force, the line in ln t_m the higher of them,
// so its root lands at or under the target — close to it where the force is flat (family-09's trochoid
// fronts: 529, 445 and 365 N at t_m 0.022, 0.011 and 0.006 mm, on a line in ln t_m), where a secant in t_m
// overshoots the root. Beyond them (both over the target, or both under) the force lies on or above both,
// the power law the higher: a line in ln t_m through two readings over the target left family-12's trochoid
// +3.5 % over it in cycle 3 where the power law took it within 3 % (the loop's largest held error over the
// family's eleven machines and six noise draws, summed: 282 → 264 %, its largest revolution over the
// target 213 → 199 %); the power law between the ends of a bracket ran the corner's fronts up to +5.7 %
// over the target where the line held them within 3.6 % (family-04 and -10).
double secant_chip_mm(double chip_a_mm, double force_a_n, double chip_b_mm, double force_b_n, double target_force_n) {
  if (!(chip_a_mm > 0.0) || !(chip_b_mm > 0.0) || chip_a_mm == chip_b_mm) return 0.0;
  const double ln_chip_ratio = std::log(chip_b_mm / chip_a_mm);
  const double slope = (force_b_n - force_a_n) / ln_chip_ratio;
  if (!(slope > 0.0)) return 0.0;
  const double on_line_mm = chip_a_mm * std::exp((target_force_n - force_a_n) / slope);
  if (!(force_a_n > 0.0) || !(force_b_n > 0.0)) return on_line_mm;
  const double exponent = std::log(force_b_n / force_a_n) / ln_chip_ratio;
  const double on_power_law_mm = chip_a_mm * std::pow(target_force_n / force_a_n, 1.0 / exponent);
  return std::min(on_line_mm, on_power_law_mm);
}

// `c` kept within the reach of the measured chip `now_mm` in the t_m it runs (c falls as t_m grows): no
// thicker than kSecantReach × (a step from one measurement far under the target, a cautious first cut,
// extrapolates the model's shape no further than a secant may), no thinner than 1 / kSlowingReach ×.
double within_reach(const PlaceModel& place, double target_force_n, double c, double now_mm) {
  const double at_thickest = place.correction_at(now_mm * kSecantReach, target_force_n);
  const double at_thinnest = place.correction_at(now_mm / kSlowingReach, target_force_n);
  if (!(at_thickest > 0.0 && at_thickest < at_thinnest)) return c;  // a model not rising there: no reach in t_m
  return std::clamp(c, at_thickest, at_thinnest);
}

// The largest c a first step from `now`, measured over the target, may take: the chip a force rising with
// exponent kMinFirstSlowingExponent would meet the target at (see kMinFirstSlowingExponent); no bound where
// the model does not rise between that chip and the one measured (no chip to aim at).
double largest_first_slowing_correction(const PlaceModel& place, double target_force_n, const PathMeasurement& now) {
  const double chip_mm = now.chip_mm * std::pow(target_force_n / now.force_n, 1.0 / kMinFirstSlowingExponent);
  const double c = place.correction_at(chip_mm, target_force_n);
  const double at_now = place.correction_at(now.chip_mm, target_force_n);
  return c > at_now && at_now > 0.0 ? c : kMaxPathCorrection;
}

// The next c with the bracket open on one side: a secant through two spread measurements, or the model's
// shape scaled to this one (c = F / F̂(t_m)), within kSecantReach of the measured chip — and, the first time a
// place reads over the target, slowed no further than kMinFirstSlowingExponent allows.
double one_sided_correction(const PlaceModel& place, double target_force_n, const PathMeasurement& now,
                            const PathMeasurement& before, double noise_n) {
  const double ratio = within_reach(place, target_force_n, now.force_n / place.force_n(now.chip_mm), now.chip_mm);
  if (!(before.force_n > 0.0) || !(before.chip_mm > 0.0)) {
    return now.force_n > target_force_n ? std::min(ratio, largest_first_slowing_correction(place, target_force_n, now))
                                        : ratio;
  }
  const double spread = std::abs(now.chip_mm - before.chip_mm);
  if (spread < kMinSecantSpread * std::max(now.chip_mm, before.chip_mm)) return ratio;
  const double min_change_n = std::max(kMinSecantForceChange * target_force_n, kSecantNoiseSigmas * noise_n);
  if (std::abs(now.force_n - before.force_n) < min_change_n) return ratio;
  const double chip_mm = secant_chip_mm(before.chip_mm, before.force_n, now.chip_mm, now.force_n, target_force_n);
  if (!(chip_mm > 0.0)) return ratio;
  const double lo = std::min(now.chip_mm, before.chip_mm) / kSlowingReach;
  const double hi = std::max(now.chip_mm, before.chip_mm) * kSecantReach;
  double c = place.correction_at(std::clamp(chip_mm, lo, hi), target_force_n);
  if (!(c > 0.0)) return ratio;
  // Within the trust region: a secant may ask the model for at most kSecantTrust times the log-step the
  // measured excess asks (ln(F / target)), so one reading off at one of its ends cannot send the place far.
  const double at_now = place.correction_at(now.chip_mm, target_force_n);
  if (at_now > 0.0) {
    const double asked = kSecantTrust * std::log(now.force_n / target_force_n);
    const double step = std::log(c / at_now);
    if ((asked > 0.0 && step > asked) || (asked < 0.0 && step < asked)) c = at_now * std::exp(asked);
  }
  return c;
}

}  // namespace

double largest_correction_not_slower(const PlaceModel& place, double target_force_n, const PlaceBracket& bracket) {
  if (!bracket.has_below()) return kMaxPathCorrection;
  const double c = place.correction_at(bracket.below_chip_mm, target_force_n);
  return c > 0.0 ? c : kMaxPathCorrection;
}

double chip_at_correction_mm(const PlaceModel& place, double target_force_n, double c, double lo_mm, double hi_mm) {
  const double c_thin = place.correction_at(lo_mm, target_force_n);
  const double c_thick = place.correction_at(hi_mm, target_force_n);
  if (!(c_thick > 0.0 && c_thick < c_thin)) return 0.0;  // no chip to aim at
  if (c >= c_thin) return lo_mm;
  if (c <= c_thick) return hi_mm;
  double lo = std::log(lo_mm), hi = std::log(hi_mm);
  for (int k = 0; k < 40; ++k) {  // c falls as t_m grows (within the reach, checked at its ends)
    const double mid = 0.5 * (lo + hi);
    if (place.correction_at(std::exp(mid), target_force_n) > c) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return std::exp(0.5 * (lo + hi));
}

double smallest_correction_not_past_proportional(const PlaceModel& place, double target_force_n,
                                                 const PlaceBracket& bracket) {
  if (!bracket.has_below() || !(bracket.below_force_n > 0.0)) return kMinPathCorrection;
  const double chip_mm = bracket.below_chip_mm * std::max(target_force_n / bracket.below_force_n, 1.0);
  const double c = place.correction_at(chip_mm, target_force_n);
  return c > 0.0 ? c : kMinPathCorrection;
}

double next_place_correction(const PlaceModel& place, double target_force_n, const PathMeasurement& now,
                             const PathMeasurement& before, const PlaceBracket& bracket, double previous,
                             double noise_n) {
  if (!(place.force_n(now.chip_mm) > 0.0)) return previous;
  double c = 0.0;
  if (std::abs(now.force_n - target_force_n) <= kHoldBand * target_force_n) {
    c = place.correction_at(now.chip_mm, target_force_n);
  } else if (bracket.has_below() && bracket.has_above()) {
    c = place.correction_at(secant_chip_mm(bracket.below_chip_mm, bracket.below_force_n, bracket.above_chip_mm,
                                           bracket.above_force_n, target_force_n),
                            target_force_n);
  } else {
    c = one_sided_correction(place, target_force_n, now, before, noise_n);
  }
  if (!(c > 0.0)) c = now.force_n / place.force_n(now.chip_mm);
  // Never past an end of the bracket: c falls as the t_m it runs grows.
  if (bracket.has_below()) {
    c = std::min(c, largest_correction_not_slower(place, target_force_n, bracket));
    // … and, where the model's force is nearly flat in the chip, faster than it only as far as a force
    // proportional to the chip would allow, unless the bracket is closed above (a secant between the two
    // ends lands at or under the target). A model flat in the chip gives no chip to aim at.
    const double exponent = place.force_exponent(bracket.below_chip_mm);
    if (!bracket.has_above() && exponent > 0.0 && exponent < kMinTrustedForceExponent) {
      c = std::max(c, smallest_correction_not_past_proportional(place, target_force_n, bracket));
    }
  }
  if (bracket.has_above()) {
    const double at_above = place.correction_at(bracket.above_chip_mm, target_force_n);
    if (at_above > 0.0) c = std::max(c, at_above);
  }
  return std::clamp(c, kMinPathCorrection, kMaxPathCorrection);
}

}  // namespace feedplan::learning::detail
