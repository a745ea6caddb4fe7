// Learning speed: one learning step (align the force log, per-revolution and per-tooth-period samples,
// RLS, robust batch refit, learning along the path) plus the re-plan of the 10-loop trochoid sample (seed 003 Table 2) — what seed 003 did in the
// air cut between two cycles. The log is the virtual machine's, simulated once before timing and held as
// read from its file; BM_ReadLogTrochoid and BM_ReplanTrochoid time the two halves apart.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/learning/model_update.hpp"
#include "feedplan/learning/path_correction.hpp"
#include "feedplan/learning/sensor_dynamics.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/sim/material.hpp"

namespace {

using namespace feedplan;

struct Setup {
  planner::PlanGeometry geometry;
  planner::PlanSettings settings;
  planner::PlanResult plan;
  force_log::ForceLog log;
};

const Setup& setup() {
  static const Setup s = [] {
    Setup out;
    const auto spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid.yaml");
    const auto cycle = cycles::generate(spec);
    out.geometry = planner::analyse(cycle.path, cycle.stock, spec.tool);
    model::ResponseSurfaceModel model;  // the sample database's magnitude for S50C, D10 Z4, a_p 10 mm
    model.beta = {300.0, 180.0, 40.0, -8.0, -4.0, 12.0};
    model.chip_center_mm = 0.05;
    model.chip_scale_mm = 0.04;
    model.contact_length_center_mm = 4.0;
    model.contact_length_scale_mm = 2.0;
    model.range = {0.005, 0.15, 0.0, 8.0};
    model.axial_depth_mm = 10.0;
    out.settings.model = model;
    out.settings.target_force_n = spec.target_force_n;
    out.settings.spindle_rpm = spec.spindle_rpm;
    out.settings.machine = spec.machine;
    out.plan = planner::plan(out.geometry, out.settings);
    trial::VirtualMachine machine;
    machine.tool = spec.tool;
    machine.coefficients =
        sim::load_materials(std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/materials.yaml").get("S50C").coefficients;
    machine.stock = cycle.stock;
    machine.machine = spec.machine;
    machine.spindle_rpm = spec.spindle_rpm;
    out.log = trial::run_on_virtual_machine(out.plan.program, machine, out.plan, spec.target_force_n).simulation.log;
    return out;
  }();
  return s;
}

void BM_LearnAndReplanTrochoid(benchmark::State& state) {
  const Setup& s = setup();
  std::size_t samples = 0;
  std::size_t tooth_periods = 0;
  const std::vector<learning::NamedLog> logs{{"cycle", s.log}};  // as read from the file, once
  for (auto _ : state) {
    const learning::ModelUpdate update =
        learning::update_model(s.plan, s.settings, s.geometry.tool.flutes, logs, {}, std::nullopt);
    // The same program again: its own model with the correction learned along the path.
    planner::PlanSettings next = s.settings;
    std::vector<learning::MeasuredRevolutions> measured;
    for (const auto& log : update.logs) measured.push_back(log.revolutions);
    next.force_correction = learning::learn_along_path(s.plan, s.settings.model, measured, s.settings.target_force_n, {}).correction;
    auto result = planner::plan(s.geometry, next);
    samples = update.samples.size();
    tooth_periods = update.logs.empty() ? 0 : update.logs.front().revolutions.tooth_periods.size();
    benchmark::DoNotOptimize(result);
  }
  state.counters["revolutions"] = static_cast<double>(samples);
  state.counters["tooth_periods"] = static_cast<double>(tooth_periods);
  state.counters["log_rows"] = static_cast<double>(s.log.rows.size());
}

BENCHMARK(BM_LearnAndReplanTrochoid)->Unit(benchmark::kMillisecond);

// Its parts: reading the log (align, revolutions, noise, refits) ...
void BM_ReadLogTrochoid(benchmark::State& state) {
  const Setup& s = setup();
  const std::vector<learning::NamedLog> logs{{"cycle", s.log}};
  for (auto _ : state) {
    auto update = learning::update_model(s.plan, s.settings, s.geometry.tool.flutes, logs, {}, std::nullopt);
    benchmark::DoNotOptimize(update);
  }
}
BENCHMARK(BM_ReadLogTrochoid)->Unit(benchmark::kMillisecond);

// ... and the re-plan with the correction learned along the path.
void BM_ReplanTrochoid(benchmark::State& state) {
  const Setup& s = setup();
  const learning::ModelUpdate update =
      learning::update_model(s.plan, s.settings, s.geometry.tool.flutes, {{"cycle", s.log}}, {}, std::nullopt);
  planner::PlanSettings next = s.settings;
  std::vector<learning::MeasuredRevolutions> measured;
  for (const auto& log : update.logs) measured.push_back(log.revolutions);
  next.force_correction = learning::learn_along_path(s.plan, s.settings.model, measured, s.settings.target_force_n, {}).correction;
  for (auto _ : state) {
    auto result = planner::plan(s.geometry, next);
    benchmark::DoNotOptimize(result);
  }
}
BENCHMARK(BM_ReplanTrochoid)->Unit(benchmark::kMillisecond);

// The dynamometer's factor per sample of the trochoid's plan (learning/sensor_dynamics.hpp), what `loop` and
// `learn` add when given a dynamometer's mode: the chip's shape alone, and with the sample tool's mechanistic
// model in S50C, for a dynamometer like the family's (1500 Hz, ζ 0.6: no factor over the cap, no kernel
// evaluated) and a soft one (275 Hz, ζ 0.3: the kernel's variants evaluated in the steady cut).
void BM_SensorFactorsTrochoid(benchmark::State& state, double natural_frequency_hz, double damping_ratio,
                              bool with_kernel) {
  const Setup& s = setup();
  model::MechanisticModel kernel;  // the sample database's: the library's S50C as its cutting tests gave it
  kernel.ktc_n_per_mm2 = 1998.5;
  kernel.krc_n_per_mm2 = 598.3;
  kernel.kte_n_per_mm = 19.94;
  kernel.kre_n_per_mm = 19.99;
  const learning::SensorKernel shape{with_kernel ? &kernel : nullptr, planner::sample_feeds_mm_per_min(s.plan)};
  double above_cap = 0.0;
  for (auto _ : state) {
    const std::vector<double> gains = learning::sensor_peak_gains(s.geometry.engagement, s.geometry.tool,
                                                                  s.settings.spindle_rpm,
                                                                  {natural_frequency_hz, damping_ratio}, shape);
    above_cap = static_cast<double>(
        std::count_if(gains.begin(), gains.end(), [](double g) { return g > learning::kMaxSensorPeakGain; }));
    benchmark::DoNotOptimize(gains);
  }
  state.counters["samples_over_cap"] = above_cap;
}
BENCHMARK_CAPTURE(BM_SensorFactorsTrochoid, stiff_chip_shape, 1500.0, 0.6, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SensorFactorsTrochoid, stiff_with_kernel, 1500.0, 0.6, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SensorFactorsTrochoid, soft_chip_shape, 275.2, 0.3, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SensorFactorsTrochoid, soft_with_kernel, 275.2, 0.3, true)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
