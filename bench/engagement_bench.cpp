// Engagement throughput on the bundled samples: samples per second of compute_engagement at
// ds = 0.05 mm (the default). Users re-plan between two parts, so a 10-loop trochoid must profile
// in well under 0.1 s; the aim is ≥ 1 M samples/s per core.

#include <benchmark/benchmark.h>

#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/geometry/engagement.hpp"

namespace {

using namespace feedplan;

void profile_sample(benchmark::State& state, const std::string& name) {
  const auto spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + name);
  const auto cycle = cycles::generate(spec);
  std::size_t samples = 0;
  for (auto _ : state) {
    auto profile = geometry::compute_engagement(cycle.path, cycle.stock, spec.tool.radius_mm(), {.ds_mm = 0.05});
    samples = profile.samples.size();
    benchmark::DoNotOptimize(profile);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * samples));
  state.counters["samples"] = static_cast<double>(samples);
}

void BM_EngagementTrochoidSample(benchmark::State& state) { profile_sample(state, "trochoid.yaml"); }
void BM_EngagementSpiralSample(benchmark::State& state) { profile_sample(state, "spiral.yaml"); }
void BM_EngagementCornerSample(benchmark::State& state) { profile_sample(state, "corner.yaml"); }
void BM_EngagementPocketSample(benchmark::State& state) { profile_sample(state, "pocket.yaml"); }

BENCHMARK(BM_EngagementTrochoidSample)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EngagementSpiralSample)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EngagementCornerSample)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EngagementPocketSample)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
