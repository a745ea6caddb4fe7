#include "feedplan/planner/sample_force_model.hpp"
#include "feedplan/planner/target_advice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "feedplan/core/number_text.hpp"
#include "feedplan/planner/feed_limit.hpp"

namespace feedplan::planner {
namespace {

// A feed so small that the chip is nothing, yet the model is evaluated on the rising branch, mm/min.
constexpr double kVanishingFeedMmPerMin = 1e-6;

std::string fixed1(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

std::string advice_text(const TargetAdvice& a, const PlanSettings& settings) {
  const std::string raise = "raise the target to at least " + fixed1(a.target_needed_n) + " N";
  if (a.unreachable_samples > 0) {
    return "at " + std::to_string(a.unreachable_samples) + " of the " + std::to_string(a.over_target_samples) +
           " samples above the target the model predicts up to " + fixed1(a.zero_feed_force_n) +
           " N even as the feed goes to 0, so no minimum feed can help there: " + raise +
           ", or take less material per pass there (the cycle's pitch or radial depth)";
  }
  return "the target needs feeds down to " + shortest_number_text(std::floor(a.needed_min_feed_mm_per_min * 10.0) / 10.0) +
         " mm/min, below the machine's min_feed_mm_per_min " + shortest_number_text(settings.machine.min_feed_mm_per_min) +
         ": lower min_feed_mm_per_min to that if the machine runs so slowly, or " + raise;
}

}  // namespace

TargetAdvice target_advice(const PlanGeometry& geometry, const PlanSettings& settings, const PlanResult& result) {
  TargetAdvice a;
  const auto& samples = geometry.engagement.samples;
  const ForceUncertainty* uncertainty = settings.uncertainty ? &*settings.uncertainty : nullptr;
  const int flutes = geometry.tool.flutes;
  a.needed_min_feed_mm_per_min = std::numeric_limits<double>::infinity();
  const SampleForceModel forces(settings.model, settings.mechanistic ? &*settings.mechanistic : nullptr,
                                geometry.engagement, geometry.tool);
  for (std::size_t i = 0; i < result.samples.size() && i < samples.size(); ++i) {
    const PlannedSample& planned = result.samples[i];
    if (!planned.engaged) continue;
    a.target_needed_n = std::max(a.target_needed_n, planned.upper_force_n);
    if (!(planned.upper_force_n > settings.target_force_n * (1.0 + 1e-9))) continue;
    ++a.over_target_samples;
    const double correction = settings.force_correction.empty() ? 1.0 : settings.force_correction[i];
    const double load_ratio = forces.load_ratio(samples[i]);
    const double zero_feed_n = correction * forces.upper_force_n(samples[i], load_ratio, kVanishingFeedMmPerMin, flutes,
                                                                 settings.spindle_rpm, uncertainty);
    if (zero_feed_n > settings.target_force_n) {
      ++a.unreachable_samples;
      a.zero_feed_force_n = std::max(a.zero_feed_force_n, zero_feed_n);
      continue;
    }
    const SampleFeedLimit limit = forces.feed_limit(samples[i], load_ratio, settings.target_force_n / correction, flutes,
                                                    settings.spindle_rpm, settings.machine.max_feed_mm_per_min,
                                                    uncertainty);
    a.needed_min_feed_mm_per_min = std::min(a.needed_min_feed_mm_per_min, limit.feed_mm_per_min);
  }
  if (!std::isfinite(a.needed_min_feed_mm_per_min)) a.needed_min_feed_mm_per_min = 0.0;
  if (a.over_target_samples > 0) a.text = advice_text(a, settings);
  return a;
}

}  // namespace feedplan::planner
