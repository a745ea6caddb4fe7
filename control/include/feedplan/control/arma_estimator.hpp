#pragma once
// Recursive least squares on the ARMA parameters θ_p of seed 002 (Eq. 21), "with covariance resetting and
// dead-zone control" as seed 002 cites from Goodwin & Sin (Adaptive Filtering, Prediction and Control,
// 1984, §3.3 and §8.5). For each sample f(t) with regressor φ = φ_m(t−1):
//
//   e = f(t) − φᵀ θ̂                         the a-priori error, N
//   |e| ≤ d: nothing changes (dead zone)     errors within the noise bound d carry no information that
//                                            outweighs the drift they cause; the estimate stops moving
//                                            once it predicts within the noise
//   otherwise
//     θ̂ ← θ̂ + P φ e / (1 + φᵀ P φ)
//     P ← P − P φ φᵀ P / (1 + φᵀ P φ), then symmetrised
//     trace(P) < reset_trace: P ← P₀ = p₀ I   covariance resetting: P shrinks like 1/t as samples
//                                            accumulate and the estimator would stop following a
//                                            changed process (a new depth of cut, a new material);
//                                            resetting restores its gain
//
// Plain RLS without a forgetting factor between resets, as Goodwin & Sin's resetting algorithm. Learning's
// RLS (learning/rls.hpp) runs the same safeguards on the response-surface coefficients; this one is on
// the four ARMA parameters and depends on nothing but Eigen.

#include <array>
#include <string>
#include <vector>

#include "feedplan/control/arma_model.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! Settings of the estimator.
struct ArmaEstimatorParameters {
  //! p₀ of P₀ = p₀ I (finite, > 0). Seed 002 gives none. The regressor holds forces and feeds of a few
  //! hundred (|φ|² ≈ 10⁶), so φᵀP₀φ ≈ 10 with 1e-5: the first informative sample moves θ̂ most of the way to
  //! what it sees, without the jumps a larger p₀ makes from the poorly excited steady cut.
  double initial_variance = 1e-5;
  //! d, N (finite, ≥ 0; 0: every sample updates). Seed 002 gives none; d must exceed the per-revolution
  //! noise so that noise alone rarely moves θ̂: 30 N is 3σ of the 10 N noise the tests use, and inside
  //! seed 002's ±50 N band around its 500 N reference.
  double dead_zone_n = 30.0;
  //! P ← P₀ when trace(P) falls below this (finite, ≥ 0 and < 4 p₀; 0: never reset): 1e-7, P shrunk 400-fold.
  double reset_trace = 1e-7;
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("arma_estimator.reset_trace = 5: must be < 4 × initial_variance = 4"). Empty when usable.
std::vector<InputProblem> validate(const ArmaEstimatorParameters& parameters,
                                   const std::string& field_prefix = "arma_estimator.");

//! What one sample did.
struct ArmaEstimatorStep {
  double error_n = 0.0;  //!< the a-priori error f(t) − φᵀθ̂, N
  bool updated = false;  //!< false: |error_n| ≤ d, nothing changed
  bool reset = false;    //!< P was reset to P₀ after this update
};

//! The estimator, one sample at a time.
class ArmaEstimator {
 public:
  //! Starts at θ̂ = `start` with P = P₀. Throws InputError with validate()'s problems for the parameters and
  //! for every non-finite coefficient of `start`.
  ArmaEstimator(const ArmaModel& start, const ArmaEstimatorParameters& parameters = {});

  //! Learns from the force `force_n` sampled at t and its regressor φ_m(t−1) (arma_regressor()); all
  //! finite (asserted).
  ArmaEstimatorStep update(double force_n, const std::array<double, 4>& regressor);

  const ArmaModel& model() const { return model_; }  //!< θ̂ now
  double covariance_trace() const;                    //!< trace(P) now
  int updates() const { return updates_; }                 //!< samples that changed θ̂
  int skipped_in_dead_zone() const { return skipped_; }    //!< samples within the dead zone
  int resets() const { return resets_; }                   //!< covariance resets

 private:
  ArmaModel model_;
  ArmaEstimatorParameters parameters_;
  std::array<double, 16> covariance_{};  // P, row-major 4×4
  int updates_ = 0;
  int skipped_ = 0;
  int resets_ = 0;
};

}  // namespace feedplan::control
