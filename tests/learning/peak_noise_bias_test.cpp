// peak_noise on a synthetic log whose noise-free force is known: tooth pulses (a half sine per tooth
// period, 400 N) sampled at 10 kHz, with Gaussian noise of a chosen spread and row-to-row correlation, and
// an air stretch of noise alone. Oracle: the excess of the peak reading over the true peak, simulated here
// on the noise-free pulses themselves (which the estimate never sees) with the noise the log was made with.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "feedplan/learning/peak_noise_bias.hpp"

namespace feedplan::learning {
namespace {

constexpr double kRowStepS = 1e-4;
constexpr double kToothPeriodS = 60.0 / (2800.0 * 4);  // 4 flutes at 2800 rpm
constexpr double kPi = 3.14159265358979323846;

// The noise-free force at t (cutting from t_cut_s on): one pulse per tooth period over its first half,
// rotating with the tooth so that x and y both carry it.
void true_force(double t, double t_cut_s, double& fx, double& fy) {
  fx = fy = 0.0;
  if (t < t_cut_s) return;
  const double phase = std::fmod(t - t_cut_s, kToothPeriodS) / kToothPeriodS;
  if (phase > 0.5) return;
  const double magnitude = 400.0 * std::sin(2.0 * kPi * phase);
  const double angle = 2.0 * kPi * phase;
  fx = magnitude * std::cos(angle);
  fy = magnitude * std::sin(angle);
}

struct Noise {
  double sigma_n;
  double lag1;
};

// AR(1) noise per axis with the given spread and correlation.
class NoiseSeries {
 public:
  NoiseSeries(Noise noise, unsigned seed) : noise_(noise), random_(seed) {
    x_ = noise.sigma_n * normal_(random_);
    y_ = noise.sigma_n * normal_(random_);
  }
  void next(double& nx, double& ny) {
    nx = x_;
    ny = y_;
    const double innovation = noise_.sigma_n * std::sqrt(1.0 - noise_.lag1 * noise_.lag1);
    x_ = noise_.lag1 * x_ + innovation * normal_(random_);
    y_ = noise_.lag1 * y_ + innovation * normal_(random_);
  }

 private:
  Noise noise_;
  std::mt19937 random_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  double x_ = 0.0, y_ = 0.0;
};

struct SyntheticLog {
  std::vector<double> t, fx, fy;
  std::vector<force_log::RevolutionPeak> air, periods;
};

// 0.2 s of air, then 1 s of cutting, windows of one tooth period each.
SyntheticLog make_log(Noise noise) {
  SyntheticLog log;
  const double t_cut_s = 0.2;
  NoiseSeries series(noise, 7u);
  for (double t = 0.0; t < 1.2; t += kRowStepS) {
    double fx, fy, nx, ny;
    true_force(t, t_cut_s, fx, fy);
    series.next(nx, ny);
    log.t.push_back(t);
    log.fx.push_back(fx + nx);
    log.fy.push_back(fy + ny);
  }
  for (double t = 0.0; t + 60.0 / 2800.0 <= t_cut_s; t += 60.0 / 2800.0) log.air.push_back({0, t, t + 60.0 / 2800.0, 0, 0, 0, 0});
  for (double t = t_cut_s; t + kToothPeriodS < 1.2; t += kToothPeriodS) log.periods.push_back({0, t, t + kToothPeriodS, 0, 0, 0, 0});
  return log;
}

// The oracle: the mean excess of the largest noisy |F| over the true largest, on the noise-free pulse.
double true_excess_n(Noise noise) {
  NoiseSeries series(noise, 99u);
  double sum = 0.0;
  const int draws = 4000;
  for (int d = 0; d < draws; ++d) {
    double largest = 0.0, noisy = 0.0;
    for (double t = 0.0; t < kToothPeriodS; t += kRowStepS) {
      double fx, fy, nx, ny;
      true_force(t, 0.0, fx, fy);
      series.next(nx, ny);
      largest = std::max(largest, std::hypot(fx, fy));
      noisy = std::max(noisy, std::hypot(fx + nx, fy + ny));
    }
    sum += noisy - largest;
  }
  return sum / draws;
}

TEST(PeakNoise, WhiteNoiseSpreadAndItsExcessOnThePeaks) {
  const Noise noise{6.0, 0.0};
  const SyntheticLog log = make_log(noise);
  const PeakNoise got = peak_noise(log.t, log.fx, log.fy, log.air, log.periods);
  EXPECT_NEAR(got.sigma_n, 6.0, 0.4);
  EXPECT_LT(got.lag1, 0.1);
  const double truth = true_excess_n(noise);
  EXPECT_GT(truth, 3.0);  // a few N on 400: what learning would otherwise hold the true force under by
  EXPECT_NEAR(got.peak_excess_n, truth, 0.3 * truth);
  EXPECT_NE(got.message.find("raises a tooth period's peak reading"), std::string::npos);
}

TEST(PeakNoise, CorrelatedNoiseIsSeenAsSuchAndRaisesThePeaksLess) {
  const Noise noise{6.0, 0.8};
  const SyntheticLog log = make_log(noise);
  const PeakNoise got = peak_noise(log.t, log.fx, log.fy, log.air, log.periods);
  EXPECT_NEAR(got.lag1, 0.8, 0.06);
  const double truth = true_excess_n(noise);
  EXPECT_LT(truth, true_excess_n({6.0, 0.0}));
  EXPECT_NEAR(got.peak_excess_n, truth, 0.3 * truth);
}

TEST(PeakNoise, WithoutNoiseNothingIsTakenOff) {
  const SyntheticLog log = make_log({0.0, 0.0});
  const PeakNoise got = peak_noise(log.t, log.fx, log.fy, log.air, log.periods);
  EXPECT_DOUBLE_EQ(got.sigma_n, 0.0);
  EXPECT_DOUBLE_EQ(got.peak_excess_n, 0.0);
}

TEST(PeakNoise, TooLittleAirEstimatesNothingAndSaysSo) {
  SyntheticLog log = make_log({6.0, 0.0});
  log.air.resize(1);
  log.air.front().t_end_s = log.air.front().t_start_s + 0.01;  // 100 rows out of the cut
  const PeakNoise got = peak_noise(log.t, log.fx, log.fy, log.air, log.periods);
  EXPECT_DOUBLE_EQ(got.peak_excess_n, 0.0);
  EXPECT_NE(got.message.find("not estimated"), std::string::npos);
}

}  // namespace
}  // namespace feedplan::learning
