#include "feedplan/planner/feed_prediction.hpp"

#include <algorithm>
#include <cassert>

#include "feedplan/planner/controller_model.hpp"
#include "feedplan/planner/sample_force_model.hpp"

namespace feedplan::planner {

FeedPrediction predict_feeds(const PlanGeometry& geometry, const PlanSettings& settings,
                             const std::vector<double>& move_feed_mm_per_min, double accel_mm_per_s2) {
  assert(move_feed_mm_per_min.size() == geometry.path.moves.size());
  const auto& samples = geometry.engagement.samples;
  FeedPrediction out;
  out.time_s.assign(samples.size(), 0.0);
  out.force_n.assign(samples.size(), 0.0);
  if (samples.size() < 2) return out;
  const std::vector<double> centripetal =
      centripetal_caps_mm_per_s(geometry.path, geometry.engagement, settings.machine.max_accel_mm_per_s2);
  std::vector<double> s_mm(samples.size());
  std::vector<double> caps(samples.size() - 1);
  std::vector<bool> cutting(samples.size() - 1);
  for (std::size_t i = 0; i < samples.size(); ++i) s_mm[i] = samples[i].s_mm;
  for (std::size_t j = 0; j + 1 < samples.size(); ++j) {
    const auto move = static_cast<std::size_t>(samples[j].move_index);
    const bool rapid = geometry.path.moves[move].kind == geometry::MoveKind::kRapid;
    caps[j] = rapid ? settings.machine.rapid_feed_mm_per_min / 60.0
                    : std::min(move_feed_mm_per_min[move] / 60.0, centripetal[j]);
    cutting[j] = samples[j].cutting;
  }
  const ControllerRun run =
      run_controller(s_mm, caps, controller_stops(geometry.path, geometry.engagement), cutting, accel_mm_per_s2);
  out.cycle_time_s = run.cycle_time_s;
  out.cutting_time_s = run.cutting_time_s;
  out.time_s = run.time_s;
  const SampleForceModel forces(settings.model, settings.mechanistic ? &*settings.mechanistic : nullptr,
                                geometry.engagement, geometry.tool);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double correction = settings.force_correction.empty() ? 1.0 : settings.force_correction[i];
    out.force_n[i] = correction * forces.predicted_force_n(samples[i], forces.load_ratio(samples[i]),
                                                           run.speed_mm_per_s[i] * 60.0, geometry.tool.flutes,
                                                           settings.spindle_rpm);
    out.peak_force_n = std::max(out.peak_force_n, out.force_n[i]);
  }
  return out;
}

}  // namespace feedplan::planner
