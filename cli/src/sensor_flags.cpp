#include "sensor_flags.hpp"

#include "feedplan/core/input_error.hpp"
#include "number_flag.hpp"

namespace feedplan::cli {

void add_sensor_flags(CLI::App* command, SensorFlags& flags) {
  add_number_flag(command, "--sensor-hz", flags.natural_frequency_hz,
                  "Force sensor's natural frequency as mounted, Hz (its tap test or data sheet): peaks are corrected for\n"
                  "its dynamics before learning (with --sensor-damping)");
  add_number_flag(command, "--sensor-damping", flags.damping_ratio, "Force sensor's damping ratio ζ, in (0, 2] (with --sensor-hz)");
}

std::optional<learning::SensorDynamics> sensor_dynamics(const SensorFlags& flags) {
  if (!flags.natural_frequency_hz && !flags.damping_ratio) return std::nullopt;
  if (!flags.natural_frequency_hz || !flags.damping_ratio) {
    throw InputError(flags.natural_frequency_hz ? "--sensor-damping" : "--sensor-hz",
                     std::string("is missing: the sensor's mode needs both --sensor-hz and --sensor-damping"));
  }
  const learning::SensorDynamics sensor{*flags.natural_frequency_hz, *flags.damping_ratio};
  learning::check_sensor_dynamics(sensor, "--sensor-hz", "--sensor-damping");
  return sensor;
}

}  // namespace feedplan::cli
