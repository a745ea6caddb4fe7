#pragma once
// One learning step (seed 003 §2.3, docs/method.md §5.4): the force logs of cycles cut with a plan →
// aligned per-revolution samples → RLS (seed 003 Eq. 5, what the controller does in the air cut) and a
// robust batch refit with a prior toward the model the cycles were planned with, rescaled by the median
// ratio of measured to predicted force (one gain every log excites) → the next model and
// its covariance, with before/after errors. Nothing is stored here; the CLI stores the result as a new
// model version with lineage.

#include <array>
#include <string>
#include <vector>

#include "feedplan/model/covariance.hpp"
#include "feedplan/learning/batch_refit.hpp"
#include "feedplan/learning/learning_sample.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/learning/measured_revolutions.hpp"
#include "feedplan/learning/prediction_errors.hpp"
#include "feedplan/learning/rls.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/force_log/force_log.hpp"

namespace feedplan::learning {

//! How to learn.
struct ModelUpdateOptions {
  AlignmentOptions alignment;              //!< log → path
  MeasuredRevolutionOptions revolutions;   //!< path → per-revolution samples
  RlsOptions rls;                          //!< recursive least squares
  //! Robust refit with a prior; Cauchy by default: revolutions the quadratic cannot represent (entries
  //! into the material, where t_m and L pair unlike any straight cut) are outliers to it, and a Huber
  //! loss still lets their many large residuals bend the shape where the plan runs next. The prior holds
  //! the shape (σ_j = 0.1 |β_j| around the rescaled model): one cycle's data lie along one curve in
  //! (t_m, L), and a loose prior lets the quadratic wander where the next plan goes.
  BatchRefitOptions batch = [] {
    BatchRefitOptions options;
    options.loss = model::FitOptions::kCauchy;
    options.prior_sigma_fraction = 0.1;
    return options;
  }();
};

//! A log with its name (for messages).
struct NamedLog {
  std::string name;  //!< file name or "cycle 2"
  force_log::ForceLog log; //!< the log
};

//! What one log gave.
struct LogEvidence {
  std::string name;                 //!< the log's name
  Alignment alignment;              //!< its place on the path
  MeasuredRevolutions revolutions;  //!< per-revolution samples (empty when the alignment is not usable)
};

//! Whether the step produced a model.
enum class ModelUpdateStatus {
  kOk,           //!< a new model from the logs
  kNoEvidence,   //!< no log gave a usable sample: the model is unchanged (see the logs' messages)
};

//! "ok", "no evidence".
std::string to_string(ModelUpdateStatus status);

//! The outcome of a learning step.
struct ModelUpdate {
  ModelUpdateStatus status = ModelUpdateStatus::kNoEvidence;  //!< outcome
  std::vector<std::string> messages;         //!< one line per thing to know (per log, per fit)
  std::vector<LogEvidence> logs;             //!< per log
  std::vector<LearningSample> samples;       //!< this step's samples (all usable logs)
  RlsResult rls;                             //!< RLS from the plan's model over this step's samples
  BatchRefitResult batch;                    //!< the refit over earlier + this step's samples
  PredictionErrors before;                   //!< the plan's model on this step's samples
  PredictionErrors after_rls;                //!< the RLS model on them
  PredictionErrors after_batch;              //!< the refitted model on them
  double gain = 1.0;                         //!< median measured / predicted: the prior of the refit is the plan's model × this
  model::ResponseSurfaceModel model;      //!< the next model: the batch refit (the plan's model on kNoEvidence)
  model::Covariance covariance;              //!< its covariance, N² (for the next cautious plan)
};

//! Each log aligned with `plan` (align_log) and, when usable, its revolutions (measured_revolutions with
//! `model`, `flutes`, `spindle_rpm` and `revolutions`), in the order of `logs`; a line per log (and per
//! revolutions' message) appended to `messages`. What both kinds of model learn from.
std::vector<LogEvidence> log_evidence(const planner::PlanResult& plan, const model::ResponseSurfaceModel& model, int flutes,
                                      double spindle_rpm, const std::vector<NamedLog>& logs,
                                      const AlignmentOptions& alignment, const MeasuredRevolutionOptions& revolutions,
                                      std::vector<std::string>& messages);

//! Appends to `messages` what infeasible_places (infeasible_places.hpp) finds in `logs`' revolutions, if anything.
void add_infeasible_message(const planner::PlanResult& plan, const std::vector<LogEvidence>& logs,
                            double target_force_n, std::vector<std::string>& messages);

//! Learns from `logs` of cycles cut with `plan` (planned with `settings`, tool with `flutes`). The batch
//! refit spans `earlier` samples (of earlier cycles of the same tool, material and machine) and this
//! step's, its prior is settings.model with `prior_covariance` when given. Throws InputError on invalid
//! options. A log that cannot be aligned (another program, inches, no cut) is reported in the messages and
//! left out; when none is usable the status is kNoEvidence and the model is the plan's.
ModelUpdate update_model(const planner::PlanResult& plan, const planner::PlanSettings& settings, int flutes,
                         const std::vector<NamedLog>& logs, const std::vector<LearningSample>& earlier,
                         const std::optional<model::Covariance>& prior_covariance,
                         const ModelUpdateOptions& options = {});

}  // namespace feedplan::learning
