#include "feedplan/learning/model_update.hpp"

#include "feedplan/learning/infeasible_places.hpp"

#include <algorithm>
#include <cstdio>

#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning {
namespace {

std::string errors_line(const char* what, const PredictionErrors& e) {
  char text[256];
  std::snprintf(text, sizeof text, "%s: RMS %.2f %% (%.1f N), max %.2f %%, median %.2f %%, p95 %.2f %%, mean %+.2f %%",
                what, e.rms_percent, e.rms_n, e.max_abs_percent, e.median_abs_percent, e.p95_abs_percent, e.mean_percent);
  return text;
}

// Median of measured / predicted force (samples with a positive prediction); 1 when there are none.
double median_force_ratio(const model::ResponseSurfaceModel& model, const std::vector<LearningSample>& samples) {
  std::vector<double> ratios;
  for (const LearningSample& sample : samples) {
    const double predicted = model::predict(model, sample.chip_mm, sample.contact_length_mm).force_n;
    if (predicted > 0.0 && sample.force_n > 0.0) ratios.push_back(sample.force_n / predicted);
  }
  if (ratios.empty()) return 1.0;
  const auto middle = ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2);
  std::nth_element(ratios.begin(), middle, ratios.end());
  return *middle;
}

}  // namespace

void add_infeasible_message(const planner::PlanResult& plan, const std::vector<LogEvidence>& logs,
                            double target_force_n, std::vector<std::string>& messages) {
  std::vector<MeasuredRevolutions> measured;
  for (const LogEvidence& log : logs) measured.push_back(log.revolutions);
  const std::string text = describe(infeasible_places(plan, measured, target_force_n), target_force_n);
  if (!text.empty()) messages.push_back(text);
}

std::vector<LogEvidence> log_evidence(const planner::PlanResult& plan, const model::ResponseSurfaceModel& model, int flutes,
                                      double spindle_rpm, const std::vector<NamedLog>& logs,
                                      const AlignmentOptions& alignment, const MeasuredRevolutionOptions& revolutions,
                                      std::vector<std::string>& messages) {
  std::vector<LogEvidence> evidence_of_logs;
  for (const NamedLog& named : logs) {
    LogEvidence evidence;
    evidence.name = named.name;
    evidence.alignment = align_log(named.log, plan, alignment);
    messages.push_back(named.name + ": " + to_string(evidence.alignment.status) + " — " + evidence.alignment.message);
    if (usable(evidence.alignment.status)) {
      evidence.revolutions = measured_revolutions(named.log, evidence.alignment, plan, model, flutes, spindle_rpm, revolutions);
      if (!evidence.revolutions.message.empty()) messages.push_back(named.name + ": " + evidence.revolutions.message);
    }
    evidence_of_logs.push_back(std::move(evidence));
  }
  return evidence_of_logs;
}

std::string to_string(ModelUpdateStatus status) { return status == ModelUpdateStatus::kOk ? "ok" : "no evidence"; }

ModelUpdate update_model(const planner::PlanResult& plan, const planner::PlanSettings& settings, int flutes,
                         const std::vector<NamedLog>& logs, const std::vector<LearningSample>& earlier,
                         const std::optional<model::Covariance>& prior_covariance,
                         const ModelUpdateOptions& options) {
  ModelUpdate update;
  update.model = settings.model;
  update.logs = log_evidence(plan, settings.model, flutes, settings.spindle_rpm, logs, options.alignment,
                             options.revolutions, update.messages);
  add_infeasible_message(plan, update.logs, settings.target_force_n, update.messages);
  for (const LogEvidence& evidence : update.logs) {
    update.samples.insert(update.samples.end(), evidence.revolutions.samples.begin(), evidence.revolutions.samples.end());
  }
  if (update.samples.empty()) {
    update.messages.push_back("no usable per-revolution sample in any log: the model is unchanged");
    if (prior_covariance) update.covariance = *prior_covariance;
    return update;
  }

  update.before = prediction_errors(settings.model, update.samples);
  update.rls = rls_update(settings.model, update.samples, options.rls);
  update.after_rls = prediction_errors(update.rls.model, update.samples);

  std::vector<LearningSample> all = earlier;
  all.insert(all.end(), update.samples.begin(), update.samples.end());
  // The prior: the planned-with model rescaled by the median ratio measured / predicted over all samples.
  // A harder lot, a worn tool or another machine's stiffness mostly scale the forces; the one gain is
  // excited by any data, so the refit then only has to correct the shape where the data say so, and the
  // prior holds the shape in the directions they do not excite.
  const double gain = median_force_ratio(settings.model, all);
  model::ResponseSurfaceModel prior = settings.model;
  for (double& beta : prior.beta) beta *= gain;
  BatchRefitOptions batch = options.batch;
  if (prior_covariance) {
    model::Covariance scaled = *prior_covariance;
    for (double& c : scaled.entries()) c *= gain * gain;
    batch.prior_covariance_n2 = scaled;
  }
  update.gain = gain;
  update.batch = batch_refit(prior, all, batch);
  update.after_batch = prediction_errors(update.batch.model, update.samples);
  update.model = update.batch.model;
  update.covariance = update.batch.covariance;
  update.status = ModelUpdateStatus::kOk;
  char gain_text[96];
  std::snprintf(gain_text, sizeof gain_text, "measured / predicted force, median over the refit's samples: %.3f", gain);
  update.messages.push_back(gain_text);
  update.messages.push_back(std::to_string(update.samples.size()) + " per-revolution samples from this step, " +
                            std::to_string(all.size()) + " in the refit");
  update.messages.push_back(errors_line("planned-with model", update.before));
  update.messages.push_back(errors_line("after RLS (seed 003 Eq. 5)", update.after_rls));
  update.messages.push_back(errors_line("after batch refit", update.after_batch));
  if (update.batch.status != BatchRefitStatus::kOk) update.messages.push_back("batch refit: " + update.batch.message);
  return update;
}

}  // namespace feedplan::learning
