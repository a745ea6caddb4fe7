#pragma once
// How well a model predicts measured per-revolution peaks: the error of F̂ against each measured
// sample, summarised as RMS, largest and percentiles of |error| — the before/after figures of a
// learning step.

#include <vector>

#include "feedplan/learning/learning_sample.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::learning {

//! Errors of a model on a set of samples, in percent of the measured force.
struct PredictionErrors {
  int n = 0;                          //!< samples compared
  double rms_n = 0.0;                 //!< RMS of F̂ − F, N
  double rms_percent = 0.0;           //!< RMS of (F̂ − F)/F, %
  double max_abs_percent = 0.0;       //!< largest |F̂ − F|/F, %
  double median_abs_percent = 0.0;    //!< 50th percentile of |F̂ − F|/F, %
  double p90_abs_percent = 0.0;       //!< 90th percentile, %
  double p95_abs_percent = 0.0;       //!< 95th percentile, %
  double mean_percent = 0.0;          //!< mean signed (F̂ − F)/F, %: > 0 the model over-predicts
};

//! The errors of predictions `predicted_n` of the measured forces `measured_n` (pairwise; pairs with a
//! measured force ≤ 0 are skipped). Percentiles by the nearest-rank rule. All zero when no pair qualifies.
PredictionErrors prediction_errors(const std::vector<double>& measured_n, const std::vector<double>& predicted_n);

//! The errors of `model` on `samples` (forces > 0; samples with F ≤ 0 are skipped). Percentiles by the
//! nearest-rank rule. All zero when no sample qualifies.
PredictionErrors prediction_errors(const model::ResponseSurfaceModel& model, const std::vector<LearningSample>& samples);

}  // namespace feedplan::learning
