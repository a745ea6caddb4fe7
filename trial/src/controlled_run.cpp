#include "feedplan/trial/controlled_run.hpp"

#include <memory>

namespace feedplan::trial {

ControlledRun run_under_control(const geometry::Program& program, VirtualMachine machine,
                                const OverrideControlSettings& settings, const ControlLaw& law) {
  auto trace = std::make_shared<ControlTrace>();
  machine.override_loop = make_override_loop(settings, law, trace);
  enable_sensor(settings.sensor.sensor, machine.sensors);
  ControlledRun run;
  run.simulation = simulate_on(program, machine);
  run.trace = std::move(*trace);
  run.judgement = judge_control(run.simulation.revolutions, settings.target_force_n, run.simulation.summary.cycle_time_s);
  return run;
}

}  // namespace feedplan::trial
