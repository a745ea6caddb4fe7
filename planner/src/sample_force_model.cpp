#include "feedplan/planner/sample_force_model.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/geometry/chip_load.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/planner/engaged_sections.hpp"
#include "feedplan/planner/tooth_chord.hpp"

namespace feedplan::planner {
namespace {

// The smallest feed the solve looks at, relative to the largest: the edge forces alone.
constexpr double kVanishingFeedRatio = 1e-6;
// The secant step from the previous sample's solution moves the feed by at most this ratio.
constexpr double kSecantStepRatio = 1.5;
// The top of the bracket when the caller sets no air feed (the safety check asks for the force's own limit).
constexpr double kLargestSolveFeedMmPerMin = 1e6;

double feed_per_tooth_mm(const geometry::EngagementSample& sample, double feed_mm_per_min, int flutes, double rpm) {
  return feed_mm_per_min / (flutes * rpm) * sample.xy_speed_ratio;
}

//! The kernel's peak at `sample` for the XY feed per tooth `feed_per_tooth_mm`, read along the chord of the last
//! tooth period (tooth_chord.hpp): `sections` turned into its frame, its length the feed per tooth.
double chord_peak_n(const model::MechanisticModel& model, SampleSections& sections, const model::CutterGeometry& cutter,
                    const geometry::EngagementProfile& profile, const geometry::EngagementSample& sample,
                    double feed_per_tooth_mm) {
  const ToothChord chord = tooth_chord(profile, sample, feed_per_tooth_mm / sample.xy_speed_ratio);
  sections.turn(chord.angle_rad);
  return model::predicted_peak_force_n(model, sections.sections(), cutter, chord.length_mm);
}

double bound_factor(const ForceUncertainty* uncertainty) {
  return uncertainty ? 1.0 + uncertainty->sigmas * uncertainty->relative : 1.0;
}

}  // namespace

SampleForceModel::SampleForceModel(const model::ResponseSurfaceModel& surface, const model::MechanisticModel* mechanistic,
                                   const geometry::EngagementProfile& profile, const geometry::Tool& tool,
                                   std::shared_ptr<geometry::StraightCutLoads> straight_cuts)
    : straight_cuts_(straight_cuts ? std::move(straight_cuts) : std::make_shared<geometry::StraightCutLoads>(tool)), surface_(surface), mechanistic_(mechanistic), profile_(profile), tool_(tool) {}

double SampleForceModel::load_ratio(const geometry::EngagementSample& sample) const {
  if (mechanistic_ || !is_engaged(sample) || sample.layer_count == 0) return 0.0;
  return load_ratio(sample, geometry::peak_chip_load_mm(profile_, sample, tool_));
}

double SampleForceModel::load_ratio(const geometry::EngagementSample& sample, double peak_chip_load_mm) const {
  return mechanistic_ ? 0.0 : chip_load_ratio(surface_, sample, peak_chip_load_mm, *straight_cuts_);
}

double SampleForceModel::kernel_peak_n(const geometry::EngagementSample& sample, double feed_per_tooth_mm) const {
  if (!is_engaged(sample) || !(feed_per_tooth_mm > 0.0)) return 0.0;
  SampleSections sections(profile_, sample);
  if (sections.sections().empty()) return 0.0;
  return chord_peak_n(*mechanistic_, sections, cutter_geometry(tool_), profile_, sample, feed_per_tooth_mm);
}

SampleFeedLimit SampleForceModel::finish_kernel_limit(SampleFeedLimit limit, const geometry::EngagementSample& sample,
                                                      double feed_mm_per_min, int flutes, double spindle_rpm) const {
  limit.feed_mm_per_min = feed_mm_per_min;
  last_solution_mm_per_min_ = feed_mm_per_min;  // the slope stays the one the secant step used
  const double chip_mm = chip_thickness_mm(sample, feed_mm_per_min, flutes, spindle_rpm);
  limit.extrapolated = model::chip_outside(surface_.range, chip_mm) && chip_mm > surface_.range.chip_max_mm;
  return limit;
}

SampleFeedLimit SampleForceModel::kernel_feed_limit(const geometry::EngagementSample& sample, double target_force_n,
                                                    int flutes, double spindle_rpm, double air_feed_mm_per_min,
                                                    double bound) const {
  SampleFeedLimit limit;
  limit.feed_mm_per_min = air_feed_mm_per_min;
  if (!is_engaged(sample) || sample.xy_speed_ratio < kMinChipFactor) return limit;
  SampleSections sections(profile_, sample);
  if (sections.sections().empty()) return limit;
  const model::CutterGeometry cutter = cutter_geometry(tool_);
  const auto peak_at = [&](double feed_mm_per_min) {
    return bound * chord_peak_n(*mechanistic_, sections, cutter, profile_, sample,
                                feed_per_tooth_mm(sample, feed_mm_per_min, flutes, spindle_rpm));
  };
  limit.reason = FeedLimitReason::kForce;
  const double top = std::isfinite(air_feed_mm_per_min) ? air_feed_mm_per_min : kLargestSolveFeedMmPerMin;
  const double bottom = kVanishingFeedRatio * top;
  const double close_n = kMechanisticForceTolerance * target_force_n;
  double lo = bottom, hi = top, f_lo = 0.0, f_hi = 0.0;
  // Neighbouring samples have nearly the same solution and slope: a secant step from the last solution with
  // the last slope usually lands within the tolerance at once (one or two evaluations); its two points
  // bracket the solution or say on which side of them it lies.
  bool bracketed = false;
  if (last_solution_mm_per_min_ > bottom && last_solution_mm_per_min_ < top && last_slope_n_per_mm_per_min_ > 0.0) {
    const double f0 = last_solution_mm_per_min_, e0 = peak_at(f0) - target_force_n;
    if (e0 <= 0.0 && e0 > -close_n) return finish_kernel_limit(limit, sample, f0, flutes, spindle_rpm);
    const double aim = f0 - (e0 + 0.5 * close_n) / last_slope_n_per_mm_per_min_;
    const double f1 = std::clamp(aim, std::max(bottom, f0 / kSecantStepRatio), std::min(top, f0 * kSecantStepRatio));
    const double e1 = peak_at(f1) - target_force_n;
    if (e1 <= 0.0 && e1 > -close_n) return finish_kernel_limit(limit, sample, f1, flutes, spindle_rpm);
    lo = std::min(f0, f1), hi = std::max(f0, f1);
    f_lo = f0 < f1 ? e0 : e1, f_hi = f0 < f1 ? e1 : e0;
    bracketed = f_lo < 0.0 && f_hi > 0.0;
    if (!bracketed && f_hi < 0.0) {  // both below the target: from the higher to the air feed
      lo = hi;
      f_lo = f_hi;
      hi = top;
      f_hi = peak_at(hi) - target_force_n;
      bracketed = true;
    } else if (!bracketed && f_lo > 0.0) {  // both above: from the vanishing feed to the lower
      hi = lo;
      f_hi = f_lo;
      lo = bottom;
      f_lo = peak_at(lo) - target_force_n;
      bracketed = true;
    }
  }
  if (!bracketed) {
    lo = bottom, hi = top;
    f_lo = peak_at(lo) - target_force_n;
    f_hi = peak_at(hi) - target_force_n;
  }
  last_solution_mm_per_min_ = 0.0;
  last_slope_n_per_mm_per_min_ = 0.0;
  if (f_lo >= 0.0) {
    limit.target_below_model = true;
    limit.solve_status = model::FeedSolveStatus::kTargetBelowModel;
    limit.feed_mm_per_min = lo;
    return limit;
  }
  if (f_hi <= 0.0) {
    limit.feed_mm_per_min = hi;  // the target is not reached below the air feed: the machine's range decides
  } else {
    // Illinois regula falsi: the peak is nearly affine in the feed (cutting terms ∝ f, edge terms constant).
    int side = 0;
    for (int evaluation = 2; evaluation < kMechanisticSolveEvaluations && hi - lo > kMechanisticFeedTolerance * hi;
         ++evaluation) {
      double next = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      const double f_next = peak_at(next) - target_force_n;
      if (f_next > 0.0) {
        hi = next;
        f_hi = f_next;
        if (side == -1) f_lo *= 0.5;
        side = -1;
      } else {
        lo = next;
        f_lo = f_next;
        if (f_next > -kMechanisticForceTolerance * target_force_n) break;  // at the target, from below
        if (side == +1) f_hi *= 0.5;
        side = +1;
      }
    }
    limit.feed_mm_per_min = lo;  // at or below the target
    last_solution_mm_per_min_ = lo;
    last_slope_n_per_mm_per_min_ = hi > lo ? (f_hi - f_lo) / (hi - lo) : 0.0;
  }
  const double chip_mm = chip_thickness_mm(sample, limit.feed_mm_per_min, flutes, spindle_rpm);
  limit.extrapolated = model::chip_outside(surface_.range, chip_mm) && chip_mm > surface_.range.chip_max_mm;
  return limit;
}

SampleFeedLimit SampleForceModel::feed_limit(const geometry::EngagementSample& sample, double load_ratio,
                                             double target_force_n, int flutes, double spindle_rpm,
                                             double air_feed_mm_per_min, const ForceUncertainty* uncertainty) const {
  if (!mechanistic_) {
    return sample_feed_limit(surface_, sample, load_ratio, target_force_n, flutes, spindle_rpm, air_feed_mm_per_min,
                             uncertainty);
  }
  return kernel_feed_limit(sample, target_force_n, flutes, spindle_rpm, air_feed_mm_per_min, bound_factor(uncertainty));
}

double SampleForceModel::predicted_force_n(const geometry::EngagementSample& sample, double load_ratio,
                                           double feed_mm_per_min, int flutes, double spindle_rpm) const {
  if (!mechanistic_) return planner::predicted_force_n(surface_, sample, load_ratio, feed_mm_per_min, flutes, spindle_rpm);
  return kernel_peak_n(sample, feed_per_tooth_mm(sample, feed_mm_per_min, flutes, spindle_rpm));
}

double SampleForceModel::upper_force_n(const geometry::EngagementSample& sample, double load_ratio,
                                       double feed_mm_per_min, int flutes, double spindle_rpm,
                                       const ForceUncertainty* uncertainty) const {
  if (!mechanistic_) {
    return planner::upper_force_n(surface_, sample, load_ratio, feed_mm_per_min, flutes, spindle_rpm, uncertainty);
  }
  return bound_factor(uncertainty) * predicted_force_n(sample, load_ratio, feed_mm_per_min, flutes, spindle_rpm);
}

double SampleForceModel::transfer_factor(const geometry::EngagementSample& sample, double load_ratio,
                                         double feed_mm_per_min, int flutes, double spindle_rpm) const {
  if (!mechanistic_) return force_transfer_factor(surface_, sample, load_ratio, feed_mm_per_min, flutes, spindle_rpm);
  return 1.0;
}

}  // namespace feedplan::planner
