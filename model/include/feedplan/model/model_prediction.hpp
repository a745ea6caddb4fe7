#pragma once
// Evaluating the response-surface model (seed 003 Eq. 1, docs/method.md §5.3) at one point (t_m, L): the
// regressor vector ψ of seed 003 Eq. 4 and the predicted force, with whether the point lies outside the
// range the model was fitted on (where the model extrapolates).

#include <array>

#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::model {

//! Relative tolerance of the fitted-range checks: a value counts as inside [min, max] when it lies within
//! kRangeRelativeTolerance · max(|min|, |max|) of it, so that a feed solved exactly at a range edge, or a
//! range edge read back from text, is not reported as an extrapolation.
inline constexpr double kRangeRelativeTolerance = 1e-9;

//! The model's prediction at one point.
struct ForcePrediction {
  double force_n = 0.0;                 //!< F̂, the predicted peak XY force per spindle revolution, N
  bool chip_outside = false;            //!< t_m lies outside [range.chip_min_mm, range.chip_max_mm]
  bool contact_length_outside = false;  //!< L lies outside [range.contact_length_min_mm, range.contact_length_max_mm]
};

//! ψ = [1, X1, X2, X1², X2², X1·X2] with X1 = (t_m − c1)/s1 and X2 = (L − c2)/s2 (seed 003 Eq. 4), in
//! BetaIndex order, so that F̂ = Σ βᵢ ψᵢ. Needs a model whose scales are > 0 (validate()); any t_m and L
//! are accepted, NaN in gives NaN out.
std::array<double, 6> regressors(const ResponseSurfaceModel& model, double chip_mm, double contact_length_mm);

//! True when chip_mm lies outside the range's t_m interval by more than the relative tolerance
//! kRangeRelativeTolerance (NaN is outside).
bool chip_outside(const FittedRange& range, double chip_mm);

//! True when contact_length_mm lies outside the range's L interval by more than the relative tolerance
//! kRangeRelativeTolerance (NaN is outside).
bool contact_length_outside(const FittedRange& range, double contact_length_mm);

//! F̂ = β0 + β1 X1 + β2 X2 + β11 X1² + β22 X2² + β12 X1 X2 at t_m = chip_mm and L = contact_length_mm, and
//! whether each input lies outside the fitted range (the force is then an extrapolation, still returned).
//! Needs a model that passes validate() — it is not checked here, as the planner calls this once per path
//! sample; check a model once when it is loaded. NaN inputs give a NaN force, flagged as outside.
ForcePrediction predict(const ResponseSurfaceModel& model, double chip_mm, double contact_length_mm);

}  // namespace feedplan::model
