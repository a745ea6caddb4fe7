#pragma once
// `feedplan calibrate-currents LOG.csv [-o CALIBRATION.json] [--json]`: fit seed 002's servo-current
// calibration I = a + b·|F| per axis from a log that has both forces and currents, and write it for
// `feedplan learn --calibration`, which turns current-only logs into force logs with it.

#include <CLI/CLI.hpp>

#include <string>

#include "feedplan/learning/current_calibration.hpp"

namespace feedplan::cli {

struct CalibrationOptions {
  std::string log_path;     //!< the log with forces and currents
  std::string output_path;  //!< -o: the calibration file (JSON)
  bool json = false;        //!< --json
};

//! Registers the subcommand.
void add_calibration_command(CLI::App& app, CalibrationOptions& options);

//! Runs it: 0 done; throws InputError on a log without forces or currents, or without variation.
int run_calibration_command(const CalibrationOptions& options);

//! Reads a calibration file written by the command. Throws InputError naming the field on anything
//! missing, not a number, or b ≤ 0.
learning::CurrentCalibration load_current_calibration(const std::string& path);

}  // namespace feedplan::cli
