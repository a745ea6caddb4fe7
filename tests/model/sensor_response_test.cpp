// The dynamometer's modes (model/sensor_response.hpp), the peak it reads (sensed_peak.hpp) and identifying
// its modes with the coefficients (mechanistic_identification.hpp, identify_sensor). The oracle is a
// time-domain integration, written here and independent of the code under test, of the plate the file
// comment of sensor_response.hpp describes: two modal coordinates q_m along d_m, each
//   q̈_m + 2 ζ_m ω_m q̇_m + ω_m² q_m = ω_m² d_mᵀ F(t),   reading = Σ_m d_m q_m,
// by the classical Runge–Kutta method, run over enough revolutions for the start's transient to die out.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model/prediction_interval.hpp"
#include "feedplan/model/sensed_peak.hpp"
#include "feedplan/model/sensor_response.hpp"

namespace feedplan::model {
namespace {

constexpr double kPi = 3.14159265358979323846;

//! The oracle's plate: modes (Hz, damping) along θ and θ + 90°.
struct Plate {
  double f0_hz, zeta0, f1_hz, zeta1, theta_deg;
};

SensorResponse as_sensor(const Plate& p) {
  SensorResponse s;
  s.modes[0] = {p.f0_hz, p.zeta0};
  s.modes[1] = {p.f1_hz, p.zeta1};
  s.mode_angle_deg = p.theta_deg;
  return s;
}

using Xy = std::array<double, 2>;

//! The plate's reading over the last of `revolutions` revolutions at `rpm`, at `steps` equal steps of the
//! spindle angle from 0, for a force `force(angle)` repeating every revolution (RK4 on the step, the force
//! also read at the half steps).
std::vector<Xy> ring(const Plate& p, double rpm, const std::function<Xy(double)>& force, int steps, int revolutions) {
  const double h = 60.0 / rpm / steps;
  std::vector<Xy> f(static_cast<std::size_t>(2 * steps));
  for (int i = 0; i < 2 * steps; ++i) f[static_cast<std::size_t>(i)] = force(2 * kPi * i / (2.0 * steps));
  const double theta = p.theta_deg * kPi / 180;
  const Xy d[2] = {{std::cos(theta), std::sin(theta)}, {-std::sin(theta), std::cos(theta)}};
  const double w[2] = {2 * kPi * p.f0_hz, 2 * kPi * p.f1_hz}, z[2] = {p.zeta0, p.zeta1};
  // State per mode: q, q̇.
  double q[2][2] = {{0, 0}, {0, 0}};
  auto derivative = [&](int m, double qm, double vm, const Xy& fm) {
    const double load = d[m][0] * fm[0] + d[m][1] * fm[1];
    return std::array<double, 2>{vm, w[m] * w[m] * (load - qm) - 2 * z[m] * w[m] * vm};
  };
  std::vector<Xy> reading(static_cast<std::size_t>(steps));
  for (int rev = 0; rev < revolutions; ++rev) {
    for (int i = 0; i < steps; ++i) {
      if (rev == revolutions - 1) {
        reading[static_cast<std::size_t>(i)] = {d[0][0] * q[0][0] + d[1][0] * q[1][0], d[0][1] * q[0][0] + d[1][1] * q[1][0]};
      }
      const Xy& fa = f[static_cast<std::size_t>(2 * i)];
      const Xy& fb = f[static_cast<std::size_t>(2 * i + 1)];
      const Xy& fc = f[static_cast<std::size_t>((2 * i + 2) % (2 * steps))];
      for (int m = 0; m < 2; ++m) {
        const auto k1 = derivative(m, q[m][0], q[m][1], fa);
        const auto k2 = derivative(m, q[m][0] + 0.5 * h * k1[0], q[m][1] + 0.5 * h * k1[1], fb);
        const auto k3 = derivative(m, q[m][0] + 0.5 * h * k2[0], q[m][1] + 0.5 * h * k2[1], fb);
        const auto k4 = derivative(m, q[m][0] + h * k3[0], q[m][1] + h * k3[1], fc);
        q[m][0] += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]);
        q[m][1] += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]);
      }
    }
  }
  return reading;
}

