// Virtual machine speed: simulated seconds per wall-clock second on the sample trochoid (seed 003
// Table 2, 10 loops) run at a constant feed (f_z 0.05 mm at 2800 rpm, 560 mm/min, about 40 s of
// program) in S50C-like steel with the default resolution (1° spindle steps, 0.25 mm slices). A 30 s
// program must simulate in well under a minute on one core.

#include <benchmark/benchmark.h>

#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace {

using namespace feedplan;

sim::SimulationRequest trochoid_request() {
  const auto spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid.yaml");
  const auto cycle = cycles::generate(spec);
  sim::SimulationRequest request;
  request.program.path = cycle.path;
  for (const auto& move : cycle.path.moves) {
    geometry::BlockCommand block;
    block.feed_mm_per_min = move.kind == geometry::MoveKind::kRapid ? 0.0 : 560.0;
    block.spindle_rpm = 2800;
    block.spindle = geometry::SpindleDirection::kClockwise;
    request.program.blocks.push_back(block);
  }
  request.stock = cycle.stock;
  request.tool = spec.tool;
  request.coefficients.ktc_n_per_mm2 = 2000;  // docs/method.md §6.2 medium-carbon steel
  request.coefficients.krc_n_per_mm2 = 600;
  request.coefficients.kac_n_per_mm2 = 300;
  request.coefficients.kte_n_per_mm = 20;
  request.coefficients.kre_n_per_mm = 20;
  request.coefficients.kae_n_per_mm = 5;
  request.machine.max_accel_mm_per_s2 = spec.machine.max_accel_mm_per_s2;
  request.machine.rapid_feed_mm_per_min = spec.machine.rapid_feed_mm_per_min;
  return request;
}

void BM_SimulateTrochoidSample(benchmark::State& state) {
  const sim::SimulationRequest request = trochoid_request();
  double simulated_s = 0.0;
  long long steps = 0;
  for (auto _ : state) {
    const auto result = sim::simulate(request);
    simulated_s = result.summary.cycle_time_s;
    steps = result.summary.steps;
    benchmark::DoNotOptimize(result);
  }
  state.counters["simulated_s"] = simulated_s;
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["simulated_s_per_wall_s"] =
      benchmark::Counter(simulated_s * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_SimulateTrochoidSample)->Unit(benchmark::kSecond)->Iterations(2);

}  // namespace

BENCHMARK_MAIN();
