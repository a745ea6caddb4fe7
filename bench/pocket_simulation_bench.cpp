// Virtual machine at shop size: the pocket sample (samples/pocket.yaml: 60 × 40 × 10 mm, helical
// bore, spiral, trochoid slots, finishing) planned at 650 N — a program of about 5 000 lines — read
// back and run as `feedplan simulate` runs it: the force
// log streamed to a file, the per-revolution peaks kept. Counters: simulated seconds, internal steps,
// engagement samples computed, and the process's peak resident memory (run one benchmark per
// process, --benchmark_filter, for its own peak).
//
// The program is not committed (it is the planner's output); make it once with
//   build/cli/feedplan plan samples/pocket.yaml -o build/bench/pocket.nc --target-force 650
// or point FEEDPLAN_BENCH_POCKET_PROGRAM at another one. Two runs: as `feedplan simulate` runs it —
// the layers above a re-cut helix share the lowest layer's engagement where the re-cutting tracks lie
// within the program's number resolution of the helix's (SimulationOptions::recut_tolerance_mm unset:
// 1.4 µm for 3 decimals) — and with tracks re-cut only exactly (1e-9 mm), every layer of the bore
// computed along the whole path.

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/force_log/force_log_file_writer.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace {

using namespace feedplan;

std::string pocket_program_path() {
  const char* path = std::getenv("FEEDPLAN_BENCH_POCKET_PROGRAM");
  return path ? path : FEEDPLAN_BENCH_POCKET_PROGRAM;
}

sim::SimulationRequest pocket_request() {
  const auto spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/pocket.yaml");
  const auto materials = sim::load_materials(std::string(FEEDPLAN_DATA_DIR) + "/materials.yaml");
  sim::SimulationRequest request;
  request.program = gcode::load_program(pocket_program_path());
  request.stock = cycles::generate(spec).stock;
  request.tool = spec.tool;
  request.coefficients = materials.get(spec.material, "material").coefficients;
  request.machine = spec.machine;
  request.options.default_spindle_rpm = spec.spindle_rpm;
  return request;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // kB on Linux
}

void simulate_pocket_sample(benchmark::State& state, std::optional<double> recut_tolerance_mm) {
  if (!std::filesystem::exists(pocket_program_path())) {
    state.SkipWithError(("no program at " + pocket_program_path() + ": make it with feedplan plan samples/pocket.yaml "
                         "-o build/bench/pocket.nc --target-force 650").c_str());
    return;
  }
  sim::SimulationRequest request = pocket_request();
  request.options.recut_tolerance_mm = recut_tolerance_mm;
  const std::string log_path = (std::filesystem::temp_directory_path() / "feedplan_pocket_bench_log.csv").string();
  sim::SimulationSummary summary;
  for (auto _ : state) {
    force_log::ForceLogFileWriter log(log_path);
    request.log_sink = &log;
    summary = sim::simulate(request).summary;
    if (!log.finish().empty()) state.SkipWithError("the force log could not be written");
  }
  std::filesystem::remove(log_path);
  state.counters["simulated_s"] = summary.cycle_time_s;
  state.counters["steps"] = static_cast<double>(summary.steps);
  state.counters["engagement_samples"] = static_cast<double>(summary.engagement_samples);
  state.counters["recut_tolerance_um"] = summary.recut_tolerance_mm * 1e3;
  state.counters["peak_rss_mb"] = peak_rss_mb();
}

void BM_SimulatePocketSample(benchmark::State& state) { simulate_pocket_sample(state, std::nullopt); }
void BM_SimulatePocketSampleExactRecut(benchmark::State& state) { simulate_pocket_sample(state, 1e-9); }

BENCHMARK(BM_SimulatePocketSample)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK(BM_SimulatePocketSampleExactRecut)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
