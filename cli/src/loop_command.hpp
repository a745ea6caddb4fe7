#pragma once
// `feedplan loop SPEC.yaml --cycles N …`: plan → cut on the virtual machine → learn → re-plan, N times,
// from a model that is deliberately wrong for the virtual machine (its cutting coefficients scaled by
// --machine-scale), printing per cycle the per-revolution force error and the cycle time. Nothing is
// written to the database.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

#include "sensor_flags.hpp"

namespace feedplan::cli {

struct LoopOptions {
  std::string spec_path;            //!< the cycle spec
  std::string db_path;              //!< --db
  int cycles = 3;                   //!< --cycles
  //! --machine-scale: the virtual machine's true forces ≈ this × the model's; unset: 1.4 (without --machine)
  std::optional<double> machine_scale;
  std::string machine_path;         //!< --machine: a machine file instead of the scaled material
  std::optional<double> target_force_n;  //!< --target-force; unset: the spec's
  //! --cautious R: first cut on F̂ + z·σ with relative uncertainty R (0: off); unset: from how far the
  //! starting model is borrowed (0, off, for an exact one)
  std::optional<double> cautious;
  double sigmas = 2.0;              //!< --sigmas z
  std::optional<std::int64_t> model_id;  //!< --model-id; unset: the closest active model
  std::string materials_path;       //!< --materials
  bool json = false;                //!< --json
  std::string revolutions_path;     //!< --revolutions: per-revolution CSV of every cycle
  std::string plot_path;            //!< --plot: learning along the path, every cycle, as SVG
  std::string html_path;            //!< --html: the learning history and the next plan as one HTML file
  SensorFlags sensor;               //!< --sensor-hz, --sensor-damping
};

//! Registers the subcommand.
void add_loop_command(CLI::App& app, LoopOptions& options);

//! Runs it. Returns 0 (done) or 1 (no model); throws InputError on bad input.
int run_loop_command(const LoopOptions& options);

}  // namespace feedplan::cli
