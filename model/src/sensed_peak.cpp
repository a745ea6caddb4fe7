#include "feedplan/model/sensed_peak.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

#include "feedplan/model/mechanistic_force.hpp"
#include "revolution_series.hpp"

namespace feedplan::model {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kColumns = 6;
//! Local maxima of the sampled reading refined, those within kCandidateBand of the largest sample.
constexpr int kCandidates = 4;
constexpr double kCandidateBand = 0.9;
constexpr int kGoldenIterations = 40;  // 0.5° bracket × 0.618⁴⁰: far below 1e-9 rad

//! The reading's Fourier series: the sensed regressor columns weighted by the coefficients.
struct SensedSeries {
  detail::Harmonics x, y;
  double magnitude(double angle_rad) const {
    return std::hypot(detail::series_value(x, kSensedPeakSamples, angle_rad),
                      detail::series_value(y, kSensedPeakSamples, angle_rad));
  }
};

}  // namespace

SensedPeak predicted_sensed_peak(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                 const CutterGeometry& cutter, double feed_per_tooth_mm, const SensorResponse& sensor,
                                 double spindle_rpm) {
  assert(std::isfinite(spindle_rpm) && spindle_rpm > 0.0);
  constexpr int n = kSensedPeakSamples;
  const double step_rad = kTwoPi / n;
  // Columns of the regressors over the revolution, [axis][column][sample].
  std::vector<double> columns[2][kColumns];
  for (auto& axis : columns) {
    for (auto& column : axis) column.resize(n);
  }
  SensedPeak peak;
  const std::array<double, 6> k = coefficients(model);
  std::vector<double> angles_rad(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) angles_rad[static_cast<std::size_t>(j)] = j * step_rad;
  const std::vector<ForceRegressors> samples = regressors_at_angles(model, sections, cutter, feed_per_tooth_mm, angles_rad);
  for (int j = 0; j < n; ++j) {
    const ForceRegressors& r = samples[static_cast<std::size_t>(j)];
    double f[2] = {0.0, 0.0};
    for (int axis = 0; axis < 2; ++axis) {
      for (int c = 0; c < kColumns; ++c) {
        columns[axis][c][static_cast<std::size_t>(j)] = r.rows[static_cast<std::size_t>(axis)][static_cast<std::size_t>(c)];
        f[axis] += r.rows[static_cast<std::size_t>(axis)][static_cast<std::size_t>(c)] * k[static_cast<std::size_t>(c)];
      }
    }
    peak.force_peak_n = std::max(peak.force_peak_n, std::hypot(f[0], f[1]));
  }
  detail::Harmonics sensed[2][kColumns];
  SensedSeries reading;
  reading.x.assign(n / 2 + 1, 0.0);
  reading.y.assign(n / 2 + 1, 0.0);
  for (int c = 0; c < kColumns; ++c) {
    sensed[0][c] = detail::revolution_harmonics(columns[0][c]);
    sensed[1][c] = detail::revolution_harmonics(columns[1][c]);
    detail::apply_sensor(sensor, spindle_rpm / 60.0, sensed[0][c], sensed[1][c]);
    for (std::size_t h = 0; h < reading.x.size(); ++h) {
      reading.x[h] += k[static_cast<std::size_t>(c)] * sensed[0][c][h];
      reading.y[h] += k[static_cast<std::size_t>(c)] * sensed[1][c][h];
    }
  }
  const std::vector<double> x = detail::series_samples(reading.x, n), y = detail::series_samples(reading.y, n);
  std::vector<double> magnitude(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) magnitude[static_cast<std::size_t>(j)] = std::hypot(x[static_cast<std::size_t>(j)], y[static_cast<std::size_t>(j)]);
  const double largest = *std::max_element(magnitude.begin(), magnitude.end());
  if (!(largest > 0.0)) return peak;

  // Local maxima of the samples (circularly), the largest first.
  std::vector<int> maxima;
  for (int j = 0; j < n; ++j) {
    const double m = magnitude[static_cast<std::size_t>(j)];
    if (m >= kCandidateBand * largest && m >= magnitude[static_cast<std::size_t>((j + n - 1) % n)] &&
        m >= magnitude[static_cast<std::size_t>((j + 1) % n)]) {
      maxima.push_back(j);
    }
  }
  std::sort(maxima.begin(), maxima.end(),
            [&](int a, int b) { return magnitude[static_cast<std::size_t>(a)] > magnitude[static_cast<std::size_t>(b)]; });
  if (maxima.size() > static_cast<std::size_t>(kCandidates)) maxima.resize(kCandidates);
  const double g = (std::sqrt(5.0) - 1.0) / 2.0;
  double best_angle = 0.0, best = -1.0;
  for (int j : maxima) {
    double lo = (j - 1) * step_rad, hi = (j + 1) * step_rad;
    double p1 = hi - g * (hi - lo), p2 = lo + g * (hi - lo);
    double m1 = reading.magnitude(p1), m2 = reading.magnitude(p2);
    for (int i = 0; i < kGoldenIterations; ++i) {
      if (m1 > m2) {
        hi = p2, p2 = p1, m2 = m1;
        p1 = hi - g * (hi - lo);
        m1 = reading.magnitude(p1);
      } else {
        lo = p1, p1 = p2, m1 = m2;
        p2 = lo + g * (hi - lo);
        m2 = reading.magnitude(p2);
      }
    }
    // The refined point, or the sample itself should the series dip between samples.
    double angle = 0.5 * (lo + hi), value = reading.magnitude(angle);
    if (magnitude[static_cast<std::size_t>(j)] > value) angle = j * step_rad, value = magnitude[static_cast<std::size_t>(j)];
    if (value > best) best = value, best_angle = angle;
  }
  best_angle -= kTwoPi * std::floor(best_angle / kTwoPi);
  peak.force_n = best;
  peak.spindle_angle_rad = best_angle;
  for (int axis = 0; axis < 2; ++axis) {
    for (int c = 0; c < kColumns; ++c) {
      peak.regressors[static_cast<std::size_t>(axis)][static_cast<std::size_t>(c)] =
          detail::series_value(sensed[axis][c], n, best_angle);
    }
  }
  return peak;
}

}  // namespace feedplan::model
