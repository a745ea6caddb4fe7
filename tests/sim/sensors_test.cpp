// Sensors: DC gain, −3 dB at the stated bandwidth, seed 002's current characteristic, noise level,
// reproducibility, validation. Amplitudes are measured by a least-squares sine fit written here, not
// taken from the filter coefficients.

#include "feedplan/sim/sensors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <numbers>
#include <sstream>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::sim {
namespace {

constexpr double kPi = std::numbers::pi;

// Amplitude of the best fit y ≈ a sin(ωt) + b cos(ωt) + c (least squares, 3×3 normal equations).
double fitted_amplitude(const std::vector<double>& t_s, const std::vector<double>& y, double frequency_hz) {
  double m[3][4] = {};
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double phase = 2 * kPi * frequency_hz * t_s[i];
    const double basis[3] = {std::sin(phase), std::cos(phase), 1.0};
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) m[r][c] += basis[r] * basis[c];
      m[r][3] += basis[r] * y[i];
    }
  }
  for (int p = 0; p < 3; ++p) {  // Gauss–Jordan; the matrix is well conditioned over many periods
    for (int r = 0; r < 3; ++r) {
      if (r == p) continue;
      const double factor = m[r][p] / m[p][p];
      for (int c = p; c < 4; ++c) m[r][c] -= factor * m[p][c];
    }
  }
  const double a = m[0][3] / m[0][0];
  const double b = m[1][3] / m[1][1];
  return std::hypot(a, b);
}

// Drives `sensors` with force(t) on all three axes for `duration_s` and returns the reading chosen by
// `pick` over the last `measure_s` seconds.
struct Trace {
  std::vector<double> t_s;
  std::vector<double> value;
};
Trace run(Sensors& sensors, const std::function<double(double)>& force, double duration_s, double measure_s,
          const std::function<double(const SensorReading&)>& pick) {
  Trace trace;
  const double dt = sensors.step_s();
  const auto steps = static_cast<long>(std::llround(duration_s / dt));
  for (long i = 1; i <= steps; ++i) {
    const double t = i * dt;
    const double f = force(t - 0.5 * dt);  // force acting during the step
    const SensorReading r = sensors.update(f, f, f);
    if (t > duration_s - measure_s) {
      trace.t_s.push_back(t);
      trace.value.push_back(pick(r));
    }
  }
  return trace;
}

SensorOptions all_enabled() {
  SensorOptions o;
  o.spindle_sensor.enabled = true;
  o.servo_current.enabled = true;
  return o;
}

TEST(Sensors, SteadyForcePassesUnchanged) {
  Sensors sensors(all_enabled(), 20e-6);
  SensorReading r;
  for (int i = 0; i < 10000; ++i) r = sensors.update(250.0, -120.0, 40.0);  // 0.2 s
  EXPECT_NEAR(r.dynamometer_fx_n, 250.0, 1e-9);
  EXPECT_NEAR(r.dynamometer_fy_n, -120.0, 1e-9);
  EXPECT_NEAR(r.dynamometer_fz_n, 40.0, 1e-9);
  EXPECT_NEAR(r.spindle_fx_n, 250.0, 1e-9);
  EXPECT_NEAR(r.spindle_fy_n, -120.0, 1e-9);
}

TEST(Sensors, CurrentIsSeed002CharacteristicInSteadyState) {
  Sensors sensors(all_enabled(), 20e-6);
  SensorReading r;
  for (int i = 0; i < 25000; ++i) r = sensors.update(1000.0, -500.0, 200.0);  // 0.5 s ≫ 1/(2π·62 Hz)
  // Seed 002 Eqs. 12–14 on the force magnitude.
  EXPECT_NEAR(r.ix_a, 4.12 + 0.00362 * 1000.0, 1e-9);
  EXPECT_NEAR(r.iy_a, 7.24 + 0.00450 * 500.0, 1e-9);
  EXPECT_NEAR(r.iz_a, 18.5 + 0.00289 * 200.0, 1e-9);
}

TEST(Sensors, DisabledSensorsReadNaN) {
  Sensors sensors(SensorOptions{}, 20e-6);
  const SensorReading r = sensors.update(1, 2, 3);
  EXPECT_TRUE(std::isnan(r.spindle_fx_n) && std::isnan(r.spindle_fy_n));
  EXPECT_TRUE(std::isnan(r.ix_a) && std::isnan(r.iy_a) && std::isnan(r.iz_a));
  EXPECT_FALSE(std::isnan(r.dynamometer_fx_n));
}

