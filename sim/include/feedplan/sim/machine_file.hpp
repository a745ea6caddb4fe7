#pragma once
// A test machine as data: the physics one virtual machine cuts with — a material's cutting
// coefficients (a material of the library, with fields overridden), the size effect, per-tooth
// runout, how far the tool's true helix lies from its catalogue helix, and the dynamometer's
// bandwidth and noise. A force model fitted on one machine is judged on machines whose physics differ
// from the model in shape, not only in scale; each file describes one such machine
// (data/machines/*.yaml, docs/method.md §4).
//
// File format (one YAML document):
//
//   name: steel-worn-holder              # required, free text
//   description: ...                     # optional
//   material: S50C                       # required: a name or alias of the material library
//   coefficients: {ktc_n_per_mm2: 2300}  # optional: any of the six, each replacing the material's
//   size_effect: {exponent: 0.2, reference_chip_mm: 0.05, min_chip_mm: 0.005}  # optional: replaces
//   runout_mm: [0.006, 0, -0.003, 0]     # required: radial runout per tooth, one per flute, mm
//   helix_offset_deg: 4                  # required: true helix − catalogue helix, deg
//   dynamometer: {bandwidth_hz: 800, damping_ratio: 0.707, noise_n: 8}  # required (damping optional)
//
// The machine does not know the tool: the runout list must have one value per flute of the tool it
// is used with, which apply_machine checks.

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/sim/cutting_coefficients.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "feedplan/sim/sensors.hpp"

namespace feedplan::sim {

//! One virtual test machine, read from a machine file, its material resolved.
struct MachineFile {
  std::string name;                   //!< the machine's name, free text
  std::string description;            //!< what is special about it, free text
  std::string source_name;            //!< the file it was read from, for messages
  std::string material;               //!< canonical name of the library material it starts from
  CuttingCoefficients coefficients;   //!< the material's, with the file's overrides and size effect
  std::vector<double> runout_mm;      //!< radial runout per tooth, mm (tooth j cuts at r + runout_mm[j])
  double helix_offset_deg = 0.0;      //!< true helix − catalogue helix of the tool, deg
  DynamometerOptions dynamometer;     //!< bandwidth, damping and noise of the table dynamometer
};

//! Parses and validates a machine file from YAML text; `source_name` names it in messages, and the
//! material is looked up in `materials`.
//!
//! Checks: a mapping with known fields only (an unknown one lists the expected names and suggests the
//! closest); name, material, runout_mm, helix_offset_deg and dynamometer {bandwidth_hz, noise_n}
//! present; material a name or alias of `materials`; each coefficient override finite and ≥ 0
//! (ktc_n_per_mm2 > 0); size_effect.exponent in [0, 1), reference_chip_mm > 0, min_chip_mm in (0,
//! reference_chip_mm]; runout_mm a list of 1 to 16 numbers each within ±0.05 mm; helix_offset_deg in
//! [−15, 15]; dynamometer.bandwidth_hz finite and > 0, damping_ratio in (0, 2], noise_n finite and ≥ 0.
//! Every problem found is collected, then one feedplan::InputError carries them all, each naming the
//! field with its line, the value and the expectation. Returns the machine with its coefficients
//! resolved.
MachineFile read_machine_file(const std::string& yaml_text, const std::string& source_name,
                              const MaterialLibrary& materials);

//! Reads the file at `path` and parses it with read_machine_file. A file that does not exist or
//! cannot be read is an InputError naming the path.
MachineFile load_machine_file(const std::string& path, const MaterialLibrary& materials);

//! Puts `machine` into `request`: its coefficients, its runout, the tool's helix moved by
//! helix_offset_deg (request.tool must be set) and the dynamometer options (the noise seed is kept).
//! Returns the problems that need the tool — runout_mm must have one value per flute, the true helix
//! must stay in [0, 70) deg — named "<source> runout_mm" and so on, and leaves `request` unchanged
//! then. Empty on success.
std::vector<InputProblem> apply_machine(const MachineFile& machine, SimulationRequest& request);

}  // namespace feedplan::sim