// A calibrated dynamometer reads a static force right; on its own axis a mode peaks at 1/(2ζ) at its natural
// frequency with a 90° lag; with θ = 0 the axes do not couple; with θ ≠ 0 a force along a mode's direction
// is read along it, through that mode alone.
TEST(SensorResponse, GainOfTheTwoModes) {
  const SensorResponse axes = as_sensor({800, 0.05, 1000, 0.02, 0.0});
  const SensorGain dc = sensor_gain(axes, 0.0);
  EXPECT_NEAR(std::abs(dc.xy[0][0] - 1.0), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(dc.xy[1][1] - 1.0), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(dc.xy[0][1]), 0.0, 1e-15);
  const SensorGain at_x_mode = sensor_gain(axes, 800.0);
  EXPECT_NEAR(at_x_mode.xy[0][0].real(), 0.0, 1e-12);
  EXPECT_NEAR(at_x_mode.xy[0][0].imag(), -1.0 / (2 * 0.05), 1e-9);
  EXPECT_NEAR(std::abs(at_x_mode.xy[1][0]), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(sensor_gain(axes, 1000.0).xy[1][1]), 1.0 / (2 * 0.02), 1e-9);
  // Far above the modes the reading falls as (f_m / f)².
  EXPECT_NEAR(std::abs(sensor_gain(axes, 80000.0).xy[0][0]), 1e-4, 1e-6);

  const SensorResponse turned = as_sensor({800, 0.05, 1000, 0.02, 30.0});
  const double c = std::cos(30 * kPi / 180), s = std::sin(30 * kPi / 180);
  for (double f : {0.0, 350.0, 800.0, 1000.0, 2500.0}) {
    const SensorGain g = sensor_gain(turned, f);
    const std::complex<double> h0 = 1.0 / std::complex<double>(1 - (f / 800) * (f / 800), 2 * 0.05 * f / 800);
    const std::complex<double> h1 = 1.0 / std::complex<double>(1 - (f / 1000) * (f / 1000), 2 * 0.02 * f / 1000);
    // Along d_0 = (c, s): read h0 (c, s); along d_1 = (−s, c): read h1 (−s, c).
    EXPECT_NEAR(std::abs(g.xy[0][0] * c + g.xy[0][1] * s - h0 * c), 0.0, 1e-12) << f;
    EXPECT_NEAR(std::abs(g.xy[1][0] * c + g.xy[1][1] * s - h0 * s), 0.0, 1e-12) << f;
    EXPECT_NEAR(std::abs(g.xy[0][0] * -s + g.xy[0][1] * c - h1 * -s), 0.0, 1e-12) << f;
    EXPECT_NEAR(std::abs(g.xy[1][0] * -s + g.xy[1][1] * c - h1 * c), 0.0, 1e-12) << f;
  }
}

