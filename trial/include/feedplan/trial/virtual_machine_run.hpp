#pragma once
// Running a planned program on the virtual machine (first-principles forces, not the response-surface
// model) and comparing its true per-revolution peaks with the plan's target — what `feedplan plan
// --simulate` reports and what `feedplan loop` learns from.

#include <functional>

#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/learning/sensor_dynamics.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/peak_comparison.hpp"
#include "feedplan/sim/cutting_coefficients.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::trial {

//! What the virtual machine needs besides the program.
struct VirtualMachine {
  geometry::Tool tool;                    //!< the end mill
  sim::CuttingCoefficients coefficients;  //!< the true physics of the tool–material pair
  geometry::Stock stock;                  //!< the material before the program
  geometry::MachineLimits machine;          //!< feed, acceleration and rapid limits
  double spindle_rpm = 0.0;               //!< for blocks without S, rev/min
  sim::SensorOptions sensors;             //!< what is logged (dynamometer by default)
  std::vector<double> runout_mm;          //!< radial runout per tooth, mm; empty: none
  //! Keep the force log's rows in the run (learning reads them); false: only its header, the
  //! per-revolution peaks and the summary — what `plan --simulate` needs, in bounded memory.
  bool keep_log = true;
  //! Where the force log's rows go as they are recorded (must outlive the run); null: kept or dropped as
  //! keep_log says.
  force_log::ForceLogSink* log_sink = nullptr;
  //! A feedback controller on the feed override (override_control.hpp); empty controller: none.
  sim::OverrideLoop override_loop;
  //! Called with the fraction of the simulation done (sim::SimulationRequest::progress); may be empty.
  std::function<void(double)> progress;
};

//! Gives `machine` the physics of a machine file (sim/machine_file.hpp) on the catalogue tool `tool`: the
//! tool with the file's helix offset, the cutting coefficients, the runout and the dynamometer. Throws
//! InputError with sim::apply_machine's problems when the file does not fit the tool (machine unchanged).
void use_machine_file(VirtualMachine& machine, const sim::MachineFile& file, const geometry::Tool& tool);

//! The machine's own physics as the planner's mechanistic kernel (model/mechanistic_force.hpp): its cutting
//! and edge coefficients with their size effect, its runout per tooth and its tool's helix — the force
//! model of a planner that knows the machine perfectly. The simulator's teeth are the kernel's, in the same
//! order (tests/model/mechanistic_simulator_test.cpp checks the two forces against each other).
model::MechanisticModel own_physics(const VirtualMachine& machine);

//! The first mode of a virtual dynamometer as its tap test would give it: the natural frequency from the
//! −3 dB bandwidth and the damping (sim/sensors.hpp: ω_n = ω_bw / sqrt(1 − 2ζ² + sqrt((1 − 2ζ²)² + 1))).
learning::SensorDynamics dynamometer_mode(const sim::DynamometerOptions& dynamometer);

//! One run.
struct VirtualMachineRun {
  sim::SimulationResult simulation;       //!< log (rows only with keep_log), true per-revolution peaks, summary
  planner::PeakComparison comparison;     //!< true peaks against the target along the plan
};

//! Simulates `program` on `machine`: its tool, true physics, stock, limits, spindle speed, sensors and
//! override loop; the log's rows go to machine.log_sink when set, else are kept only with machine.keep_log. Throws InputError on an invalid request (sim::validate).
sim::SimulationResult simulate_on(const geometry::Program& program, const VirtualMachine& machine);

//! Simulates `program` on `machine` and places every simulated revolution on the plan's path: the
//! machine's motion gives the path length at each revolution's start and end; a program that begins
//! with a move the plan does not have (a G-code text read back starts from the machine's position) is
//! aligned by the difference of the lengths to the plan's end point, as both end there — the last move
//! of `program` that ends there (within its coordinate_resolution_mm, at least 1 µm); moves after it (the
//! writer's safe return, read back as a park) are not on the plan's path. Throws InputError on an
//! invalid request (sim::validate).
VirtualMachineRun run_on_virtual_machine(const geometry::Program& program, const VirtualMachine& machine,
                                         const planner::PlanResult& plan, double target_force_n);

}  // namespace feedplan::trial
