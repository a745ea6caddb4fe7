#pragma once
// Internal: the robust step of fit_model() — minimising Σ w_i ρ(y_i − ψ_iᵀβ) with Ceres for a model that
// is linear in β, from a given start, some coefficients held fixed. Ceres stays inside the .cpp.

#include <array>
#include <string>
#include <vector>

#include "feedplan/model/model_fit.hpp"

namespace feedplan::model::detail {

//! What the robust minimisation returned.
struct RobustLinearFit {
  std::array<double, 6> beta{};  //!< the last iterate (the minimum when converged)
  bool converged = false;        //!< Ceres reported CONVERGENCE
  int iterations = 0;            //!< Ceres iterations
  std::string report;            //!< Ceres' termination message
};

//! Minimises Σ w_i ρ(y_i − ψ_iᵀβ), ρ the Huber or Cauchy loss of scale `scale_n` (Ceres' HuberLoss /
//! CauchyLoss, times w_i by ScaledLoss), starting from `initial`; coefficients with active[j] false stay at
//! initial[j]. `regressors`, `forces_n` and `weights` have one entry per sample. Needs loss kHuber or kCauchy.
RobustLinearFit robust_linear_fit(const std::vector<std::array<double, 6>>& regressors,
                                  const std::vector<double>& forces_n, const std::vector<double>& weights,
                                  FitOptions::Loss loss, double scale_n, const std::array<bool, 6>& active,
                                  const std::array<double, 6>& initial, int max_iterations);

}  // namespace feedplan::model::detail
