#pragma once
// `feedplan simulate`: run a G-code program (or a virtual cutting test) on the virtual machine and
// write the force log a dynamometer would record, with a summary and optionally a plot.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace feedplan::cli {

struct SimulateOptions {
  std::string program_path;        //!< the G-code program; empty with --cutting-test
  std::string spec_path;           //!< cycle spec to take tool, material, spindle, machine and stock from
  std::string tool_text;           //!< "diameter_mm=10,flutes=4,helix_deg=30[,name=…]"
  std::string tools_path;          //!< tool library (the end mill of each T number); conflicts with tool_text
  std::string material_name;       //!< name or alias in the materials file
  std::string materials_path;      //!< materials file; empty: the bundled one
  std::string stock_path;          //!< stock YAML (or a cycle spec); empty: a block around the program
  std::string log_path;            //!< force log CSV to write
  std::string plot_path;           //!< SVG plot to write; empty: none
  std::string peaks_path;          //!< per-revolution peaks CSV to write; empty: none
  bool json = false;               //!< summary as JSON
  std::optional<double> spindle_rpm;          //!< spindle speed for blocks without S (and the cutting test's S); unset: the spec's
  std::optional<double> max_accel_mm_per_s2;  //!< unset: the spec's or the default
  std::optional<double> rapid_feed_mm_per_min;  //!< unset: the spec's or the default
  std::optional<double> max_feed_mm_per_min;  //!< unset: the spec's or the default
  std::string machine_path;        //!< machine file (data/machines/); sets material, runout, helix offset, dynamometer
  std::string runout_text;         //!< per-tooth runout in mm, comma separated
  std::optional<double> noise_n;   //!< dynamometer noise RMS, N; unset: 0 (or the machine file's)
  bool currents = false;           //!< log servo currents (seed 002's I = a + b·F)
  double log_rate_hz = 10000.0;    //!< log sample rate, Hz
  double angle_step_deg = 1.0;     //!< spindle rotation per internal step, deg
  double layer_mm = 0.25;          //!< axial slice thickness, mm
  std::uint64_t seed = 1;          //!< sensor noise seed
  bool cutting_test = false;       //!< simulate a straight cut instead of a program
  std::optional<double> radial_depth_mm;  //!< cutting test a_e, mm
  std::optional<double> axial_depth_mm;   //!< cutting test a_p, mm
  std::optional<double> feed_mm_per_min;  //!< cutting test F, mm/min
  double cut_length_mm = 40.0;     //!< cutting test block length
  bool up_milling = false;         //!< cutting test: conventional instead of climb milling
};

//! Registers the subcommand.
void add_simulate_command(CLI::App& app, SimulateOptions& options);

//! Runs the command. Returns the exit code (0 ok, 1 failed); throws InputError on bad input.
int run_simulate_command(const SimulateOptions& options);

}  // namespace feedplan::cli