// A pulse train (a half sine on a quarter of the revolution in x, a narrower one in y: rich in harmonics)
// read through a coupled plate at 6000 rpm, its modes between the 8th and 12th harmonic: the steady
// reading at 400 samples equals the oracle's after 40 revolutions within 1e-3 of the force's peak.
TEST(SensorResponse, SteadyReadingOfAPulseTrainMatchesATimeDomainIntegration) {
  const Plate plate{850, 0.04, 1150, 0.06, 20.0};
  constexpr double kRpm = 6000;
  constexpr int kSamples = 400;
  auto force = [](double angle) -> Xy {
    const double a = std::fmod(angle, 2 * kPi);
    const double x = a < kPi / 2 ? 300 * std::sin(2 * a) : 0.0;
    const double y = a > kPi && a < 1.25 * kPi ? -200 * std::sin(4 * (a - kPi)) : 0.0;
    return {x, y};
  };
  std::vector<double> fx, fy;
  for (int j = 0; j < kSamples; ++j) {
    const Xy f = force(2 * kPi * j / kSamples);
    fx.push_back(f[0]);
    fy.push_back(f[1]);
  }
  // The oracle at 16 steps per sample; its reading at the samples.
  const std::vector<Xy> truth = ring(plate, kRpm, force, 16 * kSamples, 40);
  const RevolutionForce read = sensed_revolution(as_sensor(plate), kRpm, fx, fy);
  double largest_error = 0.0, largest_reading = 0.0;
  for (int j = 0; j < kSamples; ++j) {
    const Xy& t = truth[static_cast<std::size_t>(16 * j)];
    largest_error = std::max({largest_error, std::abs(read.fx_n[static_cast<std::size_t>(j)] - t[0]),
                              std::abs(read.fy_n[static_cast<std::size_t>(j)] - t[1])});
    largest_reading = std::max({largest_reading, std::abs(t[0]), std::abs(t[1])});
  }
  std::printf("pulse train through the plate: largest reading %.1f N (force 300 N), largest difference from the "
              "time-domain oracle %.3f N\n", largest_reading, largest_error);
  EXPECT_GT(largest_reading, 330.0);  // it rings: more than the force
  EXPECT_LT(largest_error, 0.3);      // 1e-3 of the force's 300 N: the pulses' kinks fold above 200 harmonics
}

// One harmonic is read as its amplitude times |H| and shifted by arg H (the closed form of a mode), at any
// sample count, odd or even, prime factors small or not; the harmonic n/2 of an even count, which samples
// cannot tell from its phase, as a cosine through them (times Re H).
TEST(SensorResponse, AHarmonicIsReadThroughTheModeAtAnySampleCount) {
  const SensorResponse sensor = as_sensor({800, 0.05, 1000, 0.02, 0.0});
  constexpr double kRpm = 6000;  // 100 Hz revolutions
  for (int n : {7, 8, 45, 97, 720}) {
    const int k = n > 8 ? 7 : 3;  // 700 Hz, or 300 Hz
    const std::complex<double> h = sensor_gain(sensor, k * kRpm / 60).xy[0][0];
    std::vector<double> fx, fy;
    for (int j = 0; j < n; ++j) {
      fx.push_back(120 * std::cos(k * 2 * kPi * j / n + 0.4));
      fy.push_back(0.0);
    }
    const RevolutionForce read = sensed_revolution(sensor, kRpm, fx, fy);
    for (int j = 0; j < n; ++j) {
      const double expected = 120 * std::abs(h) * std::cos(k * 2 * kPi * j / n + 0.4 + std::arg(h));
      EXPECT_NEAR(read.fx_n[static_cast<std::size_t>(j)], expected, 1e-9) << "n " << n << " sample " << j;
      EXPECT_NEAR(read.fy_n[static_cast<std::size_t>(j)], 0.0, 1e-9) << "n " << n << " sample " << j;
    }
  }
  const std::vector<double> alternating = {50, -50, 50, -50, 50, -50, 50, -50}, zero(8, 0.0);
  const double re_h = sensor_gain(sensor, 4 * kRpm / 60).xy[1][1].real();
  const RevolutionForce read = sensed_revolution(sensor, kRpm, zero, alternating);
  for (std::size_t j = 0; j < 8; ++j) EXPECT_NEAR(read.fy_n[j], alternating[j] * re_h, 1e-9) << j;
}

TEST(SensorResponse, BadSensorsAreNamed) {
  SensorResponse s;
  s.modes[0].natural_frequency_hz = -5;
  s.modes[1].damping_ratio = 1.2;
  s.mode_angle_deg = NAN;
  const auto problems = validate(s);
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_EQ(problems[0].field, "sensor.modes[0].natural_frequency_hz");
  EXPECT_EQ(problems[1].field, "sensor.modes[1].damping_ratio");
  EXPECT_NE(problems[1].message.find("must be in (0, 1)"), std::string::npos) << problems[1].message;
  EXPECT_EQ(problems[2].field, "sensor.mode_angle_deg");
  EXPECT_TRUE(validate(SensorResponse{}).empty());
}

