#include "feedplan/planner/feed_limit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/chip_load.hpp"
#include "feedplan/model/model_prediction.hpp"

namespace feedplan::planner {

namespace {

// One way of carrying the straight-cut model over to a sample (feed_limit.hpp): the contact length F̂ is
// evaluated at and the factor applied to it; ratio 0 means the way does not apply.
struct Transfer {
  double contact_length_mm = 0.0;
  double ratio = 0.0;
};

std::array<Transfer, 2> transfers(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                                  double load_ratio) {
  const auto& range = model.range;
  const double clamped_mm = std::min(model_contact_length_mm(model, sample.contact_length_mm),
                                     std::max(range.contact_length_max_mm, range.contact_length_min_mm));
  return {Transfer{model_contact_length_mm(model, sample.contact_length_mm), axial_depth_ratio(model, sample.axial_depth_mm)},
          Transfer{clamped_mm, load_ratio}};
}

// The solved feed per tooth for one transfer, with what the solve said.
struct TransferSolution {
  double feed_per_tooth_mm = 0.0;
  FeedLimitReason reason = FeedLimitReason::kForce;
  bool extrapolated = false;
  bool target_below_model = false;
  model::FeedSolveStatus status = model::FeedSolveStatus::kOk;
};

TransferSolution solve_transfer(const model::ResponseSurfaceModel& model, double k, const Transfer& transfer,
                                double target_force_n) {
  TransferSolution out;
  // F̂ · ratio = target  ⇔  F̂ = target / ratio.
  const model::FeedSolution solution =
      model::solve_feed(model, std::min(k, 1.0), transfer.contact_length_mm, target_force_n / transfer.ratio);
  out.status = solution.status;
  // solve_feed's feed per tooth is along the path: its chip factor already holds the XY speed ratio.
  out.feed_per_tooth_mm = solution.feed_per_tooth_mm;
  switch (solution.status) {
    case model::FeedSolveStatus::kOk:
      break;
    case model::FeedSolveStatus::kClampedToRange:
      if (solution.root_feed_per_tooth_mm && *solution.root_feed_per_tooth_mm < solution.feed_per_tooth_mm) {
        // Below the fitted chip range: the root still gives F̂ = target (flagged as extrapolation); the
        // range edge would overload.
        out.feed_per_tooth_mm = *solution.root_feed_per_tooth_mm;
        out.extrapolated = true;
      } else {
        out.reason = FeedLimitReason::kModelRange;
      }
      break;
    case model::FeedSolveStatus::kTargetBelowModel:
      // No feed meets the target: the caller plans the machine's minimum feed here and reports it.
      out.target_below_model = true;
      out.feed_per_tooth_mm = 0.0;
      break;
    case model::FeedSolveStatus::kUnreachable:
      out.reason = FeedLimitReason::kModelRange;
      break;
  }
  if (solution.contact_length_outside) out.extrapolated = true;
  return out;
}

// The largest feed at or below `limit` at which the upper bound meets the target (bisection; the bound
// rises with the feed on the rising branch).
void hold_upper_bound(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                      double load_ratio, double target_force_n, int flutes, double spindle_rpm,
                      const ForceUncertainty* uncertainty, SampleFeedLimit& limit) {
  const auto bound = [&](double feed) {
    return upper_force_n(model, sample, load_ratio, feed, flutes, spindle_rpm, uncertainty);
  };
  if (bound(limit.feed_mm_per_min) <= target_force_n) return;
  double lo = 0.0;
  double hi = limit.feed_mm_per_min;
  if (bound(1e-9 * hi) > target_force_n) {
    limit.target_below_model = true;
    limit.feed_mm_per_min = 0.0;
    return;
  }
  for (int i = 0; i < 60 && hi - lo > 1e-9 * limit.feed_mm_per_min; ++i) {
    const double mid = 0.5 * (lo + hi);
    (bound(mid) > target_force_n ? hi : lo) = mid;
  }
  limit.feed_mm_per_min = lo;
  limit.reason = FeedLimitReason::kForce;
}

}  // namespace

bool is_engaged(const geometry::EngagementSample& sample) { return sample.engagement_rad > 0.0; }

bool meets_material(const geometry::EngagementSample& sample) {
  return is_engaged(sample) || sample.end_face_in_material;
}

double axial_depth_ratio(const model::ResponseSurfaceModel& model, double axial_depth_mm) {
  if (model.axial_depth_mm <= 0.0 || axial_depth_mm <= 0.0) return 1.0;
  return axial_depth_mm / model.axial_depth_mm;
}

double model_contact_length_mm(const model::ResponseSurfaceModel& model, double contact_length_mm) {
  return std::max(contact_length_mm, model.range.contact_length_min_mm);
}

double chip_load_ratio(const model::ResponseSurfaceModel& model, const geometry::EngagementProfile& profile,
                       const geometry::EngagementSample& sample, const geometry::Tool& tool) {
  if (!is_engaged(sample) || sample.chip_factor < kMinChipFactor || sample.layer_count == 0) return 0.0;
  geometry::StraightCutLoads straight_cuts(tool);
  return chip_load_ratio(model, sample, geometry::peak_chip_load_mm(profile, sample, tool), straight_cuts);
}

double chip_load_ratio(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                       double load_mm, geometry::StraightCutLoads& straight_cuts) {
  const double k = sample.chip_factor;
  if (!is_engaged(sample) || k < kMinChipFactor || sample.layer_count == 0) return 0.0;
  const auto& range = model.range;
  const double clamped_mm = std::min(model_contact_length_mm(model, sample.contact_length_mm),
                                     std::max(range.contact_length_max_mm, range.contact_length_min_mm));
  const double reference_rad = clamped_mm / straight_cuts.tool().radius_mm();
  const double reference_depth_mm = model.axial_depth_mm > 0.0 ? model.axial_depth_mm : sample.material_height_mm;
  // The straight cut with the same t_m: f_z' = t_m / sin(min(α', π/2)), so per unit f_z of the sample its
  // load is C_ref · k / sin(min(α', π/2)).
  const double reference_mm =
      straight_cuts.peak_mm(reference_rad, reference_depth_mm) * k / std::sin(std::min(reference_rad, 0.5 * kPi));
  if (!(reference_mm > 0.0) || !std::isfinite(reference_mm)) return 0.0;
  return load_mm / reference_mm;
}

double plunge_feed_limit_mm_per_min(const geometry::Move& move, const geometry::Tool& tool, double spindle_rpm,
                                    double resolution_mm) {
  const double length_mm = geometry::length_mm(move);
  const double descent_mm = move.start.z_mm - move.end.z_mm;
  if (!(descent_mm > 0.0) || !(length_mm > 0.0)) return std::numeric_limits<double>::infinity();
  return tool.plunge_feed_per_tooth_mm() * tool.flutes * spindle_rpm * length_mm /
         (descent_mm + std::max(resolution_mm, 0.0));
}

double chip_thickness_mm(const geometry::EngagementSample& sample, double feed_mm_per_min, int flutes,
                         double spindle_rpm) {
  const double feed_per_tooth_mm = feed_mm_per_min / (flutes * spindle_rpm);
  return sample.chip_factor * sample.xy_speed_ratio * feed_per_tooth_mm;
}

double predicted_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                         double load_ratio, double feed_mm_per_min, int flutes, double spindle_rpm) {
  if (!is_engaged(sample)) return 0.0;
  const double chip_mm = chip_thickness_mm(sample, feed_mm_per_min, flutes, spindle_rpm);
  double force_n = 0.0;
  for (const Transfer& t : transfers(model, sample, load_ratio)) {
    if (t.ratio > 0.0) force_n = std::max(force_n, model::predict(model, chip_mm, t.contact_length_mm).force_n * t.ratio);
  }
  return force_n;
}

