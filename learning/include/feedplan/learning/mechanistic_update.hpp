#pragma once
// One learning step for the mechanistic kind (docs/method.md §5.4, §5.7): the force logs of cycles cut with
// a mechanistic plan → the same aligned per-revolution peaks the response surface learns from → the cutting
// and edge coefficients K = (K_tc, K_rc, K_te, K_re) by RLS (seed 003 Eq. 5 with the kernel's regressor)
// and by a robust batch refit with a prior → the next model and its covariance. The runout, helix and size
// effect the cutting tests identified are held: one cycle's revolutions cannot separate them.
//
// The regressor. For a given engagement, feed and chip the force of every tooth element is linear in K, so
// the per-revolution peak of the XY resultant is homogeneous of degree one in K: peak(K) = g(K)·K with
// g = ∂peak/∂K (Euler). g is taken by central differences of the kernel's peak (read along the last tooth's
// chord, planner::SampleForceModel) at the engagement sample nearest the revolution's peak and the feed
// actually run there. It depends on K only through where in the revolution the peak falls, so RLS uses g
// at the planned model, and the batch refit recomputes it at each Gauss–Newton step.
//
// RLS: θ = K, ψ = g at the planned model; the steps of rls.hpp (forgetting factor, dead zone, noise σ) with
// P₀ the prior covariance below.
//
// Batch refit: minimise Σ_i ρ(F_i − g_i(K)·K)/σ² + (K − K₀)ᵀ Σ₀⁻¹ (K − K₀), with ρ the Cauchy loss of scale
// δ (revolutions where the kernel reads the path badly — the first one of a front — count less), by
// Gauss–Newton with the loss's IRLS weights u_i = 1/(1 + r_i²/δ²). Its covariance (Σ u g gᵀ/σ² + Σ₀⁻¹)⁻¹ is
// stored with the version and is the next step's prior (a Bayesian update from part to part).
//
// The prior Σ₀: the version's covariance plus (q·K_j)² on the diagonal. The identification's covariance
// counts every bin of the cutting tests as independent and is far too small to stand for how well straight
// cuts carry to a cycle; q (10 % by default) is that doubt, and between parts the drift of a tool that
// wears. Measured peaks are what the sensor read: a dynamometer that rounds the tooth pulses makes the
// learned coefficients those of its reading.

#include <array>
#include <string>
#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/learning/model_update.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning {

//! The coefficients learned: K_tc, K_rc, K_te, K_re.
using MechanisticCoefficients = std::array<double, 4>;
//! Their covariance, row-major, units N²/mm⁴ … N²/mm².
using MechanisticCovariance = std::array<std::array<double, 4>, 4>;

//! How to learn.
struct MechanisticUpdateOptions {
  AlignmentOptions alignment;             //!< log → path
  MeasuredRevolutionOptions revolutions;  //!< path → per-revolution samples (the raw peaks are used)
  double forgetting_factor = 0.98;        //!< RLS λ in (0, 1]
  double dead_zone_n = 2.0;               //!< RLS dead zone d, N (≥ 0)
  double noise_sigma_n = 5.0;             //!< σ of a per-revolution peak, N (> 0)
  double prior_sigma_fraction = 0.1;      //!< q: the prior's doubt on each coefficient, fraction of it (> 0)
  double loss_scale_n = 10.0;             //!< δ of the batch refit's Cauchy loss, N (> 0)
  int gauss_newton_steps = 4;             //!< batch refit iterations (≥ 1)
};

//! Every problem with the options, each naming its field ("forgetting_factor = 1.5: must be in (0, 1]").
std::vector<InputProblem> validate(const MechanisticUpdateOptions& options);

//! One measured revolution as the mechanistic kind learns from it.
struct MechanisticSample {
  double s_mm = 0.0;                  //!< where its peak was measured on the planned path, mm
  double feed_mm_per_min = 0.0;       //!< the feed run there, mm/min
  double force_n = 0.0;               //!< the measured peak, N
  MechanisticCoefficients regressor{};  //!< g = ∂peak/∂K at the planned model
};

//! The outcome of a learning step.
struct MechanisticUpdate {
  ModelUpdateStatus status = ModelUpdateStatus::kNoEvidence;  //!< outcome
  std::vector<std::string> messages;     //!< one line per thing to know (per log, per fit)
  std::vector<LogEvidence> logs;         //!< per log
  std::vector<MechanisticSample> samples;  //!< this step's samples
  PredictionErrors before;               //!< the plan's model on them
  PredictionErrors after_rls;            //!< the RLS model on them
  PredictionErrors after_batch;          //!< the refitted model on them
  model::MechanisticModel rls_model;     //!< the plan's model with the RLS coefficients
  model::MechanisticModel model;         //!< the next model: the batch refit (the plan's on kNoEvidence)
  MechanisticCovariance covariance{};    //!< its covariance (the prior's on kNoEvidence)
  double rms_error_after_n = 0.0;        //!< RMS error of the refit over the samples, N
};

//! Learns from `logs` of cycles cut with `plan`, planned with `settings` (settings.mechanistic set) on
//! `profile` (the plan's engagement) with `tool`; `prior_covariance` is the planned version's. Throws
//! InputError on invalid options or a plan without the mechanistic kind. A log that cannot be aligned is
//! reported in the messages and left out; when none is usable the status is kNoEvidence.
MechanisticUpdate update_mechanistic(const planner::PlanResult& plan, const planner::PlanSettings& settings,
                                     const geometry::EngagementProfile& profile, const geometry::Tool& tool,
                                     const std::vector<NamedLog>& logs, const MechanisticCovariance& prior_covariance,
                                     const MechanisticUpdateOptions& options = {});

}  // namespace feedplan::learning
