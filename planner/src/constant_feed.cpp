#include "feedplan/planner/sample_force_model.hpp"
#include "feedplan/planner/constant_feed.hpp"

#include <algorithm>
#include <cassert>

#include "feedplan/planner/controller_model.hpp"
#include "feedplan/planner/feed_limit.hpp"

namespace feedplan::planner {

geometry::Program constant_feed_program(const geometry::ToolPath& path, double feed_mm_per_min, double spindle_rpm) {
  geometry::Program program;
  program.path = path;
  for (const geometry::Move& move : path.moves) {
    geometry::BlockCommand block;
    block.feed_mm_per_min = move.kind == geometry::MoveKind::kRapid ? 0.0 : feed_mm_per_min;
    block.spindle_rpm = spindle_rpm;
    block.spindle = geometry::SpindleDirection::kClockwise;
    program.blocks.push_back(block);
  }
  return program;
}

ConstantFeedPrediction predict_constant_feed(const PlanGeometry& geometry, const PlanSettings& settings,
                                             double feed_mm_per_min, double accel_mm_per_s2) {
  assert(feed_mm_per_min > 0.0);
  const auto& samples = geometry.engagement.samples;
  ConstantFeedPrediction out;
  out.feed_mm_per_min = feed_mm_per_min;
  if (samples.size() < 2) return out;
  const std::vector<double> centripetal =
      centripetal_caps_mm_per_s(geometry.path, geometry.engagement, settings.machine.max_accel_mm_per_s2);
  std::vector<double> s_mm(samples.size());
  std::vector<double> caps(samples.size() - 1);
  std::vector<bool> cutting(samples.size() - 1);
  for (std::size_t i = 0; i < samples.size(); ++i) s_mm[i] = samples[i].s_mm;
  for (std::size_t j = 0; j + 1 < samples.size(); ++j) {
    const bool rapid = geometry.path.moves[static_cast<std::size_t>(samples[j].move_index)].kind == geometry::MoveKind::kRapid;
    caps[j] = rapid ? settings.machine.rapid_feed_mm_per_min / 60.0 : std::min(feed_mm_per_min / 60.0, centripetal[j]);
    cutting[j] = samples[j].cutting;
  }
  const ControllerRun run =
      run_controller(s_mm, caps, controller_stops(geometry.path, geometry.engagement), cutting, accel_mm_per_s2);
  out.cycle_time_s = run.cycle_time_s;
  out.cutting_time_s = run.cutting_time_s;
  const SampleForceModel forces(settings.model, settings.mechanistic ? &*settings.mechanistic : nullptr,
                                geometry.engagement, geometry.tool);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const double correction = settings.force_correction.empty() ? 1.0 : settings.force_correction[i];
    out.peak_force_n = std::max(out.peak_force_n, correction * forces.predicted_force_n(samples[i], forces.load_ratio(samples[i]),
                                                                                        run.speed_mm_per_s[i] * 60.0,
                                                                                        geometry.tool.flutes,
                                                                                        settings.spindle_rpm));
  }
  return out;
}

}  // namespace feedplan::planner
