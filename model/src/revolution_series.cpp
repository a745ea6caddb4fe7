#include "revolution_series.hpp"

#include <cassert>
#include <cmath>

#include <unsupported/Eigen/FFT>

namespace feedplan::model::detail {
namespace {

//! a_k of the series (see the header).
double series_weight(int k, int samples) { return k == 0 || 2 * k == samples ? 1.0 : 2.0; }

}  // namespace

Harmonics revolution_harmonics(std::span<const double> samples) {
  const std::size_t n = samples.size();
  assert(n >= 1);
  const std::vector<double> input(samples.begin(), samples.end());
  std::vector<std::complex<double>> spectrum;
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, input);
  Harmonics c(n / 2 + 1);
  for (std::size_t k = 0; k < c.size(); ++k) c[k] = spectrum[k] / static_cast<double>(n);
  return c;
}

double series_value(const Harmonics& harmonics, int samples, double angle_rad) {
  double value = 0.0;
  for (int k = 0; k < static_cast<int>(harmonics.size()); ++k) {
    value += series_weight(k, samples) * (harmonics[static_cast<std::size_t>(k)] * std::polar(1.0, k * angle_rad)).real();
  }
  return value;
}

std::vector<double> series_samples(const Harmonics& harmonics, int samples) {
  const std::size_t n = static_cast<std::size_t>(samples);
  assert(harmonics.size() == n / 2 + 1);
  // The full spectrum of the real series: c_k and its conjugate at n − k, the ends (k = 0, k = n/2 of an
  // even n) by their real parts, as the series takes them.
  std::vector<std::complex<double>> spectrum(n);
  const double scale = static_cast<double>(n);
  for (std::size_t k = 0; k < harmonics.size(); ++k) {
    const bool end = k == 0 || 2 * k == n;
    const std::complex<double> c = end ? std::complex<double>(harmonics[k].real(), 0.0) : harmonics[k];
    spectrum[k] = scale * c;
    if (!end) spectrum[n - k] = scale * std::conj(c);
  }
  std::vector<std::complex<double>> values;
  Eigen::FFT<double> fft;
  fft.inv(values, spectrum);  // divides by n
  std::vector<double> x(n);
  for (std::size_t j = 0; j < n; ++j) x[j] = values[j].real();
  return x;
}

void apply_sensor(const SensorResponse& sensor, double revolution_hz, Harmonics& x, Harmonics& y) {
  assert(x.size() == y.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    const SensorGain g = sensor_gain(sensor, static_cast<double>(k) * revolution_hz);
    const std::complex<double> fx = x[k], fy = y[k];
    x[k] = g.xy[0][0] * fx + g.xy[0][1] * fy;
    y[k] = g.xy[1][0] * fx + g.xy[1][1] * fy;
  }
}

}  // namespace feedplan::model::detail
