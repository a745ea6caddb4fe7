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
// The tool is in contact where the measured peak envelope exceeds this share of its (robust) maximum …
constexpr double kContactFraction = 0.03;
// … and this multiple of the envelope's level out of the cut (its 5th percentile: every program moves in air
// somewhere), where the sensor's noise alone sets it: a dynamometer with 9 N of noise per axis has a peak
// envelope of 15–20 N in air, over 3 % of a 500 N maximum, and took the whole log for contact.
constexpr double kNoiseEnvelopeFactor = 2.0;
constexpr double kNoiseQuantile = 0.05;
// … but never above this share of the maximum (a log cut throughout has no air to measure the noise in).
constexpr double kMaxContactFraction = 0.3;

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

std::vector<double> in_contact(const std::vector<double>& force_bins, int width) {
  std::vector<double> envelope = moving_max(force_bins, width);
  std::vector<double> finite;
  for (double v : envelope) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  if (finite.empty()) return envelope;
  const auto quantile = [&finite](double q) {
    const std::size_t k = static_cast<std::size_t>(q * static_cast<double>(finite.size() - 1));
    std::nth_element(finite.begin(), finite.begin() + static_cast<long>(k), finite.end());
    return finite[k];
  };
  const double maximum = quantile(0.999);
  const double noise_envelope = quantile(kNoiseQuantile);
  const double threshold =
      std::max(kContactFraction * maximum, std::min(kNoiseEnvelopeFactor * noise_envelope, kMaxContactFraction * maximum));
  for (double& v : envelope) {
    if (std::isfinite(v)) v = v > threshold ? 1.0 : 0.0;
  }
  return envelope;
}

}  // namespace feedplan::learning::detail
