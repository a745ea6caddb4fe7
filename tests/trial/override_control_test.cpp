// The feedback controllers on the virtual machine's feed override, in seed 002's scenario (Kim & Kim 1996,
// §4 and Fig. 10): a 500 N per-revolution peak held while the axial depth of a slot steps from 1 to 2 mm,
// the force sensed through the feed-drive currents. Seed 002 reports the controlled force "within 50 N at
// the steady-state region for the desired command input of 500 N, regardless of the change of
// depth-of-cut". The judge is the virtual machine's true per-revolution peak of |F_xy| (the cutting force
// itself, before any sensor), which the controller never sees — it sees currents.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include "feedplan/control/integral_force_controller.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/trial/controlled_run.hpp"

namespace feedplan::trial {
namespace {

constexpr double kTargetN = 500.0;  // seed 002's reference force
constexpr double kBoundN = 50.0;    // seed 002's steady error bound

// A straight slot with a Ø20 mm two-flute end mill at 600 rev/min (seed 002's Fig. 6 tool and speed: 20 Hz
// tooth passing, one revolution per 100 ms sample), its axial depth stepping from 1 mm to 2 mm over
// x = 25…27 mm. The tool enters the block (x from 0 to 55) from x = −11 and leaves it at x = 66.
constexpr const char* kDepthStepSlot =
    "G21 G90 G17\n"
    "G0 X-11 Y0 Z5 S600 M3\n"
    "G0 Z-1\n"
    "G1 X25 F300\n"
    "G1 X27 Z-2\n"
    "G1 X66\n"
    "G0 Z5\n"
    "M5\n"
    "M30\n";

// The machine the slot is cut on: S50C (the materials file's physics, edge forces included), the block,
// and the feed-drive currents with a little noise (0.02 A RMS, about 5 N on x).
VirtualMachine slot_machine() {
  const sim::MaterialLibrary materials = sim::load_materials(std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/materials.yaml");
  VirtualMachine machine;
  machine.tool.diameter_mm = 20.0;
  machine.tool.flutes = 2;
  machine.tool.helix_deg = 30.0;
  machine.tool.name = "EM D20 Z2";
  machine.coefficients = materials.get("S50C").coefficients;
  machine.stock.regions.push_back({geometry::Contour::rectangle({0.0, -30.0}, {55.0, 30.0}), {}});
  machine.stock.z_top_mm = 0.0;
  machine.stock.z_bottom_mm = -10.0;
  machine.spindle_rpm = 600.0;
  machine.sensors.servo_current.noise_amp = 0.02;
  machine.keep_log = true;
  return machine;
}

// The currents' calibration: the x and y characteristics the virtual machine's drives follow (seed 002
// Eqs. 12–13, sim::ServoCurrentOptions' defaults), as a calibration cut would give them.
ForceSensorSettings current_sensor() {
  const sim::ServoCurrentOptions drives;
  ForceSensorSettings sensor;
  sensor.sensor = ForceSensor::kServoCurrents;
  sensor.calibration.x = {drives.x.a_amp, drives.x.b_amp_per_n, 1.0, 0};
  sensor.calibration.y = {drives.y.a_amp, drives.y.b_amp_per_n, 1.0, 0};
  return sensor;
}

OverrideControlSettings alone_settings() {
  OverrideControlSettings settings;
  settings.sensor = current_sensor();
  settings.target_force_n = kTargetN;
  return settings;
}

// The steady parts of the cut, by the tool's x: the full slot at 1 mm after 10 mm of it (x 10…25) and at
// 2 mm from 10 mm after the step until the cutter's front edge reaches the block's end (x 37…44; at x 45
// the Ø20 tool starts to leave the block at x = 55) — seed 002's Fig. 10 settles within about a second,
// 10 mm at these feeds is 2 s and more.
bool first_depth_steady(double x_mm) { return x_mm >= 10.0 && x_mm <= 25.0; }
bool second_depth_steady(double x_mm) { return x_mm >= 37.0 && x_mm <= 44.0; }

// The true peaks of the steady revolutions, each placed by the tool's x at its end (from the force log).
struct SteadyPeaks {
  int revolutions = 0;
  double max_abs_error_n = 0.0;
  double mean_error_n = 0.0;
  double first_depth_max_abs_error_n = 0.0;   // x 10…25, 1 mm
  double second_depth_max_abs_error_n = 0.0;  // x 37…44, 2 mm
};

SteadyPeaks steady_peaks(const ControlledRun& run) {
  const std::vector<force_log::ForceLogRow>& rows = run.simulation.log.rows;
  SteadyPeaks out;
  double sum = 0.0;
  std::size_t row = 0;
  for (const force_log::RevolutionPeak& rev : run.simulation.revolutions) {
    while (row + 1 < rows.size() && rows[row + 1].t_s <= rev.t_end_s) ++row;
    if (rows.empty()) continue;
    const bool first = first_depth_steady(rows[row].x_mm), second = second_depth_steady(rows[row].x_mm);
    if (!first && !second) continue;
    const double error_n = rev.peak_xy_n - kTargetN;
    ++out.revolutions;
    sum += error_n;
    out.max_abs_error_n = std::max(out.max_abs_error_n, std::abs(error_n));
    double& section = first ? out.first_depth_max_abs_error_n : out.second_depth_max_abs_error_n;
    section = std::max(section, std::abs(error_n));
  }
  if (out.revolutions > 0) out.mean_error_n = sum / out.revolutions;
  return out;
}

ControlledRun run_slot(const ControlLaw& law, const OverrideControlSettings& settings = alone_settings()) {
  return run_under_control(gcode::read_program(kDepthStepSlot, "depth-step slot"), slot_machine(), settings, law);
}

ControlLaw named_law(ControllerKind kind, double loop_gain_per_s = 3.0) {
  ControllerSettings settings;
  settings.kind = kind;
  settings.target_force_n = kTargetN;
  settings.loop_gain_per_s = loop_gain_per_s;
  return make_control_law(settings);
}

void print(const char* name, const SteadyPeaks& s, const ControlledRun& run) {
  std::printf("%s: %d steady revolutions, largest |true peak − 500 N| %.1f N (1 mm: %.1f N, 2 mm: %.1f N), mean error "
              "%+.1f N; cycle %.2f s, largest peak %.1f N\n",
              name, s.revolutions, s.max_abs_error_n, s.first_depth_max_abs_error_n, s.second_depth_max_abs_error_n,
              s.mean_error_n, run.judgement.cycle_time_s, run.judgement.max_peak_n);
}

// The slot has about 70 steady revolutions at 600 rev/min under control; fewer means the run or the
// placing went wrong.
constexpr int kMinSteadyRevolutions = 50;

TEST(OverrideControl, RobustServoOnCurrentsHoldsSeed002sBoundAcrossTheDepthStep) {
  const ControlledRun run = run_slot(named_law(ControllerKind::kRobustServo));
  const SteadyPeaks s = steady_peaks(run);
  print("robust servo, currents", s, run);
  ASSERT_GE(s.revolutions, kMinSteadyRevolutions);
  EXPECT_LE(s.max_abs_error_n, kBoundN);
  // The servo's own steps: once per revolution (100 ms at 600 rev/min), in cut.
  ASSERT_FALSE(run.trace.steps.empty());
  int stepped = 0;
  for (const ControlStep& step : run.trace.steps) stepped += step.in_cut ? 1 : 0;
  EXPECT_GT(stepped, kMinSteadyRevolutions);
}

TEST(OverrideControl, ZeroGainDoesNotHoldTheTargetAtTheSecondDepth) {
  // K = 0: the override stays at 100 %, the programmed 300 mm/min, which cuts near 500 N at 1 mm and
  // about twice that at 2 mm.
  const ControlledRun run = run_slot(named_law(ControllerKind::kIntegral, 0.0));
  const SteadyPeaks s = steady_peaks(run);
  print("integral, zero gain", s, run);
  ASSERT_GE(s.revolutions, 30);  // faster than under control: fewer revolutions in the same length
  EXPECT_GT(s.max_abs_error_n, 4.0 * kBoundN);
}

TEST(OverrideControl, WrongSignRunsAwayFromTheTarget) {
  // The integral ACC given the force error with its sign turned: it feeds faster when the force is too
  // high. Built on the real controller, fed 2·target − F (the error F_R − F turned into F − F_R).
  control::IntegralControllerParameters p;
  p.reference_force_n = kTargetN;
  p.controller_gain_mm_per_min_per_n_s = 3.0 / (kTargetN / kProgrammedFeedPercent);
  p.programmed_feed_mm_per_min = kProgrammedFeedPercent;
  p.initial_feed_mm_per_min = kProgrammedFeedPercent;
  auto controller = std::make_shared<control::IntegralForceController>(p);
  ControlLaw law;
  law.step = [controller](double force_n, double dt_s) { return controller->step(2.0 * kTargetN - force_n, dt_s); };
  law.period_s = 0.1;
  const ControlledRun run = run_slot(law);
  const SteadyPeaks s = steady_peaks(run);
  print("integral, wrong sign", s, run);
  ASSERT_GE(s.revolutions, 20);
  EXPECT_GT(s.max_abs_error_n, 4.0 * kBoundN);
}

TEST(OverrideControl, IntegralHoldsTheTargetWhereItsGainWasSetAndLosesItAtTwiceTheProcessGain) {
  // The companion of the two above, and seeds 000/001's point: the fixed-gain integral ACC is set for the
  // process gain of the programmed feed cutting at the target — the 1 mm depth — and holds it there; at
  // 2 mm the process gain doubles, and so does its loop gain (6 /s against the ~0.2 s delay of drive and
  // sensor: past the stability limit), so it no longer holds the target.
  const ControlledRun run = run_slot(named_law(ControllerKind::kIntegral));
  const SteadyPeaks s = steady_peaks(run);
  print("integral", s, run);
  ASSERT_GE(s.revolutions, kMinSteadyRevolutions);
  EXPECT_LE(s.first_depth_max_abs_error_n, kBoundN);
  EXPECT_GT(s.second_depth_max_abs_error_n, 2.0 * kBoundN);
}

// Seed 004's model-reference controllers on the same slot, their known plant the 1 mm depth's (the
// programmed feed cutting at the target, K_p0 = 5 N/%), never told of the step to 2 mm (the machine
// cannot know it). They have no integrator (trial/model_reference_law.hpp): at 1 mm they hold the target,
// at 2 mm, where the process gain about doubles, they keep a steady error — the closed form of the law's
// file comment gives +45 % (F / F_r = 2ρ / (1 + ρ), ρ ≈ 1.6) for an exact doubling; the virtual machine's
// edge forces make the doubling inexact. Measured: 1 mm within 27–28 N of the target (all three), 2 mm
// largest errors 270 N (model-reference), 308 N (multi-model-1), 282 N (multi-model-2), the mean +117 …
// +123 N over both depths. At 2 mm multi-model-1's error is not only an offset: on the same slot made
// longer (feedplan control with --log) its feed swings between 40 and 360 mm/min, a limit cycle the two
// others do not have (170–236 mm/min); this test bounds the largest error only. Bounds: seed 002's 50 N at the known depth; at 2 mm an error between 150 N
// (a third below the closed form's +225 N: it would mean the law had found the new gain, which it cannot)
// and 400 N (the open loop's +500 N less a fifth: the law would no longer be acting).
TEST(OverrideControl, ModelReferenceHoldsTheTargetAtTheKnownDepthAndKeepsASteadyErrorAtTheOther) {
  for (const ControllerKind kind : {ControllerKind::kModelReference, ControllerKind::kMultiModel1, ControllerKind::kMultiModel2}) {
    ControllerSettings settings;
    settings.kind = kind;
    settings.target_force_n = kTargetN;
    settings.spindle_rpm = 600.0;
    settings.flutes = 2;
    settings.min_ratio = 0.1;
    const ControlledRun run = run_slot(make_control_law(settings));
    const SteadyPeaks s = steady_peaks(run);
    print(std::string(to_string(kind)).c_str(), s, run);
    ASSERT_GE(s.revolutions, kMinSteadyRevolutions);
    EXPECT_LE(s.first_depth_max_abs_error_n, kBoundN) << to_string(kind);
    EXPECT_GT(s.second_depth_max_abs_error_n, 150.0) << to_string(kind);
    EXPECT_LT(s.second_depth_max_abs_error_n, 400.0) << to_string(kind);
  }
}

TEST(OverrideControl, SensorsReadTheForceTheyAreCalibratedFor) {
  // One reading, each sensor's conversion against the force it was made from.
  sim::SensorReading reading;
  reading.dynamometer_fx_n = 300.0;
  reading.dynamometer_fy_n = -400.0;
  ForceSensorSettings dynamometer;
  EXPECT_DOUBLE_EQ(sensed_force_n(dynamometer, reading, 600.0), 500.0);

  const ForceSensorSettings currents = current_sensor();
  reading.ix_a = currents.calibration.x.a_a + currents.calibration.x.b_a_per_n * 300.0;
  reading.iy_a = currents.calibration.y.a_a + currents.calibration.y.b_a_per_n * 400.0;
  EXPECT_NEAR(sensed_force_n(currents, reading, 600.0), 500.0, 1e-9);

  // 1 kW at 600 rev/min on a 10 mm radius: torque 1000 / (20π) N·m, F_t = torque / 0.01 m = 1591.5 N.
  ForceSensorSettings spindle;
  spindle.sensor = ForceSensor::kSpindlePower;
  spindle.tool_radius_mm = 10.0;
  reading.spindle_power_w = 1000.0;
  EXPECT_NEAR(sensed_force_n(spindle, reading, 600.0), 1000.0 / (600.0 / 60.0 * 2.0 * std::numbers::pi) / 0.01, 1e-9);
  EXPECT_NEAR(sensed_force_n(spindle, reading, 600.0), 1591.549, 1e-3);
}

TEST(OverrideControl, BadSettingsAreNamed) {
  OverrideControlSettings settings = alone_settings();
  settings.min_ratio = 2.0;
  settings.sensor.calibration.x.b_a_per_n = 0.0;
  const std::vector<InputProblem> problems = validate(settings);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].field, "control.sensor.calibration.x.b_a_per_n");
  EXPECT_EQ(problems[1].field, "control.min_ratio");
  ControllerSettings controller;
  controller.kind = ControllerKind::kVariableGain;
  controller.target_force_n = kTargetN;
  controller.loop_gain_per_s = 0.0;
  EXPECT_THROW(make_control_law(controller), InputError);
  EXPECT_EQ(controller_named("variable-gain-lathe"), ControllerKind::kVariableGainLathe);
  EXPECT_FALSE(controller_named("pid").has_value());
  EXPECT_EQ(force_sensor_named("spindle"), ForceSensor::kSpindlePower);
}

}  // namespace
}  // namespace feedplan::trial
