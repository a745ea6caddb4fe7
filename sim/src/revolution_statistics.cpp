#include "revolution_statistics.hpp"

#include <cmath>
#include <cstddef>
#include <utility>

#include "feedplan/core/angle.hpp"

namespace feedplan::sim::detail {

void RevolutionStatistics::add(double t_s, double spindle_angle_rad, double fxy_n) {
  const int rev_now = static_cast<int>(std::floor(spindle_angle_rad / kTwoPi + 1e-9));
  if (rev_now != revolution_ && steps_ > 0) {
    close_revolution(t_s);
    current_ = force_log::RevolutionPeak{};
    current_.revolution = rev_now;
    current_.t_start_s = t_s;
    sum_n_ = 0.0;
    steps_ = 0;
  }
  revolution_ = rev_now;
  if (fxy_n > current_.peak_xy_n || steps_ == 0) {
    current_.peak_xy_n = fxy_n;
    current_.t_peak_s = t_s;
  }
  sum_n_ += fxy_n;
  ++steps_;
}

std::vector<force_log::RevolutionPeak> RevolutionStatistics::finish(double t_end_s) {
  if (steps_ > 0) close_revolution(t_end_s);
  return std::move(revolutions_);
}

void RevolutionStatistics::close_revolution(double t_end_s) {
  current_.t_end_s = t_end_s;
  current_.mean_xy_n = sum_n_ / steps_;
  current_.samples = static_cast<std::size_t>(steps_);
  revolutions_.push_back(current_);
}

}  // namespace feedplan::sim::detail
