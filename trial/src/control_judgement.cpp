#include "feedplan/trial/control_judgement.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace feedplan::trial {

ControlJudgement judge_control(const std::vector<force_log::RevolutionPeak>& revolutions, double target_force_n,
                               double cycle_time_s) {
  assert(target_force_n > 0.0);
  ControlJudgement judgement;
  judgement.target_force_n = target_force_n;
  judgement.cycle_time_s = cycle_time_s;
  double squares = 0.0;
  int within = 0;
  for (const force_log::RevolutionPeak& rev : revolutions) {
    judgement.max_peak_n = std::max(judgement.max_peak_n, rev.peak_xy_n);
    if (rev.peak_xy_n > target_force_n) judgement.time_above_target_s += rev.t_end_s - rev.t_start_s;
    if (rev.peak_xy_n < kJudgedInCutFraction * target_force_n) continue;
    const double error_n = rev.peak_xy_n - target_force_n;
    ++judgement.in_cut_revolutions;
    squares += error_n * error_n;
    if (std::abs(error_n) <= 0.05 * target_force_n) ++within;
  }
  judgement.max_overshoot_percent = (judgement.max_peak_n / target_force_n - 1.0) * 100.0;
  if (judgement.in_cut_revolutions > 0) {
    const double n = judgement.in_cut_revolutions;
    judgement.rms_error_n = std::sqrt(squares / n);
    judgement.rms_error_percent = judgement.rms_error_n / target_force_n * 100.0;
    judgement.within_5_percent_share = within / n;
  }
  return judgement;
}

}  // namespace feedplan::trial
