#pragma once
// `feedplan plan … --simulate`: run the program just written on the virtual machine (the text read back
// by the G-code reader, first-principles forces for the spec's material — not the planner's model) and
// compare its per-revolution peak forces with the target along the plan.

#include <functional>
#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/peak_comparison.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"

namespace feedplan::trial {

//! What the virtual machine did with a planned program.
struct PlanCheck {
  double cycle_time_s = 0.0;            //!< simulated program duration, s
  double max_peak_n = 0.0;              //!< largest per-revolution peak, N
  planner::PeakComparison comparison;   //!< per-revolution peaks against the target
  std::vector<std::string> warnings;    //!< the simulation's warnings
};

//! The virtual machine for `spec` on `cycle.stock`: the spec's tool, machine limits and spindle speed,
//! the cutting coefficients of `spec.material` from the materials file at `materials_path`. Throws
//! InputError when the material is unknown to the virtual machine.
VirtualMachine virtual_machine_for(const cycles::CycleSpec& spec, const cycles::Cycle& cycle,
                                   const std::string& materials_path);

//! Reads `program_text` back (gcode::read_program), simulates it on `cycle.stock` with the spec's tool,
//! machine limits and the material `spec.material` from the materials file at `materials_path`, and
//! compares the true per-revolution peaks with `target_force_n` along `plan`, the force log not kept
//! (bounded memory). `progress`, if set, is called with the fraction of the simulation done. Throws
//! InputError when the material is unknown to the virtual machine.
PlanCheck check_on_virtual_machine(const std::string& program_text, const cycles::CycleSpec& spec,
                                   const cycles::Cycle& cycle, const planner::PlanResult& plan, double target_force_n,
                                   const std::string& materials_path, const std::function<void(double)>& progress = {});

}  // namespace feedplan::trial
