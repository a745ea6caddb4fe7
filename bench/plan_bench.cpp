// Planning speed: the long trochoid slot (770 loops of the Table 2 trochoid, ≈ 100 000 blocks) —
// engagement once, then plan (what learning repeats between two parts), then the G-code text — and
// the 10-loop trochoid sample re-planned from its engagement (seed 003 re-planned in the air cut), with the
// response surface and with the mechanistic kind.
//
// To compare with LinuxCNC reading the same program: FEEDPLAN_BENCH_PROGRAM=/tmp/long.ngc makes the
// bench write the long program there once, then `time rs274 -g /tmp/long.ngc /tmp/long.out`.

#include <benchmark/benchmark.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace {

using namespace feedplan;

// A model of the sample database's magnitude for S50C, D10 Z4, a_p 10 mm (the bench needs no database).
model::ResponseSurfaceModel bench_model() {
  model::ResponseSurfaceModel model;
  model.beta = {300.0, 180.0, 40.0, -8.0, -4.0, 12.0};
  model.chip_center_mm = 0.05;
  model.chip_scale_mm = 0.04;
  model.contact_length_center_mm = 4.0;
  model.contact_length_scale_mm = 2.0;
  model.range = {0.005, 0.15, 0.0, 8.0};
  model.axial_depth_mm = 10.0;
  return model;
}

struct Job {
  cycles::CycleSpec spec;
  planner::PlanGeometry geometry;
  planner::PlanSettings settings;
};

Job make_job(double slot_length_mm) {
  Job job;
  job.spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid.yaml");
  auto trochoid = std::get<cycles::TrochoidSpec>(job.spec.geometry);
  trochoid.end = {slot_length_mm, 0.0};
  job.spec.geometry = trochoid;
  const cycles::Cycle cycle = cycles::generate(job.spec);
  job.geometry = planner::analyse(cycle.path, cycle.stock, job.spec.tool);
  job.settings.model = bench_model();
  job.settings.target_force_n = job.spec.target_force_n;
  job.settings.spindle_rpm = job.spec.spindle_rpm;
  job.settings.machine = job.spec.machine;
  return job;
}

const Job& long_job() {
  static const Job job = make_job(769.0);  // 770 loops
  return job;
}

void BM_EngagementLongTrochoid(benchmark::State& state) {
  const Job& job = long_job();
  const cycles::Cycle cycle = cycles::generate(job.spec);
  for (auto _ : state) {
    auto geometry = planner::analyse(cycle.path, cycle.stock, job.spec.tool);
    benchmark::DoNotOptimize(geometry);
  }
  state.counters["samples"] = static_cast<double>(job.geometry.engagement.samples.size());
}

void BM_PlanLongTrochoid(benchmark::State& state) {
  const Job& job = long_job();
  std::size_t blocks = 0;
  for (auto _ : state) {
    auto result = planner::plan(job.geometry, job.settings);
    blocks = result.blocks.size();
    benchmark::DoNotOptimize(result);
  }
  state.counters["blocks"] = static_cast<double>(blocks);
  state.counters["samples"] = static_cast<double>(job.geometry.engagement.samples.size());
}

void BM_WriteLongTrochoid(benchmark::State& state) {
  const Job& job = long_job();
  const planner::PlanResult result = planner::plan(job.geometry, job.settings);
  std::string text;
  for (auto _ : state) {
    text = gcode::write_gcode(result.program, {});
    benchmark::DoNotOptimize(text);
  }
  state.counters["blocks"] = static_cast<double>(result.blocks.size());
  state.counters["bytes"] = static_cast<double>(text.size());
  if (const char* path = std::getenv("FEEDPLAN_BENCH_PROGRAM"); path && *path) std::ofstream(path) << text;
}

void BM_ReplanTrochoidSample(benchmark::State& state) {
  static const Job job = make_job(9.0);  // the 10-loop sample
  for (auto _ : state) {
    auto result = planner::plan(job.geometry, job.settings);
    benchmark::DoNotOptimize(result);
  }
  state.counters["samples"] = static_cast<double>(job.geometry.engagement.samples.size());
}

// The 10-loop sample planned with the mechanistic kind: cutting and edge coefficients of S50C's size
// (data/materials.yaml) with 3 µm of runout on one tooth — the kernel's slower path, a peak scan over the
// whole revolution — beside the response surface's re-plan above.
void BM_PlanTrochoidSampleMechanistic(benchmark::State& state) {
  static const Job job = [] {
    Job j = make_job(9.0);
    model::MechanisticModel mechanistic;
    mechanistic.ktc_n_per_mm2 = 2000.0;
    mechanistic.krc_n_per_mm2 = 700.0;
    mechanistic.kte_n_per_mm = 20.0;
    mechanistic.kre_n_per_mm = 22.0;
    mechanistic.runout_mm = {0.003, 0.0, 0.0, 0.0};
    j.settings.mechanistic = mechanistic;
    return j;
  }();
  for (auto _ : state) {
    auto result = planner::plan(job.geometry, job.settings);
    benchmark::DoNotOptimize(result);
  }
  state.counters["samples"] = static_cast<double>(job.geometry.engagement.samples.size());
}

BENCHMARK(BM_EngagementLongTrochoid)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_PlanLongTrochoid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WriteLongTrochoid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ReplanTrochoidSample)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PlanTrochoidSampleMechanistic)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
