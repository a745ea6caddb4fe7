#include "feedplan/trial/depth_step_errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace feedplan::trial {

void PositionTrack::begin(const force_log::ForceLog&) {
  t_s_.clear();
  x_mm_.clear();
}

void PositionTrack::add(const force_log::ForceLogRow& row) {
  t_s_.push_back(row.t_s);
  x_mm_.push_back(row.x_mm);
}

double PositionTrack::x_at(double t_s) const {
  const auto after = std::upper_bound(t_s_.begin(), t_s_.end(), t_s);
  if (after == t_s_.begin()) return std::numeric_limits<double>::quiet_NaN();
  return x_mm_[static_cast<std::size_t>(after - t_s_.begin()) - 1];
}

std::vector<DepthSteadyError> depth_steady_errors(const DepthStepSlot& slot,
                                                  const std::vector<force_log::RevolutionPeak>& revolutions,
                                                  const PositionTrack& track, double target_force_n) {
  std::vector<DepthSteadyError> out;
  std::vector<double> sums;
  for (const DepthSegment& segment : slot.segments) {
    out.push_back({segment.depth_mm, segment.steady_from_x_mm, segment.end_x_mm, 0, 0.0, 0.0});
    sums.push_back(0.0);
  }
  for (const force_log::RevolutionPeak& revolution : revolutions) {
    const double x = track.x_at(revolution.t_end_s);
    if (!std::isfinite(x)) continue;
    for (std::size_t i = 0; i < out.size(); ++i) {
      if (x < out[i].from_x_mm || x > out[i].to_x_mm) continue;
      const double error_n = revolution.peak_xy_n - target_force_n;
      ++out[i].revolutions;
      sums[i] += error_n;
      out[i].max_abs_error_n = std::max(out[i].max_abs_error_n, std::abs(error_n));
    }
  }
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (out[i].revolutions > 0) out[i].mean_error_n = sums[i] / out[i].revolutions;
  }
  return out;
}

}  // namespace feedplan::trial
