#pragma once
// --sensor-hz and --sensor-damping: the force sensor's first mode (a dynamometer's natural frequency as
// mounted and its damping ratio, from its tap test or data sheet), for `learn` and `loop`, which then take
// the sensor's own dynamics off the peaks before learning (learning/sensor_dynamics.hpp).

#include <CLI/CLI.hpp>

#include <optional>

#include "feedplan/learning/sensor_dynamics.hpp"

namespace feedplan::cli {

//! The flags' values as given.
struct SensorFlags {
  std::optional<double> natural_frequency_hz;  //!< --sensor-hz
  std::optional<double> damping_ratio;         //!< --sensor-damping
};

//! Registers both flags on `command`.
void add_sensor_flags(CLI::App* command, SensorFlags& flags);

//! The sensor's mode, or none when neither flag is given. Throws InputError (exit 2) naming the flag when
//! only one is given or a value is out of range (learning::check_sensor_dynamics).
std::optional<learning::SensorDynamics> sensor_dynamics(const SensorFlags& flags);

}  // namespace feedplan::cli