double force_transfer_factor(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                             double load_ratio, double feed_mm_per_min, int flutes, double spindle_rpm) {
  const double linear = axial_depth_ratio(model, sample.axial_depth_mm);
  if (!is_engaged(sample)) return linear;
  const double chip_mm = chip_thickness_mm(sample, feed_mm_per_min, flutes, spindle_rpm);
  const double straight_n = model::predict(model, chip_mm, model_contact_length_mm(model, sample.contact_length_mm)).force_n;
  const double transferred_n = predicted_force_n(model, sample, load_ratio, feed_mm_per_min, flutes, spindle_rpm);
  if (!(straight_n > 0.0) || !(transferred_n > 0.0)) return linear;
  return transferred_n / straight_n;
}

double upper_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                     double load_ratio, double feed_mm_per_min, int flutes, double spindle_rpm,
                     const ForceUncertainty* uncertainty) {
  if (!uncertainty || !is_engaged(sample)) {
    return predicted_force_n(model, sample, load_ratio, feed_mm_per_min, flutes, spindle_rpm);
  }
  const double chip_mm = chip_thickness_mm(sample, feed_mm_per_min, flutes, spindle_rpm);
  double bound_n = 0.0;
  for (const Transfer& t : transfers(model, sample, load_ratio)) {
    if (!(t.ratio > 0.0)) continue;
    const double force_n = model::predict(model, chip_mm, t.contact_length_mm).force_n;
    const double sigma_n = force_standard_deviation_n(model, *uncertainty, chip_mm, t.contact_length_mm);
    bound_n = std::max(bound_n, (force_n + uncertainty->sigmas * sigma_n) * t.ratio);
  }
  return uncertainty->off_straight_cut ? std::max(sample.chip_area_ratio, 1.0) * bound_n : bound_n;
}

SampleFeedLimit sample_feed_limit(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                                  double load_ratio, double target_force_n, int flutes, double spindle_rpm,
                                  double air_feed_mm_per_min, const ForceUncertainty* uncertainty) {
  SampleFeedLimit limit;
  limit.feed_mm_per_min = air_feed_mm_per_min;
  const double k = sample.chip_factor * sample.xy_speed_ratio;
  if (!is_engaged(sample) || k < kMinChipFactor) return limit;

  // The transfer that allows the smaller feed binds.
  TransferSolution binding;
  binding.feed_per_tooth_mm = std::numeric_limits<double>::infinity();
  for (const Transfer& t : transfers(model, sample, load_ratio)) {
    if (!(t.ratio > 0.0)) continue;
    const TransferSolution solution = solve_transfer(model, k, t, target_force_n);
    if (solution.feed_per_tooth_mm < binding.feed_per_tooth_mm || solution.target_below_model) binding = solution;
    if (binding.target_below_model) break;
  }
  limit.solve_status = binding.status;
  limit.reason = binding.reason;
  limit.target_below_model = binding.target_below_model;
  const double ratio = axial_depth_ratio(model, sample.axial_depth_mm);
  limit.extrapolated = binding.extrapolated || ratio < kAxialDepthRatioMin || ratio > kAxialDepthRatioMax ||
                       model::contact_length_outside(model.range, model_contact_length_mm(model, sample.contact_length_mm));
  limit.feed_mm_per_min = binding.feed_per_tooth_mm * flutes * spindle_rpm;
  if (uncertainty && !limit.target_below_model) {
    hold_upper_bound(model, sample, load_ratio, target_force_n, flutes, spindle_rpm, uncertainty, limit);
  }
  return limit;
}

}  // namespace feedplan::planner
