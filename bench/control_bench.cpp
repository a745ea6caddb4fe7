// Feedback control on the virtual machine: a 30 s cycle under seed 002's adaptive robust servo, and under
// seed 004's multi-model β-FROH controller (scheme 1, fifteen models compared every step), sensing the
// force through the feed-drive currents — a Ø20 mm two-flute end mill slotting S50C at 600 rev/min,
// the axial depth stepping from 1 mm to 2 mm (the scenario of tests/trial/override_control_test.cpp,
// lengthened) — against the same program without the controller, for the loop's share of the time.

#include <benchmark/benchmark.h>

#include <string>

#include "feedplan/gcode/reader.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/trial/controlled_run.hpp"

namespace {

using namespace feedplan;

constexpr const char* kDepthStepSlot =
    "G21 G90 G17\n"
    "G0 X-11 Y0 Z5 S600 M3\n"
    "G0 Z-1\n"
    "G1 X25 F300\n"
    "G1 X27 Z-2\n"
    "G1 X81\n"
    "G0 Z5\n"
    "M5\n"
    "M30\n";

trial::VirtualMachine slot_machine() {
  const sim::MaterialLibrary materials = sim::load_materials(std::string(FEEDPLAN_DATA_DIR) + "/materials.yaml");
  trial::VirtualMachine machine;
  machine.tool.diameter_mm = 20.0;
  machine.tool.flutes = 2;
  machine.tool.helix_deg = 30.0;
  machine.coefficients = materials.get("S50C").coefficients;
  machine.stock.regions.push_back({geometry::Contour::rectangle({0.0, -30.0}, {70.0, 30.0}), {}});
  machine.stock.z_top_mm = 0.0;
  machine.stock.z_bottom_mm = -10.0;
  machine.spindle_rpm = 600.0;
  machine.sensors.servo_current.enabled = true;
  machine.sensors.servo_current.noise_amp = 0.02;
  machine.keep_log = false;
  return machine;
}

trial::OverrideControlSettings current_control() {
  const sim::ServoCurrentOptions drives;
  trial::OverrideControlSettings settings;
  settings.sensor.sensor = trial::ForceSensor::kServoCurrents;
  settings.sensor.calibration.x = {drives.x.a_amp, drives.x.b_amp_per_n, 1.0, 0};
  settings.sensor.calibration.y = {drives.y.a_amp, drives.y.b_amp_per_n, 1.0, 0};
  settings.target_force_n = 500.0;
  return settings;
}

void report(benchmark::State& state, double simulated_s, double max_peak_n) {
  state.counters["simulated_s"] = simulated_s;
  state.counters["max_peak_n"] = max_peak_n;
  state.counters["simulated_s_per_wall_s"] =
      benchmark::Counter(simulated_s * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The depth-step slot on the currents under `controller` (its target the loop's; with `loop_bounds`, the
// loop's override bounds too).
void run_slot_under(benchmark::State& state, trial::ControllerSettings controller, bool loop_bounds) {
  const geometry::Program program = gcode::read_program(kDepthStepSlot, "depth-step slot");
  const trial::VirtualMachine machine = slot_machine();
  const trial::OverrideControlSettings settings = current_control();
  controller.target_force_n = settings.target_force_n;
  if (loop_bounds) {
    controller.min_ratio = settings.min_ratio;
    controller.max_ratio = settings.max_ratio;
  }
  controller.spindle_rpm = machine.spindle_rpm;
  controller.flutes = machine.tool.flutes;
  double simulated_s = 0.0, max_peak_n = 0.0;
  for (auto _ : state) {
    const trial::ControlledRun run = trial::run_under_control(program, machine, settings, trial::make_control_law(controller));
    simulated_s = run.judgement.cycle_time_s;
    max_peak_n = run.judgement.max_peak_n;
    benchmark::DoNotOptimize(run);
  }
  report(state, simulated_s, max_peak_n);
}

void BM_SlotUnderRobustServo(benchmark::State& state) {
  trial::ControllerSettings controller;
  controller.kind = trial::ControllerKind::kRobustServo;
  run_slot_under(state, controller, false);
}

void BM_SlotUnderMultiModel1(benchmark::State& state) {
  trial::ControllerSettings controller;
  controller.kind = trial::ControllerKind::kMultiModel1;
  run_slot_under(state, controller, true);
}

void BM_SlotWithoutControl(benchmark::State& state) {
  const geometry::Program program = gcode::read_program(kDepthStepSlot, "depth-step slot");
  const trial::VirtualMachine machine = slot_machine();
  double simulated_s = 0.0, max_peak_n = 0.0;
  for (auto _ : state) {
    const sim::SimulationResult result = trial::simulate_on(program, machine);
    simulated_s = result.summary.cycle_time_s;
    max_peak_n = result.summary.max_revolution_peak_n;
    benchmark::DoNotOptimize(result);
  }
  report(state, simulated_s, max_peak_n);
}

BENCHMARK(BM_SlotUnderRobustServo)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_SlotUnderMultiModel1)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_SlotWithoutControl)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
