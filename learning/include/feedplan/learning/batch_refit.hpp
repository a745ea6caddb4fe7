#pragma once
// Batch refit of the force model's coefficients over all aligned samples of the logged cycles, pulled toward
// the prior model where the logs do not excite a direction (docs/method.md §5.4).
//
// The method. ψ_i = regressors(prior, t_m, L) (seed 003 Eq. 4) with the prior model's centres and scales,
// which the refit keeps, so β stays comparable with the prior's.
//   1. Prior spread: σ_j = √(prior_covariance_n2[j][j]) when the prior's fit covariance is given and that
//      entry is > 0; otherwise (no covariance, or a coefficient held at 0 in a reduced fit)
//      σ_j = prior_sigma_fraction · max(|β_prior_j|, prior_floor_fraction · |β_prior_0|), and 1 N should that
//      be 0. The floor keeps a coefficient that is small in the prior free to become larger.
//   2. Estimate: minimise over β
//          Σ_i w_i ρ(F_i − ψ_iᵀβ) / σ_e²  +  prior_weight · Σ_j (β_j − β_prior_j)² / σ_j²
//      with ρ the loss of scale loss_scale_n (squared, Huber, Cauchy as model::FitOptions) and σ_e the
//      noise of a unit-weight sample. Both terms are then squared numbers of standard deviations, so the
//      prior weighs as much as data of that precision would. For squared loss the minimum is the closed form
//      (ΨᵀWΨ/σ_e² + Λ)⁻¹ (ΨᵀWF/σ_e² + Λ β_prior), Λ = prior_weight · diag(1/σ_j²). For Huber, Ceres
//      (Levenberg–Marquardt, dense QR) starts from that closed form; for Cauchy, whose loss is not convex, it
//      first runs the Huber fit and starts from there. Converged means Ceres' CONVERGENCE (tolerances 1e-10).
//   3. Covariance: (Ψᵀ Ω Ψ + Λ)⁻¹ in N², Ω_i = w_i u(r_i)/σ_e² with u the loss's IRLS weight at the minimum
//      (1 for squared loss, δ/|r| beyond δ for Huber, 1/(1 + r²/δ²) for Cauchy): the posterior covariance of
//      β for squared loss, its Gauss–Newton approximation for the robust losses.
//   4. Excitation: coefficient j is excited when the data carry at least as much information about it as
//      the prior, i.e. its posterior variance is at most half its prior variance σ_j²/prior_weight. An
//      unexcited coefficient is set by the prior (e.g. β2, β22, β12 when every sample has the same L).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/model/covariance.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/learning/learning_sample.hpp"
#include "feedplan/model/model_fit.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::learning {

//! How to refit.
struct BatchRefitOptions {
  //! The loss on the force residuals (as model::FitOptions: kSquared, kHuber, kCauchy).
  model::FitOptions::Loss loss = model::FitOptions::kHuber;
  //! δ, the residual beyond which the robust loss down-weights, N (> 0).
  double loss_scale_n = 10.0;
  //! σ_e, standard deviation of a unit-weight force sample, N (> 0): what the data term is measured against.
  //! Per-revolution peaks scatter by a few N; the prior's FitResult::rmse_n is a good value when known.
  double noise_sigma_n = 5.0;
  //! Multiplies the prior term (> 0): 1 weighs the prior by its σ_j; smaller lets the data move β more.
  double prior_weight = 1.0;
  //! σ_j as a fraction of the prior's |β_j| when no prior covariance is given (> 0): 0.5 lets a coefficient
  //! move by about half its value before the prior resists as much as one standard deviation of data.
  double prior_sigma_fraction = 0.5;
  //! Floor of |β_j| in that rule as a fraction of |β_prior_0|, the force at the centre (≥ 0).
  double prior_floor_fraction = 0.1;
  //! The prior model's fit covariance (model::FitResult::covariance), row-major 6×6 in BetaIndex order,
  //! N²; when given, its diagonal sets σ_j (entries must be finite and ≥ 0; 0 falls back to the rule above).
  std::optional<model::Covariance> prior_covariance_n2;
  //! Ceres iterations for the robust losses (≥ 1).
  int max_iterations = 1000;
};

//! Every problem with the options, each naming its field ("refit.prior_weight = 0: must be finite and > 0");
//! empty when all is well.
std::vector<InputProblem> validate(const BatchRefitOptions& options);

//! Whether the refit gave a model.
enum class BatchRefitStatus {
  kOk,                //!< the minimum was found
  kNotEnoughSamples,  //!< no samples; the result holds the prior unchanged, σ_j² as its covariance
  kNoConvergence,     //!< Ceres stopped before converging; the model is the last iterate — check before use
};

//! "ok", "not enough samples", "no convergence".
std::string to_string(BatchRefitStatus status);

//! The refitted model and how the data determined it.
struct BatchRefitResult {
  BatchRefitStatus status = BatchRefitStatus::kNotEnoughSamples;  //!< outcome
  std::string message;                  //!< one or two sentences for people, with the numbers
  //! The prior with β refitted, its centres, scales, axial depth and spindle speed unchanged, its range
  //! the union of the prior's and the samples' t_m and L.
  model::ResponseSurfaceModel model;
  int n = 0;                            //!< samples fitted
  double rms_error_before_n = 0.0;      //!< weighted RMS of F − F̂ over the samples with the prior, N
  double rms_error_after_n = 0.0;       //!< the same with the refitted model, N
  model::Covariance covariance;         //!< covariance of β (step 3), N²
  std::array<double, 6> standard_error_n{};  //!< √ of its diagonal, N
  std::array<double, 6> prior_sigma_n{};     //!< σ_j of the prior (step 1), N
  std::array<bool, 6> excited{};        //!< the data determine β_j more than the prior does (step 4)
  int downweighted_count = 0;           //!< samples the robust loss weighted below 1/2 (u(r) < 0.5)
};

//! Refits `prior`'s coefficients to `samples` by the method of the file comment. Weighted RMS errors are
//! √(Σ w r² / Σ w). Returns kOk with the model; kNotEnoughSamples for no samples (one is enough: the prior
//! makes the problem well posed); kNoConvergence with the last iterate and Ceres' reason. Throws
//! feedplan::InputError listing every problem with the options, the prior model (model::validate()) and
//! the samples, each naming the sample ("samples[3].force_n = nan: must be finite").
BatchRefitResult batch_refit(const model::ResponseSurfaceModel& prior, const std::vector<LearningSample>& samples,
                             const BatchRefitOptions& options = {});

}  // namespace feedplan::learning