// Gain at `frequency_hz` of the reading `pick` (a sine of amplitude 100 N around `offset_n`).
double measured_gain(const SensorOptions& options, double step_s, double frequency_hz, double offset_n,
                     const std::function<double(const SensorReading&)>& pick, double scale = 1.0) {
  Sensors sensors(options, step_s);
  const double settle_s = std::max(0.05, 40.0 / frequency_hz);
  const double measure_s = std::max(0.02, 40.0 / frequency_hz);
  const Trace trace = run(
      sensors, [&](double t) { return offset_n + 100.0 * std::sin(2 * kPi * frequency_hz * t); }, settle_s + measure_s,
      measure_s, pick);
  return fitted_amplitude(trace.t_s, trace.value, frequency_hz) / scale / 100.0;
}

TEST(Sensors, MinusThreeDecibelsAtEachBandwidth) {
  const double half_power = 1.0 / std::sqrt(2.0);
  for (double step_s : {10e-6, 20e-6, 50e-6}) {
    SCOPED_TRACE("step " + std::to_string(step_s));
    SensorOptions o = all_enabled();
    const double dyn = measured_gain(o, step_s, o.dynamometer.bandwidth_hz, 0.0,
                                     [](const SensorReading& r) { return r.dynamometer_fx_n; });
    EXPECT_NEAR(dyn / half_power, 1.0, 0.01) << "dynamometer gain " << dyn;
    const double spindle = measured_gain(o, step_s, o.spindle_sensor.bandwidth_hz, 0.0,
                                         [](const SensorReading& r) { return r.spindle_fy_n; });
    EXPECT_NEAR(spindle / half_power, 1.0, 0.01) << "spindle sensor gain " << spindle;
    // The current sees |F|: keep the force positive so the magnitude is the force itself.
    const double current = measured_gain(o, step_s, o.servo_current.bandwidth_hz, 500.0,
                                         [](const SensorReading& r) { return r.ix_a; }, o.servo_current.x.b_amp_per_n);
    EXPECT_NEAR(current / half_power, 1.0, 0.01) << "servo current gain " << current;
    std::ostringstream info;
    info << std::setprecision(2) << "[ info     ] step " << step_s * 1e6
              << " us: |gain at bandwidth / (1/√2) − 1| = dynamometer " << std::abs(dyn / half_power - 1.0)
              << ", spindle sensor " << std::abs(spindle / half_power - 1.0) << ", servo current "
              << std::abs(current / half_power - 1.0) << "\n";
    std::cout << info.str();
  }
}

TEST(Sensors, FlatBelowAndFallingAboveTheBandwidth) {
  SensorOptions o;
  auto pick = [](const SensorReading& r) { return r.dynamometer_fz_n; };
  EXPECT_NEAR(measured_gain(o, 20e-6, 300.0, 0.0, pick), 1.0, 0.001);  // Butterworth: 1 − 0.5 (f/fc)^4
  // Second order: −40 dB/decade well above; at 3 × bandwidth the analogue gain is 1/sqrt(1 + 3^4).
  // The bilinear transform warps frequencies away from the prewarp point: 4.6 % less gain here.
  EXPECT_NEAR(measured_gain(o, 10e-6, 9000.0, 0.0, pick) * std::sqrt(82.0), 1.0, 0.06);
}

TEST(Sensors, LowDampingGivesAResonancePeakAndKeepsTheBandwidth) {
  SensorOptions o;
  o.dynamometer.damping_ratio = 0.05;
  o.dynamometer.bandwidth_hz = 2000.0;
  auto pick = [](const SensorReading& r) { return r.dynamometer_fx_n; };
  EXPECT_NEAR(measured_gain(o, 10e-6, 2000.0, 0.0, pick) * std::sqrt(2.0), 1.0, 0.01);
  // Natural frequency from the −3 dB relation, resonance at f_n sqrt(1 − 2ζ²) with gain 1/(2ζ sqrt(1 − ζ²)).
  const double zeta = 0.05;
  const double c = 1 - 2 * zeta * zeta;
  const double natural_hz = 2000.0 / std::sqrt(c + std::sqrt(c * c + 1));
  const double peak_hz = natural_hz * std::sqrt(1 - 2 * zeta * zeta);
  const double expected_peak = 1.0 / (2 * zeta * std::sqrt(1 - zeta * zeta));
  const double measured = measured_gain(o, 10e-6, peak_hz, 0.0, pick);
  EXPECT_NEAR(measured / expected_peak, 1.0, 0.02) << "peak " << measured << " at " << peak_hz << " Hz";
}