//! Al7075-T6 (data/materials.yaml).
MechanisticModel al7075() {
  MechanisticModel m;
  m.ktc_n_per_mm2 = 796;
  m.krc_n_per_mm2 = 169;
  m.kte_n_per_mm = 27.7;
  m.kre_n_per_mm = 30.8;
  return m;
}

constexpr double kRpm = 6000;
const CutterGeometry kCutter{5.0, 2, 30.0};
constexpr double kAxialDepthMm = 3.0;

//! A down-milling test whose synchronous average is the kernel's force read through the oracle's plate,
//! averaged over `bins` bins (each from 16 oracle steps), the tooth 0 at spindle angle `phase` at bin 0's start.
MechanisticCuttingTest rung_test(const MechanisticModel& truth, const Plate& plate, double radial_depth_mm,
                                 double feed_per_tooth_mm, int bins, double phase) {
  MechanisticCuttingTest t;
  t.cutter = kCutter;
  t.arc = straight_cut_arc(StraightCutSide::kDown, radial_depth_mm, kCutter.radius_mm);
  t.axial_depth_mm = kAxialDepthMm;
  t.feed_per_tooth_mm = feed_per_tooth_mm;
  t.spindle_rpm = kRpm;
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&t.arc, 1)};
  auto force = [&](double angle) -> Xy {
    const MechanisticForce f = predicted_force(truth, std::span<const EngagedSection>(&section, 1), kCutter,
                                               feed_per_tooth_mm, phase + angle);
    return {f.fx_n, f.fy_n};
  };
  constexpr int kStepsPerBin = 16;
  const std::vector<Xy> reading = ring(plate, kRpm, force, kStepsPerBin * bins, 40);
  for (int b = 0; b < bins; ++b) {
    double fx = 0, fy = 0;
    for (int s = 0; s < kStepsPerBin; ++s) {
      // The bin's average by the midpoint rule: half of each end step's weight.
      const double w = (s == 0 ? 0.5 : 1.0) / kStepsPerBin;
      fx += w * reading[static_cast<std::size_t>(b * kStepsPerBin + s)][0];
      fy += w * reading[static_cast<std::size_t>(b * kStepsPerBin + s)][1];
    }
    const Xy& end = reading[static_cast<std::size_t>(((b + 1) * kStepsPerBin) % (kStepsPerBin * bins))];
    fx += 0.5 / kStepsPerBin * end[0];
    fy += 0.5 / kStepsPerBin * end[1];
    t.synchronous_fx_n.push_back(fx);
    t.synchronous_fy_n.push_back(fy);
  }
  t.name = "a_e " + std::to_string(radial_depth_mm).substr(0, 3) + " f_z " + std::to_string(feed_per_tooth_mm).substr(0, 5);
  return t;
}

//! One section of a down-milling cut a_e deep, its arc kept alive with it.
struct Cut {
  ImmersionArc arc;
  EngagedSection section;
  explicit Cut(double radial_depth_mm)
      : arc(straight_cut_arc(StraightCutSide::kDown, radial_depth_mm, kCutter.radius_mm)),
        section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)} {}
  std::span<const EngagedSection> sections() const { return {&section, 1}; }
};

// Modes far above every harmonic the samples hold (1 MHz): the reading is the force, and its peak the
// kernel's own (predicted_peak_force_n) within 0.1 %, with runout too.
TEST(SensedPeak, AStiffSensorReadsTheKernelsPeak) {
  MechanisticModel model = al7075();
  model.runout_mm = {0.01, 0.0};
  const SensorResponse stiff = as_sensor({1e6, 0.5, 1e6, 0.5, 0.0});
  for (double ae : {1.0, 4.0, 10.0}) {
    const Cut cut(ae);
    const double kernel_n = predicted_peak_force_n(model, cut.sections(), kCutter, 0.08);
    const SensedPeak read = predicted_sensed_peak(model, cut.sections(), kCutter, 0.08, stiff, kRpm);
    std::printf("a_e %.0f mm: kernel peak %.2f N, read by a stiff sensor %.2f N\n", ae, kernel_n, read.force_n);
    EXPECT_NEAR(read.force_n, kernel_n, 1e-3 * kernel_n) << ae;
    EXPECT_NEAR(read.force_peak_n, kernel_n, 1e-3 * kernel_n) << ae;
  }
}

