#pragma once
// A program run on the virtual machine under a feedback controller (override_control.hpp), and judged on
// the machine's true per-revolution peaks (control_judgement.hpp): what `feedplan control` does, alone
// on a constant-feed program or, in the hybrid, on a feed-forward plan's program.

#include "feedplan/geometry/program.hpp"
#include "feedplan/trial/control_judgement.hpp"
#include "feedplan/trial/feedback_controller.hpp"
#include "feedplan/trial/override_control.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"

namespace feedplan::trial {

//! One controlled run.
struct ControlledRun {
  sim::SimulationResult simulation;  //!< log (as the machine's keep_log / log_sink say), true peaks, summary
  ControlTrace trace;                //!< what the controller sensed and commanded
  ControlJudgement judgement;        //!< the true peaks against the target
};

//! Runs `program` on `machine` (its own override loop replaced) with `law` hooked to the override as
//! `settings` say, the sensor the settings name switched on. Throws InputError with the settings' problems
//! (override_control.hpp) or the simulation's (sim::validate).
ControlledRun run_under_control(const geometry::Program& program, VirtualMachine machine,
                                const OverrideControlSettings& settings, const ControlLaw& law);

}  // namespace feedplan::trial
