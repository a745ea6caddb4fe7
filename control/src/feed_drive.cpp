#include "feedplan/control/feed_drive.hpp"

#include <cassert>
#include <cmath>

#include "feedplan/core/problem_list.hpp"

namespace feedplan::control {
namespace {

//! The weights of the file comment for T_d = N T + δ.
struct DriveWeights {
  double alpha = 0.0;
  double older = 0.0;
  double newer = 0.0;
  std::size_t delay_periods = 0;  // N
};

DriveWeights drive_weights(const FeedDriveParameters& parameters, double period_s) {
  const double tau = 1.0 / parameters.bandwidth_rad_per_s;
  const double periods = std::floor(parameters.dead_time_s / period_s);
  const double delta = parameters.dead_time_s - periods * period_s;
  DriveWeights w;
  w.alpha = std::exp(-period_s / tau);
  w.older = std::exp(-(period_s - delta) / tau) * (1.0 - std::exp(-delta / tau));
  w.newer = 1.0 - std::exp(-(period_s - delta) / tau);
  w.delay_periods = static_cast<std::size_t>(periods);
  return w;
}

}  // namespace

std::vector<InputProblem> validate(const FeedDriveParameters& parameters, double period_s,
                                   const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  problems.positive("bandwidth_rad_per_s", parameters.bandwidth_rad_per_s);
  problems.non_negative("dead_time_s", parameters.dead_time_s);
  problems.positive("period_s", period_s);
  return problems.take();
}

std::optional<ArmaModel> arma_equivalent(const FeedDriveParameters& parameters, double period_s,
                                         double force_gain_n_per_mm_per_min) {
  assert(validate(parameters, period_s).empty());
  const DriveWeights w = drive_weights(parameters, period_s);
  if (w.delay_periods > 0) return std::nullopt;
  return ArmaModel{-w.alpha, 0.0, force_gain_n_per_mm_per_min * w.newer, force_gain_n_per_mm_per_min * w.older};
}

FeedDriveProcess::FeedDriveProcess(const FeedDriveParameters& parameters, double period_s,
                                   double force_gain_n_per_mm_per_min, double initial_feed_mm_per_min) {
  ProblemList problems("feed_drive.");
  problems.add_all(validate(parameters, period_s));
  problems.non_negative("force_gain_n_per_mm_per_min", force_gain_n_per_mm_per_min);
  problems.non_negative("initial_feed_mm_per_min", initial_feed_mm_per_min);
  problems.throw_if_any();
  const DriveWeights w = drive_weights(parameters, period_s);
  alpha_ = w.alpha;
  gain_older_ = w.older;
  gain_newer_ = w.newer;
  commands_.assign(w.delay_periods + 2, initial_feed_mm_per_min);
  force_gain_ = force_gain_n_per_mm_per_min;
  actual_mm_per_min_ = initial_feed_mm_per_min;
}

void FeedDriveProcess::set_force_gain(double force_gain_n_per_mm_per_min) {
  assert(std::isfinite(force_gain_n_per_mm_per_min) && force_gain_n_per_mm_per_min >= 0.0);
  force_gain_ = force_gain_n_per_mm_per_min;
}

double FeedDriveProcess::step(double command_mm_per_min) {
  assert(std::isfinite(command_mm_per_min));
  commands_.erase(commands_.begin());
  commands_.push_back(command_mm_per_min);
  // commands_ holds v_c(k−N−1) … v_c(k): the first two are the delayed commands of the recursion.
  actual_mm_per_min_ = alpha_ * actual_mm_per_min_ + gain_older_ * commands_[0] + gain_newer_ * commands_[1];
  return force_n();
}

}  // namespace feedplan::control
