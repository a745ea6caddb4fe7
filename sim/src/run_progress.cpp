#include "run_progress.hpp"

#include <algorithm>

namespace feedplan::sim::detail {

namespace {

// Rough cost of the work units relative to each other, µs on one core: one engagement sample (the
// planner's engagement runs at about 4 µs per sample on the pocket); one internal step, plus its
// share per stock layer.
constexpr double kEngagementSampleUs = 5.0;
constexpr double kStepUs = 1.0;
constexpr double kStepLayerUs = 0.1;

}  // namespace

RunProgress::RunProgress(const std::function<void(double)>& report, long long total_steps, int layers, double ds_mm)
    : report_(report),
      step_work_(static_cast<double>(total_steps) * (kStepUs + kStepLayerUs * std::max(layers, 0))),
      ds_mm_(ds_mm) {}

void RunProgress::engagement(double done_mm, double total_mm) {
  engagement_done_ = done_mm / ds_mm_ * kEngagementSampleUs;
  engagement_total_ = total_mm / ds_mm_ * kEngagementSampleUs;
  update();
}

void RunProgress::motion(double fraction) {
  motion_fraction_ = std::clamp(fraction, 0.0, 1.0);
  update();
}

void RunProgress::finish() {
  if (report_) report_(1.0);
}

void RunProgress::update() {
  if (!report_) return;
  const double total = engagement_total_ + step_work_;
  const double done = total > 0.0 ? (engagement_done_ + motion_fraction_ * step_work_) / total : 0.0;
  if (done >= next_report_ && done < 1.0) {
    report_(done);
    next_report_ = done + 0.01;
  }
}

}  // namespace feedplan::sim::detail
