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
// axial_depth_mm). Forces scale with the axial depth in contact, so at a sample cut at a_p (the height of
// material in contact above the tip, on every layer: geometry/engagement.hpp) the planner uses
// F̂(t_m, max(L, L_min)) · a_p / a_p,model (1 when either is unknown). Outside kAxialDepthRatioRange that
// scaling counts as an extrapolation.
//
// Engagements a straight cut does not have: a model fitted at a_p,model has the helix lag of its flutes
// averaged in — at a thinner cut (a helix turn, one pitch deep) the teeth hold more chip per mm of depth
// than a_p / a_p,model says; on a helix the lowest layers are cut over up to 180° (beyond the fitted
// contact lengths); at entries the engaged arc lies at the front. The force grows with the uncut chip
// the teeth hold at once, so the model also transfers as F̂(t_m, L') · C / C_ref (geometry/chip_load.hpp):
// C the sample's peak chip load over all its layers, C_ref that of the straight cut of depth a_p,model
// with the same t_m and L' = L clamped to the fitted range. The planner takes the larger of the two
// (the chip-load transfer is never allowed to lower a force the linear scaling predicts: both are
// estimates outside the data, and the cautious one is kept). On straight cuts at a_p,model both are F̂.
//
// Descending into material (plunges, ramps, helices): the Z feed per tooth is at most the tool's
// plunge feed per tooth (geometry::Tool::plunge_feed_per_tooth_mm): F ≤ f_z,plunge · Z · n / |dz/ds|.

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/straight_cut_loads.hpp"
#include "feedplan/geometry/move.hpp"
#include "feedplan/geometry/tool.hpp"
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

//! C / C_ref of the chip-load transfer (see the file comment) at `sample` of `profile` for `tool`; 0 when
//! the sample makes no chip or has no layers (the transfer does not apply).
double chip_load_ratio(const model::ResponseSurfaceModel& model, const geometry::EngagementProfile& profile,
                       const geometry::EngagementSample& sample, const geometry::Tool& tool);

//! The same with the sample's peak chip load given (`load_mm`: geometry::peak_chip_load_mm of the sample)
//! and the straight cuts' taken from `straight_cuts` (for the tool of the sample).
double chip_load_ratio(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                       double load_mm, geometry::StraightCutLoads& straight_cuts);

//! The largest path feed (mm/min) at which `move` descends no faster than the tool's plunge feed per tooth
//! allows at `spindle_rpm`, with its descent taken `resolution_mm` deeper than planned (the written
//! program's rounding: PlanOptions::coordinate_resolution_mm); +∞ when the move does not descend.
double plunge_feed_limit_mm_per_min(const geometry::Move& move, const geometry::Tool& tool, double spindle_rpm,
                                    double resolution_mm = 0.0);

//! The feed (mm/min) at which `model` predicts `target_force_n` at `sample` (engaged, cutting), by
//! model::solve_feed on the chip factor × XY speed ratio, with the axial-depth scaling above. A sample
//! that is not engaged or makes no chip gets `air_feed_mm_per_min` with reason kAirFeed. A solution
//! clamped at the top of the fitted t_m range gets reason kModelRange (the feed the model still covers);
//! one below the range uses the rising root (F̂ = target, an extrapolation downwards, flagged).
//! With `uncertainty`, the feed is the largest one at or below that limit at which the upper bound
//! F̂ + z·σ (force_bound.hpp, same axial-depth scaling) meets the target, found by bisection (F̂ + z·σ
//! rises with the feed on the rising branch); when even a vanishing feed exceeds the target,
//! target_below_model is set.
//! `load_ratio` is chip_load_ratio for the sample (0: only the linear axial scaling).
SampleFeedLimit sample_feed_limit(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                                  double load_ratio, double target_force_n, int flutes, double spindle_rpm,
                                  double air_feed_mm_per_min, const ForceUncertainty* uncertainty = nullptr);

//! F̂ + z·σ (× the chip-area ratio ρ when uncertainty->off_straight_cut) at `sample` and path feed
//! `feed_mm_per_min` (F̂ without `uncertainty`), with the axial-depth scaling; 0 when the sample is not engaged.
double upper_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                     double load_ratio, double feed_mm_per_min, int flutes, double spindle_rpm,
                     const ForceUncertainty* uncertainty);

//! F̂ (N) the model predicts at `sample` when the tool runs at path feed `feed_mm_per_min`: the larger of
//! the axial-depth scaling and the chip-load transfer with `load_ratio` (file comment); 0 when the
//! sample is not engaged.
double predicted_force_n(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                         double load_ratio, double feed_mm_per_min, int flutes, double spindle_rpm);

//! predicted_force_n / F̂(t_m, max(L, L_min)) at `sample` and path feed `feed_mm_per_min`: the factor the
//! transfer that binds there (axial-depth scaling or chip load, with its contact length) puts on the
//! straight-cut model; what a measured force is divided by to give the model's own force at those inputs
//! (learning). axial_depth_ratio when F̂ is not positive or the sample is not engaged.
double force_transfer_factor(const model::ResponseSurfaceModel& model, const geometry::EngagementSample& sample,
                             double load_ratio, double feed_mm_per_min, int flutes, double spindle_rpm);

//! t_m (mm) at `sample` for path feed `feed_mm_per_min`.
double chip_thickness_mm(const geometry::EngagementSample& sample, double feed_mm_per_min, int flutes,
                         double spindle_rpm);

//! The contact length the model is evaluated at for a sample with contact length `contact_length_mm`:
//! max(L, range.contact_length_min_mm) (see the file comment), mm.
double model_contact_length_mm(const model::ResponseSurfaceModel& model, double contact_length_mm);

//! True when the tool meets material at the sample, on any layer and on any kind of move (what the
//! force model and the plunge limit apply to; an air move that meets material is cutting).
bool is_engaged(const geometry::EngagementSample& sample);

//! True when the tool meets material at the sample with its circle on any layer (is_engaged) or, while
//! descending, with its end face (geometry::EngagementSample::end_face_in_material): where the plunge
//! limit applies and a rapid is a collision.
bool meets_material(const geometry::EngagementSample& sample);

}  // namespace feedplan::planner
