#include "feedplan/learning/path_correction.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/model_db/model_prediction.hpp"

namespace feedplan::learning {

std::vector<double> path_correction(const planner::PlanResult& plan, const model_db::ResponseSurfaceModel& model,
                                    const std::vector<MeasuredRevolutions>& measured, const std::vector<double>& previous) {
  const auto& samples = plan.samples;
  const bool first = previous.size() != samples.size();
  std::vector<double> correction = first ? std::vector<double>(samples.size(), 1.0) : previous;
  const auto first_at_or_after = [&](double s_mm) {
    return static_cast<std::size_t>(std::lower_bound(samples.begin(), samples.end(), s_mm,
                                                     [](const planner::PlannedSample& p, double s) { return p.s_mm < s; }) -
                                    samples.begin());
  };
  for (const MeasuredRevolutions& log : measured) {
    for (const LearningSample& sample : log.samples) {
      // The revolution whose span holds the sample (its middle).
      const auto revolution = std::find_if(log.revolutions.begin(), log.revolutions.end(), [&](const auto& r) {
        return r.s_start_mm <= sample.s_mm && sample.s_mm <= r.s_end_mm;
      });
      if (revolution == log.revolutions.end()) continue;
      const double predicted = model_db::predict(model, sample.chip_mm, sample.contact_length_mm).force_n;
      if (!(predicted > 0.0) || !(sample.force_n > 0.0)) continue;
      const double ratio = std::clamp(sample.force_n / predicted, kMinPathCorrection, kMaxPathCorrection);
      for (std::size_t i = first_at_or_after(revolution->s_start_mm); i < samples.size() && samples[i].s_mm <= revolution->s_end_mm;
           ++i) {
        if (samples[i].engaged) correction[i] = first ? ratio : std::sqrt(correction[i] * ratio);
      }
    }
  }
  return correction;
}

}  // namespace feedplan::learning