// Through a ringing plate, the peak is the oracle's: the largest |reading| over the last of 40 revolutions
// at 7200 steps, within 0.2 %; and it lies well above the force's own peak.
TEST(SensedPeak, ThroughARingingPlateMatchesATimeDomainIntegration) {
  const Plate plate{850, 0.03, 1150, 0.05, 20.0};
  MechanisticModel model = al7075();
  model.runout_mm = {0.01, 0.0};
  for (double ae : {2.0, 10.0}) {
    const Cut cut(ae);
    auto force = [&](double angle) -> Xy {
      const MechanisticForce f = predicted_force(model, cut.sections(), kCutter, 0.08, angle);
      return {f.fx_n, f.fy_n};
    };
    double oracle_n = 0.0;
    for (const Xy& r : ring(plate, kRpm, force, 7200, 40)) oracle_n = std::max(oracle_n, std::hypot(r[0], r[1]));
    const SensedPeak read = predicted_sensed_peak(model, cut.sections(), kCutter, 0.08, as_sensor(plate), kRpm);
    std::printf("a_e %.0f mm: force peak %.1f N, read %.1f N, oracle %.1f N\n", ae, read.force_peak_n, read.force_n, oracle_n);
    EXPECT_NEAR(read.force_n, oracle_n, 2e-3 * oracle_n) << ae;
    EXPECT_GT(read.force_n, 1.1 * read.force_peak_n) << ae;
  }
}

// The interval's fit σ propagates the covariance through the reading's gradient in the coefficients: the
// same as central finite differences of the sensed peak, within 1 %.
TEST(SensedPeak, IntervalPropagatesTheCovarianceThroughTheReading) {
  const Plate plate{850, 0.03, 1150, 0.05, 20.0};
  const MechanisticModel model = al7075();
  const Cut cut(3.0);
  const std::array<double, 4> sd{20.0, 10.0, 2.0, 3.0};
  std::array<std::array<double, 4>, 4> covariance{};
  for (int i = 0; i < 4; ++i) covariance[i][i] = sd[i] * sd[i];
  const PredictionInterval interval =
      mechanistic_sensed_peak_interval(model, covariance, cut.sections(), kCutter, 0.08, as_sensor(plate), kRpm, 0.0);
  double variance = 0.0;
  for (int i = 0; i < 4; ++i) {
    MechanisticModel up = model, down = model;
    double* u[4] = {&up.ktc_n_per_mm2, &up.krc_n_per_mm2, &up.kte_n_per_mm, &up.kre_n_per_mm};
    double* d[4] = {&down.ktc_n_per_mm2, &down.krc_n_per_mm2, &down.kte_n_per_mm, &down.kre_n_per_mm};
    *u[i] += 0.01 * sd[i];
    *d[i] -= 0.01 * sd[i];
    const double slope = (predicted_sensed_peak(up, cut.sections(), kCutter, 0.08, as_sensor(plate), kRpm).force_n -
                          predicted_sensed_peak(down, cut.sections(), kCutter, 0.08, as_sensor(plate), kRpm).force_n) /
                         (0.02 * sd[i]);
    variance += slope * slope * sd[i] * sd[i];
  }
  std::printf("sensed peak %.1f N: fit σ %.3f N, by finite differences %.3f N\n", interval.predicted_n, interval.fit_sd_n,
              std::sqrt(variance));
  EXPECT_NEAR(interval.fit_sd_n, std::sqrt(variance), 0.01 * std::sqrt(variance));
  EXPECT_NEAR(interval.predicted_n,
              predicted_sensed_peak(model, cut.sections(), kCutter, 0.08, as_sensor(plate), kRpm).force_n, 1e-9);
  EXPECT_THROW(mechanistic_sensed_peak_interval(model, covariance, cut.sections(), kCutter, 0.08,
                                                as_sensor({850, 1.5, 1150, 0.05, 0.0}), kRpm, 0.0),
               InputError);
  EXPECT_THROW(mechanistic_sensed_peak_interval(model, covariance, cut.sections(), kCutter, 0.08, as_sensor(plate), 0.0, 0.0),
               InputError);
}

