// The revolution-synchronous average against the closed form of a known force: four tooth pulses per
// turn (cos 4θ) and a once-per-turn component (runout, cos θ), sampled at 10 kHz at 2800 rpm over 60
// revolutions with 8 N of noise. The mean of cos kθ over a bin [θ_c − Δ/2, θ_c + Δ/2] is
// cos kθ_c · sin(kΔ/2) / (kΔ/2).

#include "feedplan/force_log/synchronous_average.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace feedplan::force_log {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRpm = 2800.0;

double bin_mean_of_cos(int k, double centre_rad, double width_rad) {
  const double half = 0.5 * k * width_rad;
  return std::cos(k * centre_rad) * std::sin(half) / half;
}

struct Signal {
  std::vector<double> t, fx, fy;
};

Signal tooth_pulses(double noise_n, int revolutions) {
  Signal s;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, noise_n);
  const double rate_hz = 10000.0;
  const double omega = kRpm / 60.0 * 2.0 * kPi;
  const int n = static_cast<int>(revolutions * 60.0 / kRpm * rate_hz);
  for (int i = 0; i < n; ++i) {
    const double t = i / rate_hz;
    const double theta = omega * t;
    s.t.push_back(t);
    s.fx.push_back(300.0 + 100.0 * std::cos(4.0 * theta) + 20.0 * std::cos(theta) + noise(rng));
    s.fy.push_back(-50.0 + 60.0 * std::cos(4.0 * theta) + noise(rng));
  }
  return s;
}

TEST(SynchronousAverage, MatchesTheClosedFormBinMeans) {
  const Signal s = tooth_pulses(8.0, 60);
  const auto revolutions = revolution_peaks(s.t, s.fx, s.fy, kRpm);
  ASSERT_GE(revolutions.size(), 55u);
  const int bins = 36;
  const SynchronousAverage a = synchronous_average(s.t, s.fx, s.fy, revolutions, bins);
  ASSERT_EQ(a.fx_n.size(), static_cast<std::size_t>(bins));
  EXPECT_EQ(a.revolutions, static_cast<int>(revolutions.size()));
  const double width = 2.0 * kPi / bins;
  for (int b = 0; b < bins; ++b) {
    const double centre = (b + 0.5) * width;
    const double fx = 300.0 + 100.0 * bin_mean_of_cos(4, centre, width) + 20.0 * bin_mean_of_cos(1, centre, width);
    const double fy = -50.0 + 60.0 * bin_mean_of_cos(4, centre, width);
    // Noise 8 / √(60 · 5.9) ≈ 0.4 N; six samples stand for a bin's continuous mean within about 1 N.
    EXPECT_NEAR(a.fx_n[static_cast<std::size_t>(b)], fx, 2.0) << "bin " << b;
    EXPECT_NEAR(a.fy_n[static_cast<std::size_t>(b)], fy, 2.0) << "bin " << b;
  }
}

TEST(SynchronousAverage, BinsAreLoweredToTheSamplesOfARevolution) {
  const Signal s = tooth_pulses(0.0, 10);  // about 214 samples per revolution
  const auto revolutions = revolution_peaks(s.t, s.fx, s.fy, kRpm);
  const SynchronousAverage a = synchronous_average(s.t, s.fx, s.fy, revolutions, 1000);
  EXPECT_LE(a.fx_n.size(), 107u);  // half the samples of the shortest revolution
  EXPECT_GE(a.fx_n.size(), 100u);
  for (double v : a.fx_n) EXPECT_TRUE(std::isfinite(v));
}

TEST(SynchronousAverage, NothingFromNoRevolutionsOrTooFewSamples) {
  const Signal s = tooth_pulses(0.0, 5);
  EXPECT_TRUE(synchronous_average(s.t, s.fx, s.fy, {}).fx_n.empty());
  const auto revolutions = revolution_peaks(s.t, s.fx, s.fy, kRpm);
  EXPECT_TRUE(synchronous_average(s.t, s.fx, s.fy, revolutions, 3).fx_n.empty());  // fewer than 4 bins
}

}  // namespace
}  // namespace feedplan::force_log
