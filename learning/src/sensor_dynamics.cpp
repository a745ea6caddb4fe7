#include "feedplan/learning/sensor_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include <unsupported/Eigen/FFT>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/chip_load.hpp"

namespace feedplan::learning {

namespace {

// H(iω) of the sensor at frequency f (Hz; negative frequencies give the conjugate).
std::complex<double> response(double f_hz, const SensorDynamics& sensor) {
  const double r = f_hz / sensor.natural_frequency_hz;
  return 1.0 / std::complex<double>(1.0 - r * r, 2.0 * sensor.damping_ratio * r);
}

}  // namespace

void check_sensor_dynamics(const SensorDynamics& sensor, const std::string& frequency_field,
                           const std::string& damping_field) {
  std::vector<InputProblem> problems;
  if (!(std::isfinite(sensor.natural_frequency_hz) && sensor.natural_frequency_hz > 0.0)) {
    problems.push_back({frequency_field, "= " + shortest_number_text(sensor.natural_frequency_hz) +
                                             ": must be the sensor's natural frequency in Hz (> 0)"});
  }
  if (!(sensor.damping_ratio > 0.0 && sensor.damping_ratio <= 2.0)) {
    problems.push_back({damping_field, "= " + shortest_number_text(sensor.damping_ratio) +
                                           ": must be the sensor's damping ratio, in (0, 2]"});
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

double periodic_peak_gain(const std::vector<double>& waveform, double fundamental_hz, const SensorDynamics& sensor) {
  const std::size_t n = waveform.size();
  const double peak = n < 2 ? 0.0 : *std::max_element(waveform.begin(), waveform.end());
  if (!(peak > 0.0)) return 1.0;
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, waveform);
  for (std::size_t k = 0; k < n; ++k) {
    // Harmonic k, or −(n − k) above the middle (the conjugate half of a real signal's spectrum).
    const double harmonic = k <= n / 2 ? static_cast<double>(k) : static_cast<double>(k) - static_cast<double>(n);
    spectrum[k] *= response(harmonic * fundamental_hz, sensor);
  }
  std::vector<std::complex<double>> reading;
  fft.inv(reading, spectrum);
  double read_peak = 0.0;
  for (const auto& y : reading) read_peak = std::max(read_peak, y.real());
  return read_peak / peak;
}

std::vector<double> sensor_peak_gains(const geometry::EngagementProfile& profile, const geometry::Tool& tool,
                                      double spindle_rpm, const SensorDynamics& sensor) {
  const double tooth_hz = spindle_rpm * tool.flutes / 60.0;
  std::vector<double> gains(profile.samples.size(), 1.0);
  for (std::size_t i = 0; i < profile.samples.size(); ++i) {
    const geometry::EngagementSample& sample = profile.samples[i];
    if (sample.layer_count == 0) continue;
    gains[i] = std::min(periodic_peak_gain(geometry::chip_load_waveform_mm(profile, sample, tool), tooth_hz, sensor),
                        kMaxSensorPeakGain);
  }
  return gains;
}

}  // namespace feedplan::learning
