#pragma once
// The force model at one path sample, in both directions (docs/method.md §5.3): the feed limit that makes
// the model predict the target, and the force predicted at a given feed.
//
// The chip: t_m = k · f_xy with k the sample's chip factor and f_xy the feed per tooth in the XY plane,
// f_xy = (F / (Z · n)) · xy_speed_ratio for a path feed F (mm/min), Z flutes, n rpm — on a helix only the
// XY part of the feed makes the radial chip.
//
// Contact length below the fitted range: where the tool enters or leaves the material, L falls below the
// smallest L the model was fitted on, and a quadratic extrapolated there can predict anything (often more
// force at less contact). The planner evaluates the model at max(L, L_min) there: more contact than
// there is, so the force is over- rather than under-estimated, and the feed errs on the safe side. Above
// the fitted range the model is extrapolated as it is, and the sample is flagged.
//
// Axial depth: the model has no axial-depth term; it was fitted at a_p,model (ResponseSurfaceModel::
// axial_depth_mm). Forces scale with the axial depth in contact, so at a sample cut at a_p the planner
// uses F̂ · a_p / a_p,model (1 when either is unknown). Outside kAxialDepthRatioRange that scaling counts
// as an extrapolation.

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/move.hpp"
#include "feedplan/model/feed_solve.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/force_bound.hpp"

namespace feedplan::planner {

//! Ratios a_p / a_p,model inside which axial-depth scaling is not reported as an extrapolation.
inline constexpr double kAxialDepthRatioMin = 0.5;
inline constexpr double kAxialDepthRatioMax = 2.0;  //!< see kAxialDepthRatioMin

//! Below this chip factor or XY speed ratio a sample makes no chip the model can describe (a tooth
//! only touches behind the feed, or a plunge): its feed is not limited by the force.
inline constexpr double kMinChipFactor = 1e-6;

//! The machine-independent part of a sample's feed limit.
struct SampleFeedLimit {
  double feed_mm_per_min = 0.0;                 //!< the limit, mm/min (before the machine's range)
  FeedLimitReason reason = FeedLimitReason::kAirFeed;  //!< kForce, kModelRange or kAirFeed
  bool extrapolated = false;                    //!< L or a_p outside the fitted range where it binds
  bool target_below_model = false;              //!< F̂ exceeds the target even as the feed → 0
  model::FeedSolveStatus solve_status = model::FeedSolveStatus::kOk;  //!< of model::solve_feed
};

//! a_p / a_p,model for `axial_depth_mm`, or 1 when either depth is not positive.
double axial_depth_ratio(const model::ResponseSurfaceModel& model, double axial_depth_mm);

//! The feed (mm/min) at which `model` predicts `target_force_n` at `sample` (engaged, cutting), by
//! model::solve_feed on the chip factor × XY speed ratio, with the axial-depth scaling above. A sample
//! that is not engaged or makes no chip gets `air_feed_mm_per_min` with reason kAirFeed. A solution
//! clamped at the top of the fitted t_m range gets reason kModelRange (the feed the model still covers);
//! one below the range uses the rising root (F̂ = target, an extrapolation downwards, flagged).
//! With `uncertainty`, the feed is the largest one at or below that limit at which the upper bound
//! F̂ + z·σ (force_bound.hpp, same axial-depth scaling) meets the target, found by bisection (F̂ + z·σ
//! rises with the feed on the rising branch); when even a vanishing feed exceeds the target,
//! target_below_model is set.
SampleFeedLimit sample_feed_limit(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                                  double target_force_n, int flutes, double spindle_rpm, double air_feed_mm_per_min,
                                  const ForceUncertainty* uncertainty = nullptr);

//! F̂ + z·σ (× the chip-area ratio ρ when uncertainty->off_straight_cut) at `sample` and path feed
//! `feed_mm_per_min` (F̂ without `uncertainty`), with the axial-depth scaling; 0 when the sample is not engaged.
double upper_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                     double feed_mm_per_min, int flutes, double spindle_rpm, const ForceUncertainty* uncertainty);

//! F̂ (N) the model predicts at `sample` when the tool runs at path feed `feed_mm_per_min`, with the
//! axial-depth scaling; 0 when the sample is not engaged.
double predicted_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                         double feed_mm_per_min, int flutes, double spindle_rpm);

//! t_m (mm) at `sample` for path feed `feed_mm_per_min`.
double chip_thickness_mm(const geometry::EngagementSample& sample, double feed_mm_per_min, int flutes,
                         double spindle_rpm);

//! The contact length the model is evaluated at for a sample with contact length `contact_length_mm`:
//! max(L, range.contact_length_min_mm) (see the file comment), mm.
double model_contact_length_mm(const model::ResponseSurfaceModel& model, double contact_length_mm);

//! True when the sample is on a cutting move with some engagement (what the force model applies to).
bool is_engaged(const geometry::EngagementSample& sample);

}  // namespace feedplan::planner