void print(const char* what, const MechanisticIdentification& r) {
  const SensorResponse& s = *r.sensor;
  std::printf("%s: modes %.2f Hz ζ %.4f, %.2f Hz ζ %.4f, θ %+.2f°; K_tc %.1f K_rc %.1f K_te %.2f K_re %.2f; RMS residual "
              "%.3f N\n  %s\n", what, s.modes[0].natural_frequency_hz, s.modes[0].damping_ratio,
              s.modes[1].natural_frequency_hz, s.modes[1].damping_ratio, s.mode_angle_deg, r.model.ktc_n_per_mm2,
              r.model.krc_n_per_mm2, r.model.kte_n_per_mm, r.model.kre_n_per_mm, r.rms_residual_n, r.sensor_report.c_str());
  for (const auto& u : r.unidentifiable) std::printf("  cannot identify: %s\n", u.c_str());
}

// The truth is the plate put in: modes at 850 Hz (ζ 0.04) and 1150 Hz (ζ 0.06), turned by 20°, between the
// revolution's harmonics at 6000 rpm (100 Hz). Two feeds and two radial depths, 60 bins (Nyquist 3 kHz).
// Recovered: frequencies within 0.5 %, damping within 5 % of itself, the angle within 1°, the
// coefficients within 1 %.
TEST(SensorIdentification, RecoversACoupledPlateFromRungKernelForces) {
  const Plate plate{850, 0.04, 1150, 0.06, 20.0};
  const MechanisticModel truth = al7075();
  const std::vector<MechanisticCuttingTest> tests = {
      rung_test(truth, plate, 2.0, 0.05, 60, 0.3), rung_test(truth, plate, 2.0, 0.15, 60, 1.1),
      rung_test(truth, plate, 6.0, 0.05, 60, 2.0), rung_test(truth, plate, 6.0, 0.15, 60, 0.7)};
  MechanisticIdentificationOptions options;
  options.identify_sensor = true;
  const MechanisticIdentification r = identify_mechanistic(tests, options);
  print("coupled plate", r);
  ASSERT_TRUE(r.sensor.has_value());
  EXPECT_TRUE(r.sensor_converged);
  const SensorResponse& s = *r.sensor;
  EXPECT_NEAR(s.modes[0].natural_frequency_hz, 850, 0.005 * 850);
  EXPECT_NEAR(s.modes[0].damping_ratio, 0.04, 0.05 * 0.04);
  EXPECT_NEAR(s.modes[1].natural_frequency_hz, 1150, 0.005 * 1150);
  EXPECT_NEAR(s.modes[1].damping_ratio, 0.06, 0.05 * 0.06);
  EXPECT_NEAR(s.mode_angle_deg, 20.0, 1.0);
  EXPECT_NEAR(r.model.ktc_n_per_mm2, truth.ktc_n_per_mm2, 0.01 * truth.ktc_n_per_mm2);
  EXPECT_NEAR(r.model.krc_n_per_mm2, truth.krc_n_per_mm2, 0.01 * truth.krc_n_per_mm2);
  EXPECT_NEAR(r.model.kte_n_per_mm, truth.kte_n_per_mm, 0.01 * truth.kte_n_per_mm);
  EXPECT_NEAR(r.model.kre_n_per_mm, truth.kre_n_per_mm, 0.01 * truth.kre_n_per_mm);
}

}  // namespace
}  // namespace feedplan::model
