#include "revolution_series.hpp"

#include <cassert>
#include <cmath>
#include <numbers>

namespace feedplan::model::detail {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

//! a_k of the series (see the header).
double series_weight(int k, int samples) { return k == 0 || 2 * k == samples ? 1.0 : 2.0; }

}  // namespace

Harmonics revolution_harmonics(std::span<const double> samples) {
  const int n = static_cast<int>(samples.size());
  assert(n >= 1);
  std::vector<std::complex<double>> root(static_cast<std::size_t>(n));
  for (int m = 0; m < n; ++m) root[static_cast<std::size_t>(m)] = std::polar(1.0, -kTwoPi * m / n);
  Harmonics c(static_cast<std::size_t>(n / 2 + 1));
  for (int k = 0; k <= n / 2; ++k) {
    std::complex<double> sum = 0.0;
    for (int j = 0; j < n; ++j) sum += samples[static_cast<std::size_t>(j)] * root[static_cast<std::size_t>((k * j) % n)];
    c[static_cast<std::size_t>(k)] = sum / static_cast<double>(n);
  }
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
  const int n = samples;
  std::vector<std::complex<double>> root(static_cast<std::size_t>(n));
  for (int m = 0; m < n; ++m) root[static_cast<std::size_t>(m)] = std::polar(1.0, kTwoPi * m / n);
  std::vector<double> x(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j) {
    double value = 0.0;
    for (int k = 0; k < static_cast<int>(harmonics.size()); ++k) {
      value += series_weight(k, n) *
               (harmonics[static_cast<std::size_t>(k)] * root[static_cast<std::size_t>((k * j) % n)]).real();
    }
    x[static_cast<std::size_t>(j)] = value;
  }
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
