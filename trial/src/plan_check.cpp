#include "feedplan/trial/plan_check.hpp"

#include "feedplan/gcode/reader.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"
#include "feedplan/sim/material.hpp"

namespace feedplan::trial {

VirtualMachine virtual_machine_for(const cycles::CycleSpec& spec, const cycles::Cycle& cycle,
                                   const std::string& materials_path) {
  const sim::MaterialLibrary materials = sim::load_materials(materials_path);
  VirtualMachine machine;
  machine.tool = spec.tool;
  machine.coefficients = materials.get(spec.material, "material").coefficients;
  machine.stock = cycle.stock;
  machine.machine = spec.machine;
  machine.spindle_rpm = spec.spindle_rpm;
  return machine;
}

PlanCheck check_on_virtual_machine(const std::string& program_text, const cycles::CycleSpec& spec,
                                   const cycles::Cycle& cycle, const planner::PlanResult& plan, double target_force_n,
                                   const std::string& materials_path, const std::function<void(double)>& progress) {
  VirtualMachine machine = virtual_machine_for(spec, cycle, materials_path);
  machine.keep_log = false;
  machine.progress = progress;
  const trial::VirtualMachineRun run =
      trial::run_on_virtual_machine(gcode::read_program(program_text, "planned program"), machine, plan, target_force_n);
  PlanCheck check;
  check.cycle_time_s = run.simulation.summary.cycle_time_s;
  check.max_peak_n = run.simulation.summary.max_revolution_peak_n;
  check.comparison = run.comparison;
  check.warnings = run.simulation.warnings;
  return check;
}

}  // namespace feedplan::trial
