#include "feedplan/learning/learning_sample.hpp"

#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning {

void validate(const LearningSample& s, const std::string& prefix, std::vector<InputProblem>& problems) {
  const auto text = [](double value) { return shortest_number_text(value); };
  if (!std::isfinite(s.chip_mm) || s.chip_mm < 0.0) {
    problems.push_back({prefix + "chip_mm", "= " + text(s.chip_mm) + ": must be finite and ≥ 0"});
  }
  if (!std::isfinite(s.contact_length_mm) || s.contact_length_mm < 0.0) {
    problems.push_back({prefix + "contact_length_mm", "= " + text(s.contact_length_mm) + ": must be finite and ≥ 0"});
  }
  if (!std::isfinite(s.force_n)) problems.push_back({prefix + "force_n", "= " + text(s.force_n) + ": must be finite"});
  if (!std::isfinite(s.weight) || s.weight <= 0.0) {
    problems.push_back({prefix + "weight", "= " + text(s.weight) + ": must be finite and > 0"});
  }
}

void validate(const model::ResponseSurfaceModel& model, const std::vector<LearningSample>& samples,
              std::vector<InputProblem>& problems) {
  for (InputProblem& p : model::validate(model)) problems.push_back(std::move(p));
  for (std::size_t i = 0; i < samples.size(); ++i) validate(samples[i], "samples[" + std::to_string(i) + "].", problems);
}

// √(Σ w (F − F̂)² / Σ w) over the samples; 0 for none.
double weighted_rms_error(const model::ResponseSurfaceModel& model, const std::vector<LearningSample>& samples) {
  double sum = 0.0, weight = 0.0;
  for (const LearningSample& s : samples) {
    const double e = s.force_n - model::predict(model, s.chip_mm, s.contact_length_mm).force_n;
    sum += s.weight * e * e;
    weight += s.weight;
  }
  return weight > 0.0 ? std::sqrt(sum / weight) : 0.0;
}

}  // namespace feedplan::learning
