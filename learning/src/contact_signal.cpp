#include "contact_signal.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "feedplan/force_log/logged_spindle_speed.hpp"
#include "log_rows.hpp"
#include "sampled_signal.hpp"

namespace feedplan::learning::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The tool is in contact where the measured peak envelope exceeds this share of its (robust) maximum.
constexpr double kContactFraction = 0.03;
// The noise's envelope out of the cut is raised by this factor to make the contact threshold: its 99.5th
// percentile is not its largest value, and a stretch of air read as contact moves the contact edge.
constexpr double kNoiseEnvelopeMargin = 1.25;

}  // namespace

std::vector<double> force_xy(const force_log::ForceLog& log) {
  std::vector<double> f(log.rows.size(), kNaN);
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    if (finite_force(log.rows[i])) f[i] = std::hypot(log.rows[i].fx_n, log.rows[i].fy_n);
  }
  return f;
}

double spindle_rpm_for(const force_log::ForceLog& log, const planner::PlanResult& plan) {
  if (const double logged = logged_spindle_rpm(log); logged > 0.0) return logged;
  double most = 0.0;
  for (const auto& block : plan.program.blocks) most = std::max(most, block.spindle_rpm);
  return most;
}

int revolution_bins(double rpm, double bin_s) {
  return rpm > 0.0 ? 2 * static_cast<int>(0.5 * (60.0 / rpm) / bin_s) + 1 : 1;
}

double noise_envelope_n(const std::vector<double>& envelope, int width, const std::vector<double>& in_air) {
  std::vector<double> air;
  for (std::size_t i = 0; i < envelope.size() && i < in_air.size(); ++i) {
    if (in_air[i] == 1.0 && std::isfinite(envelope[i])) air.push_back(envelope[i]);
  }
  if (air.size() < 4 * static_cast<std::size_t>(std::max(width, 1))) return 0.0;
  const std::size_t k = static_cast<std::size_t>(0.995 * static_cast<double>(air.size() - 1));
  std::nth_element(air.begin(), air.begin() + static_cast<long>(k), air.end());
  return kNoiseEnvelopeMargin * air[k];
}

std::vector<double> in_contact(const std::vector<double>& force_bins, int width, double noise_level_n) {
  return contact_of_envelope(moving_max(force_bins, width), noise_level_n);
}

std::vector<double> contact_of_envelope(std::vector<double> envelope, double noise_level_n) {
  std::vector<double> finite;
  for (double v : envelope) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  if (finite.empty()) return envelope;
  const std::size_t k = static_cast<std::size_t>(0.999 * static_cast<double>(finite.size() - 1));
  std::nth_element(finite.begin(), finite.begin() + static_cast<long>(k), finite.end());
  const double threshold = std::max(kContactFraction * finite[k], noise_level_n);
  for (double& v : envelope) {
    if (std::isfinite(v)) v = v > threshold ? 1.0 : 0.0;
  }
  return envelope;
}

}  // namespace feedplan::learning::detail
