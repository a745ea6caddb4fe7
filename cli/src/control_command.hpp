#pragma once
// `feedplan control SPEC.yaml|PROGRAM.nc --controller NAME …`: a feedback force controller of the source
// papers (integral ACC, variable-gain AC, adaptive robust servo) on the virtual machine's feed override —
// alone on a constant-feed program, or (--hybrid) trimming the override of the feed-forward plan's own
// program within 70–130 % — judged on the machine's true per-revolution peaks.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace feedplan::cli {

struct ControlOptions {
  std::string input_path;                     //!< SPEC.yaml or PROGRAM.nc / .ngc
  std::string controller;                     //!< --controller NAME
  std::optional<double> target_force_n;       //!< --target-force, N; unset: the spec's
  std::string sensor = "dynamometer";         //!< --sensor dynamometer|spindle|currents
  std::string machine_path;                   //!< --machine MACHINE.yaml
  std::optional<double> machine_scale;        //!< --machine-scale K
  bool hybrid = false;                        //!< --hybrid: the plan's program, override trimmed within 70–130 %
  std::string log_path;                       //!< --log LOG.csv
  std::string plot_path;                      //!< --plot PLOT.svg
  bool json = false;                          //!< --json
  std::string db_path;                        //!< --db, for --hybrid's plan
  std::string materials_path;                 //!< --materials
  std::string tool_text;                      //!< --tool, PROGRAM only
  std::string stock_path;                     //!< --stock, PROGRAM only
  std::string material_name;                  //!< --material, PROGRAM only
  std::optional<double> spindle_rpm;          //!< --spindle-rpm, PROGRAM only: for blocks without S
  std::string depth_steps;                    //!< --depth-steps D1,D2,…, mm: SPEC only, a depth-step slot instead of the cycle
  std::optional<double> step_length_mm;       //!< --step-length L, mm (default 30): each depth held for L
  std::string calibration_path;               //!< --calibration FILE: the currents' calibration (--sensor currents)
};

//! Registers the subcommand.
void add_control_command(CLI::App& app, ControlOptions& options);

//! Runs it: 0 done, 1 failed (an output not written, no model for --hybrid); throws InputError on bad input.
int run_control_command(const ControlOptions& options);

}  // namespace feedplan::cli
