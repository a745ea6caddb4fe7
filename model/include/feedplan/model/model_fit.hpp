#pragma once
// Fitting the response-surface model (seed 003 Eq. 1, docs/method.md §5.3) to data points (t_m, L, F) —
// cutting tests, or aligned samples of logged cycles — with a robust loss, and saying how well the
// coefficients are determined.
//
// The method.
//   1. Normalisation from the data: centre = mid-range, scale = half the range of t_m and of L; the fitted
//      range is the data's min/max. An input whose span is at most same_value_tolerance × its largest
//      magnitude "did not vary"; its scale is then |centre| (1 mm when the centre is 0).
//   2. Identifiability. When L did not vary, β2, β22 and β12 cannot be estimated; when t_m did not vary,
//      β1, β11 and β12 cannot. With allow_reduced_model those are held at 0 (`estimated` false) and the
//      status is kReducedModel; without it, or when neither input varied, kInsufficientData. With p
//      coefficients to estimate, n ≤ p samples is kInsufficientData (p determine the coefficients, one
//      more is needed to estimate their uncertainty). A design that still does not determine them (the
//      weighted regressor matrix has σ_min/σ_max ≤ 1e-9: e.g. only 2 distinct values of t_m, whose square
//      is then a combination of 1 and X1, or samples on one line in the (t_m, L) plane) is
//      kInsufficientData too, with the distinct-value counts in the message.
//   3. Estimate. Weighted ordinary least squares (Householder QR) gives the start; it is the exact minimum
//      for kSquared and the answer then. For kHuber and kCauchy, Ceres (Levenberg–Marquardt, dense QR)
//      minimises Σ w_i ρ(r_i) with r_i = F_i − F̂_i in newtons and ρ the loss with scale loss_scale_n (Ceres'
//      HuberLoss / CauchyLoss of that scale, ScaledLoss by w_i); held coefficients stay at 0 (SubsetManifold).
//      Converged means Ceres' CONVERGENCE (function, gradient or parameter tolerance 1e-10); not reaching it
//      within max_iterations is kNotConverged (the model is the last iterate, its statistics computed there).
//   4. Uncertainty (Huber 1981, §7.6, the estimate R's MASS::rlm reports). With ψ = ρ' (ψ(r) = r for
//      squared loss, clip(r, ±δ) for Huber, r / (1 + r²/δ²) for Cauchy), m = Σ w ψ'(r) / Σ w,
//      v = Σ w (ψ'(r) − m)² / Σ w, κ = 1 + (p/n)·v/m² and s² = Σ w ψ(r)² / (n − p):
//          Cov(β) = κ² s² / m² · (Xᵀ W X)⁻¹   over the estimated coefficients, 0 for held ones.
//      For kSquared this is the classical σ̂² (XᵀWX)⁻¹ with σ̂² = Σ w r² / (n − p). When m ≤ 0 (a Cauchy
//      fit with most residuals beyond the loss scale) the sandwich is undefined and the weighted-least-
//      squares form with the robust weights, σ̂² (XᵀΩX)⁻¹ with Ω = w·u(r), is used and the message says so.
//   5. Quality, weighted by w (plain means for unit weights): rmse_n = √(Σ w r² / Σ w);
//      r_squared = 1 − Σ w r² / Σ w (F − F̄_w)² (1 when every F is equal and fitted exactly);
//      loo_rmse_n by the hat-matrix shortcut e_i / (1 − h_ii) of the final weighted least-squares problem,
//      h_ii = Ω_i x_iᵀ (XᵀΩX)⁻¹ x_i, Ω_i = w_i·u(r_i), u the loss's IRLS weight (1 for squared loss). That is
//      the exact leave-one-out refit for kSquared; for robust losses it is the refit with the robust weights
//      held at their final values. A sample with h_ii ≥ 1 − 1e-9 alone determines a coefficient and cannot be
//      predicted from the others: it is left out of loo_rmse_n and the message says how many were.
//
// Sample weights are relative precisions (inverse variances up to a common factor): multiplying all of
// them by one constant changes nothing.

#include <array>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/covariance.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::model {

//! One data point.
struct FitSample {
  double chip_mm = 0.0;            //!< t_m, maximum undeformed chip thickness, mm (finite, ≥ 0)
  double contact_length_mm = 0.0;  //!< L, contact length, mm (finite, ≥ 0)
  double force_n = 0.0;            //!< measured peak XY force per spindle revolution, N (finite)
  double weight = 1.0;             //!< relative precision of force_n (finite, > 0)
};