TEST(Sensors, NoiseRmsMatchesTheOptionAndIsGaussian) {
  SensorOptions o = all_enabled();
  o.dynamometer.noise_n = 5.0;
  o.spindle_sensor.noise_n = 2.0;
  o.servo_current.noise_amp = 0.05;
  o.seed = 12345;
  Sensors sensors(o, 20e-6);
  const int n = 200000;
  double sum_x = 0, sum_xx = 0, sum_xy = 0, sum_sp = 0, sum_i = 0;
  int within_one_sigma = 0;
  for (int i = 0; i < n; ++i) {
    const SensorReading r = sensors.update(0, 0, 0);
    sum_x += r.dynamometer_fx_n;
    sum_xx += r.dynamometer_fx_n * r.dynamometer_fx_n;
    sum_xy += r.dynamometer_fx_n * r.dynamometer_fy_n;
    sum_sp += r.spindle_fy_n * r.spindle_fy_n;
    sum_i += (r.iy_a - 7.24) * (r.iy_a - 7.24);
    if (std::abs(r.dynamometer_fx_n) < 5.0) ++within_one_sigma;
  }
  EXPECT_NEAR(std::sqrt(sum_xx / n) / 5.0, 1.0, 0.02);
  EXPECT_NEAR(sum_x / n, 0.0, 0.05);                      // σ/√n ≈ 0.011 N
  EXPECT_NEAR(sum_xy / n / 25.0, 0.0, 0.02);              // axes independent
  EXPECT_NEAR(std::sqrt(sum_sp / n) / 2.0, 1.0, 0.02);
  EXPECT_NEAR(std::sqrt(sum_i / n) / 0.05, 1.0, 0.02);
  EXPECT_NEAR(static_cast<double>(within_one_sigma) / n, 0.6827, 0.005);  // normal, not uniform
}

TEST(Sensors, SameSeedSameReadingsOtherSeedOthers) {
  SensorOptions o = all_enabled();
  o.dynamometer.noise_n = 3.0;
  o.spindle_sensor.noise_n = 1.0;
  o.servo_current.noise_amp = 0.1;
  o.seed = 0xfeed'0000'0001ull;
  Sensors a(o, 20e-6), b(o, 20e-6);
  o.seed += 1;
  Sensors c(o, 20e-6);
  bool any_difference = false;
  for (int i = 0; i < 1000; ++i) {
    const double f = 100.0 * std::sin(0.01 * i);
    const SensorReading ra = a.update(f, -f, 0.5 * f);
    const SensorReading rb = b.update(f, -f, 0.5 * f);
    const SensorReading rc = c.update(f, -f, 0.5 * f);
    ASSERT_EQ(ra.dynamometer_fx_n, rb.dynamometer_fx_n);
    ASSERT_EQ(ra.dynamometer_fz_n, rb.dynamometer_fz_n);
    ASSERT_EQ(ra.spindle_fy_n, rb.spindle_fy_n);
    ASSERT_EQ(ra.iz_a, rb.iz_a);
    if (ra.dynamometer_fx_n != rc.dynamometer_fx_n) any_difference = true;
  }
  EXPECT_TRUE(any_difference);
}

TEST(SensorsValidation, ReportsEveryBadOptionWithFieldValueAndRange) {
  SensorOptions o = all_enabled();
  o.dynamometer.bandwidth_hz = -1;
  o.dynamometer.noise_n = -0.5;
  o.spindle_sensor.damping_ratio = 0;
  o.servo_current.y.b_amp_per_n = 0;
  o.servo_current.noise_amp = std::nan("");
  const auto problems = validate(o);
  ASSERT_EQ(problems.size(), 5u);
  EXPECT_EQ(to_string(problems[0]), "sensors.dynamometer.bandwidth_hz = -1: must be > 0 Hz — the sensor's −3 dB frequency");
  EXPECT_EQ(to_string(problems[1]),
            "sensors.spindle_sensor.damping_ratio = 0: must be in (0, 2] — damping ratio of the sensor's second-order "
            "low pass (0.707 flat, below that a resonance)");
  EXPECT_EQ(to_string(problems[2]), "sensors.dynamometer.noise_n = -0.5: must be ≥ 0 N — RMS noise per axis (0 = none)");
  EXPECT_EQ(to_string(problems[3]),
            "sensors.servo_current.noise_amp = nan: must be a finite number ≥ 0 A — RMS noise per current (0 = none)");
  EXPECT_EQ(problems[4].field, "sensors.servo_current.y.b_amp_per_n");
  // Disabled sensors are not checked.
  o = SensorOptions{};
  o.spindle_sensor.bandwidth_hz = -5;
  EXPECT_TRUE(validate(o).empty());
}

TEST(SensorsValidation, BandwidthMustBeBelowNyquist) {
  SensorOptions o;
  const auto problems = validate(o, 200e-6);  // Nyquist 2500 Hz < 3000 Hz
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(to_string(problems[0]), "sensors.dynamometer.bandwidth_hz = 3000: must be < 2500 Hz, the Nyquist frequency "
                                    "of the simulation step 0.0002 s — lower the bandwidth or the step");
  EXPECT_THROW(Sensors(o, 200e-6), InputError);
  EXPECT_THROW(Sensors(o, 0.0), InputError);
  EXPECT_NO_THROW(Sensors(o, 50e-6));
}

}  // namespace
}  // namespace feedplan::sim
