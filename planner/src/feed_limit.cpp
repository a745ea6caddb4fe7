#include "feedplan/planner/feed_limit.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/model/model_prediction.hpp"

namespace feedplan::planner {

bool is_engaged(const geometry::EngagementSample& sample) { return sample.cutting && sample.engagement_rad > 0.0; }

double axial_depth_ratio(const model::ResponseSurfaceModel& model, double axial_depth_mm) {
  if (model.axial_depth_mm <= 0.0 || axial_depth_mm <= 0.0) return 1.0;
  return axial_depth_mm / model.axial_depth_mm;
}

double model_contact_length_mm(const model::ResponseSurfaceModel& model, double contact_length_mm) {
  return std::max(contact_length_mm, model.range.contact_length_min_mm);
}

double chip_thickness_mm(const geometry::EngagementSample& sample, double feed_mm_per_min, int flutes,
                         double spindle_rpm) {
  const double feed_per_tooth_mm = feed_mm_per_min / (flutes * spindle_rpm);
  return sample.chip_factor * sample.xy_speed_ratio * feed_per_tooth_mm;
}

double predicted_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                         double feed_mm_per_min, int flutes, double spindle_rpm) {
  if (!is_engaged(sample)) return 0.0;
  const double chip_mm = chip_thickness_mm(sample, feed_mm_per_min, flutes, spindle_rpm);
  const double force_n = model::predict(model, chip_mm, model_contact_length_mm(model, sample.contact_length_mm)).force_n;
  return force_n * axial_depth_ratio(model, sample.axial_depth_mm);
}

double upper_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                     double feed_mm_per_min, int flutes, double spindle_rpm, const ForceUncertainty* uncertainty) {
  const double force_n = predicted_force_n(model, sample, feed_mm_per_min, flutes, spindle_rpm);
  if (!uncertainty || !is_engaged(sample)) return force_n;
  const double chip_mm = chip_thickness_mm(sample, feed_mm_per_min, flutes, spindle_rpm);
  const double sigma_n = force_standard_deviation_n(model, *uncertainty, chip_mm,
                                                    model_contact_length_mm(model, sample.contact_length_mm));
  const double bound_n = force_n + uncertainty->sigmas * sigma_n * axial_depth_ratio(model, sample.axial_depth_mm);
  return uncertainty->off_straight_cut ? std::max(sample.chip_area_ratio, 1.0) * bound_n : bound_n;
}

SampleFeedLimit sample_feed_limit(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                                  double target_force_n, int flutes, double spindle_rpm, double air_feed_mm_per_min,
                                  const ForceUncertainty* uncertainty) {
  SampleFeedLimit limit;
  limit.feed_mm_per_min = air_feed_mm_per_min;
  const double k = sample.chip_factor * sample.xy_speed_ratio;
  if (!is_engaged(sample) || k < kMinChipFactor) return limit;

  const double ratio = axial_depth_ratio(model, sample.axial_depth_mm);
  // F̂ · ratio = target  ⇔  F̂ = target / ratio.
  const model::FeedSolution solution =
      model::solve_feed(model, std::min(k, 1.0), model_contact_length_mm(model, sample.contact_length_mm),
                           target_force_n / ratio);
  limit.solve_status = solution.status;
  // solve_feed's feed per tooth is along the path: its chip factor already holds the XY speed ratio.
  double feed_per_tooth_mm = solution.feed_per_tooth_mm;
  limit.reason = FeedLimitReason::kForce;
  switch (solution.status) {
    case model::FeedSolveStatus::kOk:
      break;
    case model::FeedSolveStatus::kClampedToRange:
      if (solution.root_feed_per_tooth_mm && *solution.root_feed_per_tooth_mm < solution.feed_per_tooth_mm) {
        // Below the fitted chip range: the root still gives F̂ = target (flagged as extrapolation); the
        // range edge would overload.
        feed_per_tooth_mm = *solution.root_feed_per_tooth_mm;
        limit.extrapolated = true;
      } else {
        limit.reason = FeedLimitReason::kModelRange;
      }
      break;
    case model::FeedSolveStatus::kTargetBelowModel:
      // No feed meets the target: the caller plans the machine's minimum feed here and reports it.
      limit.target_below_model = true;
      feed_per_tooth_mm = 0.0;
      break;
    case model::FeedSolveStatus::kUnreachable:
      limit.reason = FeedLimitReason::kModelRange;
      break;
  }
  if (solution.contact_length_outside) limit.extrapolated = true;
  if (ratio < kAxialDepthRatioMin || ratio > kAxialDepthRatioMax) limit.extrapolated = true;
  limit.feed_mm_per_min = feed_per_tooth_mm * flutes * spindle_rpm;
  if (uncertainty && !limit.target_below_model) {
    // The bound rises with the feed: bisect on [0, plain limit] for the largest feed it allows.
    const auto bound = [&](double feed) { return upper_force_n(model, sample, feed, flutes, spindle_rpm, uncertainty); };
    if (bound(limit.feed_mm_per_min) > target_force_n) {
      double lo = 0.0;
      double hi = limit.feed_mm_per_min;
      if (bound(1e-9 * hi) > target_force_n) {
        limit.target_below_model = true;
        limit.feed_mm_per_min = 0.0;
      } else {
        for (int i = 0; i < 60 && hi - lo > 1e-9 * limit.feed_mm_per_min; ++i) {
          const double mid = 0.5 * (lo + hi);
          (bound(mid) > target_force_n ? hi : lo) = mid;
        }
        limit.feed_mm_per_min = lo;
        limit.reason = FeedLimitReason::kForce;
      }
    }
  }
  return limit;
}

}  // namespace feedplan::planner
