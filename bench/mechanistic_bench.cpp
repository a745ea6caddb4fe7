// Mechanistic force kernel throughput: per-revolution peak predictions per second on a trochoid's
// front engagement (an arc from the front of the tool to its right side, as a climb-milling trochoid
// loop cuts it), as one section and as three sections left by earlier layers, without and with the
// size effect and runout. A plan has about 7 000 samples, and a feed solve evaluates the peak about 10
// to 20 times per sample, so 7 000 × 20 = 140 000 predictions must fit in well under 1 s.
//
// Run: build/bench/mechanistic_bench

#include <benchmark/benchmark.h>

#include <vector>

#include "feedplan/model/mechanistic_force.hpp"

namespace {

using namespace feedplan::model;

MechanisticModel al7075(bool size_effect, bool runout) {
  MechanisticModel k;
  k.ktc_n_per_mm2 = 796;
  k.krc_n_per_mm2 = 169;
  k.kac_n_per_mm2 = 222;
  k.kte_n_per_mm = 27.7;
  k.kre_n_per_mm = 30.8;
  k.kae_n_per_mm = 1.4;
  if (size_effect) k.size_exponent = 0.2;
  if (runout) k.runout_mm = {0.008, 0.0, 0.0, 0.0};
  return k;
}

// state.range(0): sections (1 or 3); range(1): size effect; range(2): runout.
void BM_MechanisticPeakTrochoidFront(benchmark::State& state) {
  const std::vector<ImmersionArc> low{{1.6, 2.9}}, middle{{1.9, 2.9}}, high{{2.2, 2.9}};
  std::vector<EngagedSection> sections;
  if (state.range(0) == 1) {
    sections = {{0.0, 10.0, low}};
  } else {
    sections = {{0.0, 4.0, low}, {4.0, 7.0, middle}, {7.0, 10.0, high}};
  }
  const MechanisticModel model = al7075(state.range(1) != 0, state.range(2) != 0);
  const CutterGeometry cutter{5.0, 4, 30.0};
  double fz = 0.05;
  for (auto _ : state) {
    benchmark::DoNotOptimize(predicted_peak_force_n(model, sections, cutter, fz));
    fz = fz < 0.15 ? fz + 1e-4 : 0.05;  // a feed solve's varying feed
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_MechanisticPeakTrochoidFront)
    ->ArgNames({"sections", "size_effect", "runout"})
    ->Args({1, 0, 0})
    ->Args({3, 0, 0})
    ->Args({1, 1, 0})
    ->Args({3, 1, 0})
    ->Args({1, 0, 1})
    ->Args({3, 1, 1})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