//! How to fit.
struct FitOptions {
  //! The loss on the force residuals.
  enum Loss {
    kSquared,  //!< ordinary (weighted) least squares
    kHuber,    //!< quadratic up to loss_scale_n, linear beyond: outliers pull with bounded force
    kCauchy,   //!< log(1 + r²/δ²): outliers far beyond loss_scale_n hardly pull at all
  };
  Loss loss = kHuber;                  //!< robust loss
  double loss_scale_n = 10.0;          //!< δ, the residual beyond which the robust loss down-weights, N (> 0)
  //! When one input did not vary, fit only the terms the data determine (kReducedModel) instead of failing.
  bool allow_reduced_model = true;
  //! An input whose span is at most this fraction of its largest magnitude did not vary, in [0, 1).
  double same_value_tolerance = 1e-6;
  //! Ceres iterations for kHuber and kCauchy (≥ 1). The robust steps converge linearly (they are IRLS steps
  //! in effect), slowest for Cauchy with residuals well beyond its scale: ≈ 400 iterations at noise 2 × δ.
  int max_iterations = 1000;
};

//! Whether the fit gave a model, and which.
enum class FitStatus {
  kOk,                //!< all six coefficients estimated
  kReducedModel,      //!< one input did not vary; its terms are held at 0 (see FitResult::estimated)
  kInsufficientData,  //!< too few samples, or samples that do not determine the coefficients; no model
  kNotConverged,      //!< the robust fit did not converge; the model is the last iterate — check before use
};

//! "ok", "reduced model", "insufficient data", "not converged".
std::string to_string(FitStatus status);

//! The fitted model and how well the data determine it. For kInsufficientData only status, message, n,
//! the model's centres, scales and range (when there was at least one sample) are meaningful; the
//! coefficients and statistics are 0.
struct FitResult {
  FitStatus status = FitStatus::kInsufficientData;  //!< outcome
  std::string message;                              //!< one or two sentences for people, with the numbers
  ResponseSurfaceModel model;                       //!< the fitted model (β, centres, scales, range)
  int n = 0;                                        //!< samples fitted
  double rmse_n = 0.0;                              //!< weighted RMS residual, N
  double r_squared = 0.0;                           //!< weighted coefficient of determination
  std::array<double, 6> standard_error_n{};         //!< standard error of each β (BetaIndex order), N; 0 if held
  Covariance covariance;                            //!< covariance of β, N²
  double loo_rmse_n = 0.0;                          //!< weighted leave-one-out RMS prediction error, N
  std::array<bool, 6> estimated{};                  //!< false: held at 0 in a reduced model
  std::vector<double> residual_n;                   //!< F_i − F̂_i for each sample, in input order, N
  int downweighted_count = 0;                       //!< samples the robust loss weighted below 1/2 (u(r) < 0.5)
};

//! Problems with the options (fields "options.loss_scale_n", "options.same_value_tolerance",
//! "options.max_iterations", "options.loss"); empty when all is well.
std::vector<InputProblem> validate(const FitOptions& options);

//! Fits the model to `samples` by the method of the file comment.
//!
//! Returns kOk or kReducedModel with the model, its statistics and a message summarising the fit (what
//! was held and why, for a reduced model); kInsufficientData (no crash, no silent fit) with a message
//! saying what is missing; kNotConverged with the last iterate and Ceres' reason. Throws
//! feedplan::InputError listing every non-finite or out-of-range sample value, each naming the sample
//! ("samples[3].force_n = nan: must be finite"), and every problem with the options.
FitResult fit_model(const std::vector<FitSample>& samples, const FitOptions& options = {});

//! The RMS error of each sample's force predicted by the model fitted (fit_model, `options`) without the
//! samples of its group, `group[i]` being sample i's, N — cross-validation by groups, e.g. by engagement. A
//! group whose complement cannot be fitted (kInsufficientData or kNotConverged) cannot be predicted at all: its
//! samples count with the error of no prediction, their forces. Throws as fit_model, and InputError when `group`
//! is not one per sample.
double leave_group_out_rmse_n(const std::vector<FitSample>& samples, const std::vector<int>& group,
                                            const FitOptions& options = {});

}  // namespace feedplan::model
