#include "feedplan/sim/sensors.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "feedplan/core/number_text.hpp"

namespace feedplan::sim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_positive(std::vector<InputProblem>& problems, const std::string& field, double value,
                    const std::string& unit, const std::string& why) {
  if (std::isfinite(value) && value > 0.0) return;
  problems.push_back({field, "= " + shortest_number_text(value) + ": must be " +
                                 (std::isfinite(value) ? "" : "a finite number ") + "> 0 " + unit + " — " + why});
}

void check_non_negative(std::vector<InputProblem>& problems, const std::string& field, double value,
                        const std::string& unit, const std::string& why) {
  if (std::isfinite(value) && value >= 0.0) return;
  problems.push_back({field, "= " + shortest_number_text(value) + ": must be " +
                                 (std::isfinite(value) ? "" : "a finite number ") + "≥ 0 " + unit + " — " + why});
}

void check_damping(std::vector<InputProblem>& problems, const std::string& field, double value) {
  if (std::isfinite(value) && value > 0.0 && value <= 2.0) return;
  problems.push_back({field, "= " + shortest_number_text(value) +
                                 ": must be in (0, 2] — damping ratio of the sensor's second-order low pass "
                                 "(0.707 flat, below that a resonance)"});
}

// A second-order low pass: bandwidth, damping, noise, and where its fields live.
struct FilterSpec {
  std::string path;
  double bandwidth_hz;
  double damping_ratio;
};

std::vector<FilterSpec> enabled_filters(const SensorOptions& options) {
  std::vector<FilterSpec> filters = {
      {"sensors.dynamometer", options.dynamometer.bandwidth_hz, options.dynamometer.damping_ratio}};
  if (options.spindle_sensor.enabled) {
    filters.push_back({"sensors.spindle_sensor", options.spindle_sensor.bandwidth_hz,
                       options.spindle_sensor.damping_ratio});
  }
  if (options.servo_current.enabled) {
    filters.push_back({"sensors.servo_current", options.servo_current.bandwidth_hz,
                       options.servo_current.damping_ratio});
  }
  if (options.spindle_power.enabled) {
    filters.push_back({"sensors.spindle_power", options.spindle_power.bandwidth_hz,
                       options.spindle_power.damping_ratio});
  }
  return filters;
}

// A seed for one sensor's generator: the user's 64-bit seed and the sensor's index, through
// std::seed_seq (whose algorithm the standard fixes, so every platform gets the same stream).
std::mt19937_64 engine_for(std::uint64_t seed, std::uint32_t sensor_index) {
  std::seed_seq sequence{static_cast<std::uint32_t>(seed & 0xffffffffu), static_cast<std::uint32_t>(seed >> 32),
                         sensor_index};
  return std::mt19937_64(sequence);
}

}  // namespace

std::vector<InputProblem> validate(const SensorOptions& options) {
  std::vector<InputProblem> problems;
  for (const auto& filter : enabled_filters(options)) {
    check_positive(problems, filter.path + ".bandwidth_hz", filter.bandwidth_hz, "Hz",
                   "the sensor's −3 dB frequency");
    check_damping(problems, filter.path + ".damping_ratio", filter.damping_ratio);
  }
  check_non_negative(problems, "sensors.dynamometer.noise_n", options.dynamometer.noise_n, "N",
                     "RMS noise per axis (0 = none)");
  if (options.spindle_sensor.enabled) {
    check_non_negative(problems, "sensors.spindle_sensor.noise_n", options.spindle_sensor.noise_n, "N",
                       "RMS noise per axis (0 = none)");
  }
  if (options.servo_current.enabled) {
    const ServoCurrentOptions& c = options.servo_current;
    check_non_negative(problems, "sensors.servo_current.noise_amp", c.noise_amp, "A",
                       "RMS noise per current (0 = none)");
    const std::array<std::pair<const char*, const ServoCurrentAxis*>, 3> axes = {{{"x", &c.x}, {"y", &c.y}, {"z", &c.z}}};
    for (const auto& [name, axis] : axes) {
      const std::string path = std::string("sensors.servo_current.") + name;
      check_non_negative(problems, path + ".a_amp", axis->a_amp, "A",
                         "current of the moving axis without cutting force (seed 002: x 4.12, y 7.24, z 18.5)");
      check_positive(problems, path + ".b_amp_per_n", axis->b_amp_per_n, "A/N",
                     "current per newton of axis force (seed 002: x 0.00362, y 0.00450, z 0.00289)");
    }
  }
  if (options.spindle_power.enabled) {
    check_non_negative(problems, "sensors.spindle_power.noise_w", options.spindle_power.noise_w, "W",
                       "RMS noise of the power reading (0 = none)");
  }
  return problems;
}

std::vector<InputProblem> validate(const SensorOptions& options, double step_s) {
  std::vector<InputProblem> problems = validate(options);
  if (!(std::isfinite(step_s) && step_s > 0.0)) {
    problems.push_back({"sensors step_s", "= " + shortest_number_text(step_s) +
                                              ": must be a finite number > 0 s — the simulation step"});
    return problems;
  }
  const double nyquist_hz = 0.5 / step_s;
  for (const auto& filter : enabled_filters(options)) {
    if (!(std::isfinite(filter.bandwidth_hz) && filter.bandwidth_hz > 0.0)) continue;  // reported above
    if (filter.bandwidth_hz < nyquist_hz) continue;
    problems.push_back({filter.path + ".bandwidth_hz",
                        "= " + shortest_number_text(filter.bandwidth_hz) + ": must be < " +
                            shortest_number_text(nyquist_hz) + " Hz, the Nyquist frequency of the simulation step " +
                            shortest_number_text(step_s) + " s — lower the bandwidth or the step"});
  }
  return problems;
}

