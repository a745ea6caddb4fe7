// Mechanistic force kernel throughput: per-revolution peak predictions per second on a trochoid's
// front engagement (an arc from the front of the tool to its right side, as a climb-milling trochoid
// loop cuts it), as one section and as three sections left by earlier layers, without and with the
// size effect and runout. A plan has about 7 000 samples, and a feed solve evaluates the peak about 10
// to 20 times per sample with bisection, a handful with the secant method (the peak is nearly affine in the
// feed), so 7 000 samples × one feed solve must fit in well under 1 s. And the peak a ringing dynamometer
// reads of the same force (model/sensed_peak.hpp: the kernel at 720 angles over the revolution, through the
// sensor's modes), which identification through the sensor evaluates many times.
//
// Run: build/bench/mechanistic_bench

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/sensed_peak.hpp"

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

const std::vector<ImmersionArc> kLow{{1.6, 2.9}}, kMiddle{{1.9, 2.9}}, kHigh{{2.2, 2.9}};

std::vector<EngagedSection> trochoid_front(int64_t sections) {
  if (sections == 1) return {{0.0, 10.0, kLow}};
  return {{0.0, 4.0, kLow}, {4.0, 7.0, kMiddle}, {7.0, 10.0, kHigh}};
}

// state.range(0): sections (1 or 3); range(1): size effect; range(2): runout.
void BM_MechanisticPeakTrochoidFront(benchmark::State& state) {
  const std::vector<EngagedSection> sections = trochoid_front(state.range(0));
  const MechanisticModel model = al7075(state.range(1) != 0, state.range(2) != 0);
  const CutterGeometry cutter{5.0, 4, 30.0};
  double fz = 0.05;
  for (auto _ : state) {
    benchmark::DoNotOptimize(predicted_peak_force_n(model, sections, cutter, fz));
    fz = fz < 0.15 ? fz + 1e-4 : 0.05;  // a feed solve's varying feed
  }
  state.SetItemsProcessed(state.iterations());
}

// One feed solve as a planner would run it per sample: the feed per tooth whose peak is 400 N, by the
// secant method from f_z = 0.02 and 0.2 mm to 0.1 % of the target (the peak is nearly affine in f_z:
// cutting terms grow with it, edge terms do not). Counts the predictions a solve takes.
void BM_MechanisticFeedSolveTrochoidFront(benchmark::State& state) {
  const std::vector<EngagedSection> sections = trochoid_front(state.range(0));
  const MechanisticModel model = al7075(state.range(1) != 0, state.range(2) != 0);
  const CutterGeometry cutter{5.0, 4, 30.0};
  constexpr double kTargetN = 400.0;
  long long predictions = 0;
  for (auto _ : state) {
    double f0 = 0.02, f1 = 0.2;
    double g0 = predicted_peak_force_n(model, sections, cutter, f0) - kTargetN;
    double g1 = predicted_peak_force_n(model, sections, cutter, f1) - kTargetN;
    predictions += 2;
    while (std::abs(g1) > 1e-3 * kTargetN) {
      const double f2 = std::max(1e-4, f1 - g1 * (f1 - f0) / (g1 - g0));
      f0 = f1, g0 = g1, f1 = f2;
      g1 = predicted_peak_force_n(model, sections, cutter, f1) - kTargetN;
      ++predictions;
    }
    benchmark::DoNotOptimize(f1);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["predictions_per_solve"] = static_cast<double>(predictions) / static_cast<double>(state.iterations());
}

// The sensed peak at 2546 rpm through a plate ringing at 605 Hz, ζ 0.38 on both axes; range(0): sections.
void BM_SensedPeakTrochoidFront(benchmark::State& state) {
  const std::vector<EngagedSection> sections = trochoid_front(state.range(0));
  const MechanisticModel model = al7075(true, true);
  const CutterGeometry cutter{5.0, 4, 30.0};
  SensorResponse sensor;
  sensor.modes[0] = sensor.modes[1] = {605.0, 0.38};
  double fz = 0.05;
  for (auto _ : state) {
    benchmark::DoNotOptimize(predicted_sensed_peak(model, sections, cutter, fz, sensor, 2546.0).force_n);
    fz = fz < 0.15 ? fz + 1e-4 : 0.05;
  }
  state.SetItemsProcessed(state.iterations());
}

BENCHMARK(BM_SensedPeakTrochoidFront)->ArgNames({"sections"})->Arg(1)->Arg(3)->Unit(benchmark::kMicrosecond);

BENCHMARK(BM_MechanisticFeedSolveTrochoidFront)
    ->ArgNames({"sections", "size_effect", "runout"})
    ->Args({1, 0, 0})
    ->Args({3, 0, 0})
    ->Args({3, 1, 0})
    ->Args({3, 1, 1})
    ->Unit(benchmark::kMicrosecond);

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
