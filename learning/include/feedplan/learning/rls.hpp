#pragma once
// Recursive least squares on the force model's coefficients (seed 003 Eq. 5, docs/method.md §5.4), with the
// safeguards seed 002 uses after Goodwin & Sin (Adaptive Filtering, Prediction and Control, 1984): a
// forgetting factor, covariance resetting and a dead zone.
//
// The method. θ = β (BetaIndex order); ψ = regressors(start, t_m, L) (seed 003 Eq. 4) with the starting
// model's centres and scales, which stay fixed. For each sample, with forgetting factor λ, noise variance
// σ² of a unit-weight sample and the sample's weight w:
//   1. e = F − ψᵀθ, the a-priori error. With a dead zone d > 0 and |e| ≤ d the sample changes nothing
//      (counted as skipped): errors that small are mostly noise, and learning from them only lets θ drift
//      and P shrink or, with λ < 1, wind up.
//   2. K = Pψ / (λσ²/w + ψᵀPψ);  θ ← θ + K e;  P ← (P − K ψᵀP) / λ, then P ← (P + Pᵀ)/2.
//      With σ² = w = λ = 1 this is Eq. 5 as printed. It is the exact recursive minimiser of
//          λᴺ (θ − θ₀)ᵀ P₀⁻¹ (θ − θ₀) + Σₖ λᴺ⁻ᵏ wₖ eₖ² / σ²,
//      so with λ = 1, P is the covariance of θ in N² (P₀ the prior's, σ² the noise's); with λ < 1 old samples
//      count λ per sample less, an effective memory of about 1/(1 − λ) samples.
//   3. Covariance resetting: when trace(P) falls below reset_trace_min_n2 (the gain has died away and the
//      estimator would stop following a changed process) or rises above reset_trace_max_n2 (windup: with
//      λ < 1, directions ψ does not excite grow by 1/λ every update), P ← P₀ (counted).
// The model's fitted range grows to cover every sample seen, skipped ones included (the model matches them
// within the dead zone).

#include <array>
#include <vector>

#include "feedplan/model/covariance.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/learning/learning_sample.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::learning {

//! How to run the recursive least squares.
struct RlsOptions {
  //! λ in (0, 1]: each earlier sample counts λ times less; 1 remembers everything (plain Eq. 5).
  double forgetting_factor = 0.98;
  //! d, N (≥ 0): samples with |a-priori error| ≤ d are skipped; 0 turns the dead zone off.
  double dead_zone_n = 2.0;
  //! σ, N (> 0): standard deviation of a unit-weight force sample. 1 N is Eq. 5 as printed (its I); it sets
  //! how far P₀ trusts the start against the data and gives P its unit.
  double noise_sigma_n = 1.0;
  //! P₀ = this · I, N² (> 0): the variance of each starting coefficient; large lets the first samples move θ freely.
  double initial_variance_n2 = 1e4;
  //! P ← P₀ when trace(P) < this, N² (≥ 0, below trace(P₀) = 6 · initial_variance_n2); 0 never resets low.
  double reset_trace_min_n2 = 1e-3;
  //! P ← P₀ when trace(P) > this, N² (above trace(P₀); +inf never resets high).
  double reset_trace_max_n2 = 1e8;
};

//! Every problem with the options, each naming its field ("rls.forgetting_factor = 1.5: must be in (0, 1]");
//! empty when all is well.
std::vector<InputProblem> validate(const RlsOptions& options);

//! What one sample did.
struct RlsStep {
  double error_n = 0.0;  //!< a-priori error F − ψᵀθ before the sample, N
  bool updated = false;  //!< false: |error_n| lay within the dead zone and nothing changed but the range
  bool reset = false;    //!< the covariance was reset to P₀ after this update
};

//! The estimator, one sample at a time.
class RecursiveLeastSquares {
 public:
  //! Starts at `start` (its β, centres and scales, range) with P = P₀. Throws feedplan::InputError listing
  //! every problem with the options (validate()) and with the model (model::validate()).
  explicit RecursiveLeastSquares(const model::ResponseSurfaceModel& start, const RlsOptions& options = {});

  //! Learns from one sample by steps 1–3 of the file comment. Throws feedplan::InputError, fields
  //! "sample.chip_mm" etc., when t_m or L is not finite and ≥ 0, F not finite, or the weight not finite and > 0.
  RlsStep add(const LearningSample& sample);

  //! The current model: the start with θ as β and the range extended over the samples seen.
  const model::ResponseSurfaceModel& model() const { return model_; }
  //! P, row-major 6×6 in BetaIndex order, N² (symmetric).
  const model::Covariance& covariance() const { return covariance_; }
  int updates() const { return updates_; }                            //!< samples that changed θ
  int skipped_in_dead_zone() const { return skipped_in_dead_zone_; }  //!< samples within the dead zone
  int resets() const { return resets_; }                              //!< covariance resets

 private:
  model::ResponseSurfaceModel model_;
  RlsOptions options_;
  model::Covariance covariance_;
  int updates_ = 0;
  int skipped_in_dead_zone_ = 0;
  int resets_ = 0;
};

//! The outcome of learning from a set of samples.
struct RlsResult {
  //! The start with β updated, its centres and scales unchanged, its range the union of the start's and
  //! the samples' t_m and L.
  model::ResponseSurfaceModel model;
  int n = 0;                        //!< samples given
  int updates = 0;                  //!< samples that changed β
  int skipped_in_dead_zone = 0;     //!< samples whose a-priori error lay within the dead zone
  int resets = 0;                   //!< covariance resets
  double rms_error_before_n = 0.0;  //!< weighted RMS of F − F̂ over the samples with the start model, N (0 for none)
  double rms_error_after_n = 0.0;   //!< the same with the final model (a posteriori), N
  model::Covariance covariance;         //!< the final P, N²
};

//! Runs RecursiveLeastSquares from `start` over `samples` in order. The RMS errors are √(Σ w e² / Σ w).
//! Throws feedplan::InputError listing every problem with the options, the model and the samples, each
//! naming the sample ("samples[3].force_n = nan: must be finite"). No samples: the start, unchanged.
RlsResult rls_update(const model::ResponseSurfaceModel& start, const std::vector<LearningSample>& samples,
                     const RlsOptions& options = {});

}  // namespace feedplan::learning
