#include "feedplan/trial/control_sensor.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <utility>

#include "feedplan/core/number_text.hpp"

namespace feedplan::trial {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTwoPi = 6.283185307179586;

constexpr std::array<std::pair<ForceSensor, std::string_view>, 3> kNames = {{
    {ForceSensor::kDynamometer, "dynamometer"},
    {ForceSensor::kSpindlePower, "spindle"},
    {ForceSensor::kServoCurrents, "currents"},
}};

void check_positive(std::vector<InputProblem>& problems, const std::string& field, double value, const char* rule) {
  if (std::isfinite(value) && value > 0.0) return;
  std::string message = "= ";
  message += shortest_number_text(value);
  message += ": must be finite and > 0 ";
  message += rule;
  problems.push_back({field, std::move(message)});
}

}  // namespace

std::string_view to_string(ForceSensor sensor) {
  for (const auto& [value, name] : kNames) {
    if (value == sensor) return name;
  }
  return "";
}

std::optional<ForceSensor> force_sensor_named(std::string_view name) {
  for (const auto& [value, known] : kNames) {
    if (known == name) return value;
  }
  return std::nullopt;
}

std::vector<InputProblem> validate(const ForceSensorSettings& settings, const std::string& field_prefix) {
  std::vector<InputProblem> problems;
  if (settings.sensor == ForceSensor::kSpindlePower) {
    check_positive(problems, field_prefix + "tool_radius_mm", settings.tool_radius_mm,
                   "mm — the radius the tangential force acts at (F_t = P / (ω r))");
  }
  if (settings.sensor == ForceSensor::kServoCurrents) {
    check_positive(problems, field_prefix + "calibration.x.b_a_per_n", settings.calibration.x.b_a_per_n,
                   "A/N — the x current per newton (I = a + b·|F|)");
    check_positive(problems, field_prefix + "calibration.y.b_a_per_n", settings.calibration.y.b_a_per_n,
                   "A/N — the y current per newton (I = a + b·|F|)");
    for (const auto& [field, a] : {std::pair{"calibration.x.a_a", settings.calibration.x.a_a},
                                   std::pair{"calibration.y.a_a", settings.calibration.y.a_a}}) {
      if (std::isfinite(a)) continue;
      std::string message = "= ";
      message += shortest_number_text(a);
      message += ": must be finite A — the current of the moving axis without cutting force";
      problems.push_back({field_prefix + field, std::move(message)});
    }
  }
  return problems;
}

void enable_sensor(ForceSensor sensor, sim::SensorOptions& options) {
  if (sensor == ForceSensor::kSpindlePower) options.spindle_power.enabled = true;
  if (sensor == ForceSensor::kServoCurrents) options.servo_current.enabled = true;
}

double sensed_force_n(const ForceSensorSettings& settings, const sim::SensorReading& reading, double spindle_rpm) {
  switch (settings.sensor) {
    case ForceSensor::kDynamometer:
      return std::hypot(reading.dynamometer_fx_n, reading.dynamometer_fy_n);
    case ForceSensor::kSpindlePower: {
      const double omega_rad_per_s = spindle_rpm * kTwoPi / 60.0;
      if (!(omega_rad_per_s > 0.0)) return kNaN;
      return reading.spindle_power_w / (omega_rad_per_s * settings.tool_radius_mm * 1e-3);
    }
    case ForceSensor::kServoCurrents: {
      const learning::CurrentCalibration& c = settings.calibration;
      return std::hypot((reading.ix_a - c.x.a_a) / c.x.b_a_per_n, (reading.iy_a - c.y.a_a) / c.y.b_a_per_n);
    }
  }
  return kNaN;
}

RevolutionForceMeter::RevolutionForceMeter(const ForceSensorSettings& settings) : settings_(settings) {
  assert(validate(settings).empty());
}

std::optional<SensedRevolution> RevolutionForceMeter::add(double t_s, double spindle_rpm,
                                                          const sim::SensorReading& reading) {
  if (!started_) {
    started_ = true;
    last_t_s_ = t_s;
    revolution_start_s_ = t_s;
  }
  if (spindle_rpm > 0.0) turns_ += spindle_rpm / 60.0 * (t_s - last_t_s_);
  last_t_s_ = t_s;
  const double force_n = sensed_force_n(settings_, reading, spindle_rpm);
  if (std::isfinite(force_n)) largest_n_ = std::max(largest_n_, force_n);
  if (turns_ < next_turn_) return std::nullopt;
  const SensedRevolution done{revolution_start_s_, t_s, largest_n_};
  next_turn_ = std::floor(turns_) + 1.0;
  revolution_start_s_ = t_s;
  largest_n_ = 0.0;
  return done;
}

}  // namespace feedplan::trial
