#include "feedplan/model/sensor_response.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "revolution_series.hpp"

namespace feedplan::model {
namespace {

//! H_m(ω) = ω_m² / (ω_m² − ω² + 2i ζ ω_m ω), written in r = f / f_m.
std::complex<double> mode_gain(const SensorMode& mode, double frequency_hz) {
  const double r = frequency_hz / mode.natural_frequency_hz;
  return 1.0 / std::complex<double>(1.0 - r * r, 2.0 * mode.damping_ratio * r);
}

}  // namespace

std::vector<InputProblem> validate(const SensorResponse& sensor, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  for (std::size_t m = 0; m < sensor.modes.size(); ++m) {
    const std::string mode = "modes[" + std::to_string(m) + "].";
    problems.positive(mode + "natural_frequency_hz", sensor.modes[m].natural_frequency_hz);
    const double zeta = sensor.modes[m].damping_ratio;
    if (!(zeta > 0.0 && zeta < 1.0)) {
      problems.add_value(mode + "damping_ratio", shortest_number_text(zeta), "must be in (0, 1)");
    }
  }
  problems.finite("mode_angle_deg", sensor.mode_angle_deg);
  return problems.take();
}

SensorGain sensor_gain(const SensorResponse& sensor, double frequency_hz) {
  assert(std::isfinite(frequency_hz) && frequency_hz >= 0.0);
  const double theta = sensor.mode_angle_deg * std::numbers::pi / 180.0;
  const double c = std::cos(theta), s = std::sin(theta);
  const std::complex<double> h0 = mode_gain(sensor.modes[0], frequency_hz);
  const std::complex<double> h1 = mode_gain(sensor.modes[1], frequency_hz);
  // Σ H_m d_m d_mᵀ with d_0 = (c, s), d_1 = (−s, c).
  SensorGain g;
  g.xy[0][0] = h0 * c * c + h1 * s * s;
  g.xy[1][1] = h0 * s * s + h1 * c * c;
  g.xy[0][1] = (h0 - h1) * c * s;
  g.xy[1][0] = g.xy[0][1];
  return g;
}

RevolutionForce sensed_revolution(const SensorResponse& sensor, double spindle_rpm, std::span<const double> fx_n,
                                  std::span<const double> fy_n) {
  assert(fx_n.size() == fy_n.size() && fx_n.size() >= 2);
  assert(std::isfinite(spindle_rpm) && spindle_rpm > 0.0);
  const int n = static_cast<int>(fx_n.size());
  detail::Harmonics x = detail::revolution_harmonics(fx_n), y = detail::revolution_harmonics(fy_n);
  detail::apply_sensor(sensor, spindle_rpm / 60.0, x, y);
  return {detail::series_samples(x, n), detail::series_samples(y, n)};
}

}  // namespace feedplan::model