double Sensors::Biquad::step(double x) {
  const double y = b0 * x + s1;
  s1 = b1 * x - a1 * y + s2;
  s2 = b2 * x - a2 * y;
  return y;
}

double Sensors::Noise::next() {
  if (has_spare) {
    has_spare = false;
    return spare;
  }
  // Box–Muller: u1 in (0, 1] keeps the logarithm finite, u2 in [0, 1).
  constexpr double kScale = 1.0 / 9007199254740992.0;  // 2^-53
  const double u1 = 1.0 - static_cast<double>(engine() >> 11) * kScale;
  const double u2 = static_cast<double>(engine() >> 11) * kScale;
  const double radius = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * std::numbers::pi * u2;
  spare = radius * std::sin(angle);
  has_spare = true;
  return radius * std::cos(angle);
}

Sensors::Biquad Sensors::low_pass(double bandwidth_hz, double damping_ratio, double step_s) {
  // −3 dB frequency → natural frequency (see the header): |H(jω)|² = 1/2 at u = (ω/ω_n)².
  const double zeta = damping_ratio;
  const double c = 1.0 - 2.0 * zeta * zeta;
  const double u = c + std::sqrt(c * c + 1.0);
  const double omega_bw = 2.0 * std::numbers::pi * bandwidth_hz;
  const double omega_n = omega_bw / std::sqrt(u);
  // Tustin with prewarping at ω_bw: s = K (1 − z⁻¹)/(1 + z⁻¹), K = ω_bw / tan(ω_bw T / 2), so the
  // discrete response at ω_bw equals the analogue one there.
  const double k = omega_bw / std::tan(0.5 * omega_bw * step_s);
  const double w2 = omega_n * omega_n;
  const double a0 = k * k + 2.0 * zeta * omega_n * k + w2;
  Biquad f;
  f.b0 = w2 / a0;
  f.b1 = 2.0 * w2 / a0;
  f.b2 = w2 / a0;
  f.a1 = (2.0 * w2 - 2.0 * k * k) / a0;
  f.a2 = (k * k - 2.0 * zeta * omega_n * k + w2) / a0;
  return f;
}

Sensors::Sensors(const SensorOptions& options, double step_s) : options_(options), step_s_(step_s) {
  if (auto problems = validate(options, step_s); !problems.empty()) throw InputError(std::move(problems));
  const Biquad dynamometer = low_pass(options.dynamometer.bandwidth_hz, options.dynamometer.damping_ratio, step_s);
  for (auto& f : dynamometer_) f = dynamometer;
  if (options.spindle_sensor.enabled) {
    const Biquad spindle = low_pass(options.spindle_sensor.bandwidth_hz, options.spindle_sensor.damping_ratio, step_s);
    for (auto& f : spindle_) f = spindle;
  }
  if (options.servo_current.enabled) {
    const Biquad current = low_pass(options.servo_current.bandwidth_hz, options.servo_current.damping_ratio, step_s);
    for (auto& f : current_) f = current;
  }
  if (options.spindle_power.enabled) {
    power_ = low_pass(options.spindle_power.bandwidth_hz, options.spindle_power.damping_ratio, step_s);
  }
  dynamometer_noise_.engine = engine_for(options.seed, 0);
  spindle_noise_.engine = engine_for(options.seed, 1);
  current_noise_.engine = engine_for(options.seed, 2);
  power_noise_.engine = engine_for(options.seed, 3);
}

SensorReading Sensors::update(double fx_n, double fy_n, double fz_n, double spindle_power_w) {
  SensorReading r;
  const double dynamometer_noise = options_.dynamometer.noise_n;
  auto noisy = [](Noise& noise, double sigma) { return sigma > 0.0 ? sigma * noise.next() : 0.0; };
  r.dynamometer_fx_n = dynamometer_[0].step(fx_n) + noisy(dynamometer_noise_, dynamometer_noise);
  r.dynamometer_fy_n = dynamometer_[1].step(fy_n) + noisy(dynamometer_noise_, dynamometer_noise);
  r.dynamometer_fz_n = dynamometer_[2].step(fz_n) + noisy(dynamometer_noise_, dynamometer_noise);

  if (options_.spindle_sensor.enabled) {
    const double sigma = options_.spindle_sensor.noise_n;
    r.spindle_fx_n = spindle_[0].step(fx_n) + noisy(spindle_noise_, sigma);
    r.spindle_fy_n = spindle_[1].step(fy_n) + noisy(spindle_noise_, sigma);
  } else {
    r.spindle_fx_n = kNaN;
    r.spindle_fy_n = kNaN;
  }

  if (options_.servo_current.enabled) {
    // Seed 002 Eqs. 12–14 on the magnitude of the low-passed axis force (see the header).
    const ServoCurrentOptions& c = options_.servo_current;
    r.ix_a = c.x.a_amp + c.x.b_amp_per_n * std::abs(current_[0].step(fx_n)) + noisy(current_noise_, c.noise_amp);
    r.iy_a = c.y.a_amp + c.y.b_amp_per_n * std::abs(current_[1].step(fy_n)) + noisy(current_noise_, c.noise_amp);
    r.iz_a = c.z.a_amp + c.z.b_amp_per_n * std::abs(current_[2].step(fz_n)) + noisy(current_noise_, c.noise_amp);
  } else {
    r.ix_a = kNaN;
    r.iy_a = kNaN;
    r.iz_a = kNaN;
  }

  r.spindle_power_w = options_.spindle_power.enabled
                          ? power_.step(spindle_power_w) + noisy(power_noise_, options_.spindle_power.noise_w)
                          : kNaN;
  return r;
}

}  // namespace feedplan::sim
