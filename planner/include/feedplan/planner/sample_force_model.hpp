#pragma once
// The force model the planner evaluates at a path sample, of either kind (docs/method.md §5.3, §6):
//
// - the response surface (seed 003 Eq. 1) with its transfers from straight cuts to other engagements and
//   its uncertainty bound: the functions of feed_limit.hpp;
// - the mechanistic kernel (model/mechanistic_force.hpp) on the sample's engaged sections — every layer
//   the geometry found, with their arcs (engaged_sections.hpp) — at the XY feed per tooth
//   f_z = F / (Z·n) · xy_speed_ratio. No transfer is needed: the kernel integrates the edge forces over the
//   arcs the sample really has. The feed limit solves peak(F) = target by a safeguarded 1-D search
//   (the peak rises with the feed at a place: every chip grows with it): bracketed regula falsi on
//   F (Illinois), started by a secant step from the previous sample's solution with its slope (which often
//   lands within kMechanisticForceTolerance of the target at once), ending within kMechanisticFeedTolerance
//   of the feed, never above a feed whose peak is at or below the target. The uncertainty bound is F̂·(1 + z·r) (ForceUncertainty::sigmas
//   and ::relative; the response surface's covariance does not apply).
//
// One object per path: plan(), the safety check, the target advice and the constant-feed baseline all
// ask it, so the kinds are told apart in one place.

#include <memory>
#include <optional>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/straight_cut_loads.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/planner/feed_limit.hpp"
#include "feedplan/planner/force_bound.hpp"

namespace feedplan::planner {

//! Relative width of the feed bracket at which the mechanistic solve stops.
inline constexpr double kMechanisticFeedTolerance = 1e-3;
//! The mechanistic solve also stops at a feed whose peak lies within this fraction of the target below it.
inline constexpr double kMechanisticForceTolerance = 1e-3;
//! Most peak evaluations of the mechanistic solve at one sample.
inline constexpr int kMechanisticSolveEvaluations = 40;

//! The planner's force model at the samples of one engagement profile.
class SampleForceModel {
 public:
  //! `surface` is always given (its fitted range describes the tests); `mechanistic`, when given, is the
  //! force model. Keeps references: `surface`, `mechanistic`, `profile` must outlive the object.
  //! `straight_cuts`, when given, remembers the straight cuts' chip loads for `tool` across objects.
  SampleForceModel(const model::ResponseSurfaceModel& surface, const model::MechanisticModel* mechanistic,
                   const geometry::EngagementProfile& profile, const geometry::Tool& tool,
                   std::shared_ptr<geometry::StraightCutLoads> straight_cuts = nullptr);

  bool mechanistic() const { return mechanistic_ != nullptr; }

  //! chip_load_ratio (feed_limit.hpp) for the response surface; 0 for the mechanistic kernel (no transfer).
  double load_ratio(const geometry::EngagementSample& sample) const;
  //! The same with the sample's peak chip load given (geometry::peak_chip_load_mm, PlanGeometry).
  double load_ratio(const geometry::EngagementSample& sample, double peak_chip_load_mm) const;

  //! The feed limit at `sample` for `target_force_n` (sample_feed_limit for the response surface).
  SampleFeedLimit feed_limit(const geometry::EngagementSample& sample, double load_ratio, double target_force_n,
                             int flutes, double spindle_rpm, double air_feed_mm_per_min,
                             const ForceUncertainty* uncertainty) const;

  //! F̂ at `sample` and path feed `feed_mm_per_min`, N; 0 when not engaged.
  double predicted_force_n(const geometry::EngagementSample& sample, double load_ratio, double feed_mm_per_min,
                           int flutes, double spindle_rpm) const;

  //! The bound held at the target: F̂ + z·σ (upper_force_n) or F̂·(1 + z·r) for the kernel; F̂ without
  //! `uncertainty`.
  double upper_force_n(const geometry::EngagementSample& sample, double load_ratio, double feed_mm_per_min, int flutes,
                       double spindle_rpm, const ForceUncertainty* uncertainty) const;

  //! force_transfer_factor for the response surface; 1 for the kernel.
  double transfer_factor(const geometry::EngagementSample& sample, double load_ratio, double feed_mm_per_min,
                         int flutes, double spindle_rpm) const;

 private:
  double kernel_peak_n(const geometry::EngagementSample& sample, double feed_per_tooth_mm) const;
  //! The kernel's limit at `feed_mm_per_min`, found within the tolerance by the warm start (remembered as the
  //! next sample's start, the slope kept).
  SampleFeedLimit finish_kernel_limit(SampleFeedLimit limit, const geometry::EngagementSample& sample,
                                      double feed_mm_per_min, int flutes, double spindle_rpm) const;
  SampleFeedLimit kernel_feed_limit(const geometry::EngagementSample& sample, double target_force_n, int flutes,
                                    double spindle_rpm, double air_feed_mm_per_min, double bound_factor) const;

  //! The last feed limit the mechanistic solve found, mm/min (0: none): the next sample's starting bracket.
  //! Only a starting point — the solve's result does not depend on it beyond its tolerance.
  mutable double last_solution_mm_per_min_ = 0.0;
  //! The slope of the peak in the feed at that solution, N per mm/min (0: none): the next secant step's.
  mutable double last_slope_n_per_mm_per_min_ = 0.0;
  //! The straight cuts' peak chip loads the response surface's transfers asked for (shared with other
  //! plans of the path when given to the constructor).
  std::shared_ptr<geometry::StraightCutLoads> straight_cuts_;
  const model::ResponseSurfaceModel& surface_;
  const model::MechanisticModel* mechanistic_;
  const geometry::EngagementProfile& profile_;
  const geometry::Tool& tool_;
};

}  // namespace feedplan::planner
