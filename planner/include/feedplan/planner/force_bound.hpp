#pragma once
// The cautious plan: an upper confidence bound on the predicted force from the model's parameter
// covariance (the "cautious first cut"). With covariance C of β, the standard deviation of F̂ at
// (t_m, L) is σ(t_m, L) = √(ψᵀ C ψ), ψ the regressors of seed 003 Eq. 4; the planner then holds
// F̂ + z·σ at the target instead of F̂. As logs arrive the refit's covariance shrinks and the bound
// tightens toward F̂.
//
// A model fitted on cutting tests of this very tool and material knows its own fit covariance; one
// taken from another tool or material, or never checked on this machine, is wrong by more than its
// fit says — mostly by a factor (a harder lot, another machine's stiffness). That part is a relative
// standard deviation r of F̂ added in quadrature: σ² = ψᵀCψ + (r·F̂)². After learning, r is 0 and C is the
// refit's covariance, which shrinks as logs arrive.
//
// Off the straight cuts a response surface is fitted on — where the tool enters material — the model
// under-predicts by a factor the straight-cut data cannot show, at most the chip-area ratio ρ
// (geometry/chip_area_ratio.hpp: the force grows at most like the uncut chip area). Before any log of
// this path that factor is taken at its worst when off_straight_cut is set: the bound is ρ·(F̂ + z·σ). It
// multiplies, because it acts on the true force whatever the model's own error is (in quadrature, a
// 40 % soft model still overshot +7 % at trochoid entries). Once the path has been cut, the factor is
// max(ρ, the correction learning along the path measured there) (PlanSettings::force_correction): ρ is
// not dropped, because entries cut slowly in a cautious cycle measure a ratio that is too small at the
// target feed (dropped, the next cycle overshot +24 … +48 %).

#include <array>

#include "feedplan/model/covariance.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::planner {

//! Covariance of β and how many standard deviations to plan on.
struct ForceUncertainty {
  model::Covariance covariance;         //!< covariance of β, N²
  double sigmas = 2.0;                  //!< z: the bound is F̂ + z·σ (≥ 0)
  double relative = 0.0;                //!< r: relative standard deviation of F̂ not in the covariance (≥ 0)
  bool off_straight_cut = false;        //!< multiply the bound by the sample's chip-area ratio ρ
};

//! σ(F̂) = √(ψᵀ C ψ + (r·F̂)²) at t_m = chip_mm and L = contact_length_mm, N.
double force_standard_deviation_n(const model::ResponseSurfaceModel& model, const ForceUncertainty& uncertainty,
                                  double chip_mm, double contact_length_mm);

}  // namespace feedplan::planner
