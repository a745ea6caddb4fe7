// How learning converges on machines whose physics differ from the model in shape: for each machine of
// the seeded family (data/machines/family) and each sample cycle, the best achievable plan T* (the
// feeds searched against the virtual machine's true peaks, trial/best_achievable_plan.hpp) and three
// learning cycles from the sample model, reported as counters — cycle time over T*, and the largest and
// RMS error of the true per-revolution peaks over the revolutions the plan holds at the target, and the
// best plan's own largest held error (T*_held_max%; T*_steady_max% and cK_steady_max% over the steady held
// revolutions alone: straight cuts and steady arcs, planner/peak_comparison.hpp; cK_steady_mean% their mean
// signed error).
//
// The figures are quoted, never asserted (the learning tests assert the bounds on three machines).
// Slow: a T* search is up to 20 runs of the virtual machine. Choose with the environment:
//   FEEDPLAN_FAMILY_MACHINES  machine numbers, e.g. "02,04,09" (default: all 12)
//   FEEDPLAN_FAMILY_DIR       the family's directory (default data/machines/family): another draw of the
//                             family (scripts/generate-machine-family.sh OUT_DIR SEED) checks that what was
//                             measured on the checked-in machines holds on machines it was not tuned on
//   FEEDPLAN_FAMILY_SAMPLES   sample specs, e.g. "trochoid,spiral,corner" (default: trochoid)
//   FEEDPLAN_FAMILY_TARGETS   target force per sample, N, e.g. "400,400,350" (default: the spec's own)
//   FEEDPLAN_FAMILY_NEAR_FLOOR a factor, e.g. "1.05": the target is that factor × the machine's force floor
//                             for the sample instead (the largest true per-revolution peak with the plan run at
//                             the machine's minimum feed wherever it cuts; one more run of the virtual machine,
//                             a long one), reported as floor_N
//   FEEDPLAN_FAMILY_NO_T_STAR set: learning only (the counters over T* are then 0)
//   FEEDPLAN_FAMILY_T_STAR_ONLY set: the T* search only (the learning counters are then absent)
//   FEEDPLAN_FAMILY_NO_SENSOR set: peaks taken as read (default: corrected for the machine's dynamometer
//                             mode as its tap test gives it, as `loop --sensor-hz --sensor-damping`)
//   FEEDPLAN_FAMILY_CHIP_SHAPE set: the dynamometer's factor from the chip's shape everywhere (default: from the
//                             sample database's mechanistic model where the engagement is steady, as `loop`)
//   FEEDPLAN_FAMILY_CYCLES    learning cycles (default 3; the counters c1_…, c2_…, … for each)
//   FEEDPLAN_FAMILY_SEED      the dynamometer noise's seed (default 1): a cycle's largest errors are single
//                             revolutions, and how large they come out depends on the draw of the noise
//   FEEDPLAN_FAMILY_NO_NOISE  set: a dynamometer without noise (what the noise costs, apart from the rest)
//   FEEDPLAN_FAMILY_IDEAL_SENSOR set: a dynamometer of 100 kHz (ζ 0.7) without noise, read as it is (what the
//                             sensor's mode and noise cost together: the machine's physics alone; slow — the
//                             virtual machine steps fast enough for that bandwidth)
//   FEEDPLAN_FAMILY_PHASES    a count N in [2, 20]: instead of T* and learning, the sample model's first plan is
//                             cut N times with the spindle — and with it every feed — k per mille faster (k = 0 …
//                             N − 1): the same chip per tooth at every place, the teeth at other angles there. The
//                             counters give how far the true per-revolution peak at one place spreads over the N
//                             cuts (max / min − 1, at every 0.02 mm of path where every cut has a revolution over
//                             100 N in the cut), its median, 90th and 99th percentile and largest value, over
//                             steady held revolutions (steady_…) and over held ones that are not steady — entries
//                             and exits, where the engagement changes within a turn (entry_…): what no feed per
//                             place can hold, as a plan cannot set the spindle's angle at a place
//   FEEDPLAN_FAMILY_REVOLUTIONS a directory: also write, per sample and machine, every true per-revolution peak
//                             of each learning cycle and of the best plan (cut once more; cycle "best") as
//                             SAMPLE-family-NN.csv (the columns of `loop --revolutions`): where the errors are
// Run: build/bench/learning_convergence_bench --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/peak_comparison.hpp"
#include "feedplan/planner/revolution_table.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/trial/best_achievable_plan.hpp"
#include "feedplan/trial/learning_loop.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"

namespace {

using namespace feedplan;
namespace fs = std::filesystem;

std::vector<std::string> split(const char* text, const std::string& fallback) {
  std::vector<std::string> out;
  std::stringstream in(text && *text ? text : fallback);
  for (std::string item; std::getline(in, item, ',');) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// The sample model (the sample database's S50C, D10 Z4), read once into a throwaway database.
// The sample database's models of the sample tool in S50C: the response surface and the mechanistic model.
struct SampleModels {
  model_db::ModelRecord response_surface;
  model::MechanisticModel mechanistic;
};

const SampleModels& sample_models() {
  static const SampleModels models = [] {
    const fs::path dir = fs::temp_directory_path() / ("feedplan_convergence_bench_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    SampleModels out;
    {
      auto store = model_db::Store::open(dir / "m.db", model_db::OpenMode::kCreate);
      model_db::import_from_file(store, fs::path(FEEDPLAN_TEST_DATA_DIR) / "cli" / "s50c_d10_model.json");
      model_db::import_from_file(store, fs::path(FEEDPLAN_TEST_DATA_DIR) / "cli" / "s50c_d10_mechanistic.json");
      out.response_surface = *store.active_model("SC EM D10 Z4", "S50C");
      out.mechanistic = store.active_model("SC EM D10 Z4", "S50C", model_db::ModelKind::kMechanistic)->mechanistic->model;
    }
    fs::remove_all(dir);
    return out;
  }();
  return models;
}

const model_db::ModelRecord& sample_model() { return sample_models().response_surface; }

// The loop request for one sample on one machine file, as `feedplan loop SPEC --machine FILE`.
trial::LoopRequest request_for(const std::string& sample, const std::string& machine_path, double target_force_n) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + sample + ".yaml");
  const cycles::Cycle cycle = cycles::generate(spec);
  trial::LoopRequest request;
  request.geometry = planner::analyse(cycle.path, cycle.stock, spec.tool);
  request.settings.model = sample_model().model;
  request.settings.target_force_n = target_force_n > 0.0 ? target_force_n : spec.target_force_n;
  request.settings.spindle_rpm = spec.spindle_rpm;
  request.settings.machine = spec.machine;
  request.start_fit_covariance = sample_model().fit.covariance;
  const sim::MaterialLibrary materials = sim::load_materials(std::string(FEEDPLAN_DATA_DIR) + "/materials.yaml");
  const sim::MachineFile file = sim::load_machine_file(machine_path, materials);
  trial::use_machine_file(request.machine, file, spec.tool);
  if (!std::getenv("FEEDPLAN_FAMILY_NO_SENSOR")) {
    request.sensor = trial::dynamometer_mode(file.dynamometer);
    if (!std::getenv("FEEDPLAN_FAMILY_CHIP_SHAPE")) request.sensor_kernel = sample_models().mechanistic;
  }
  request.machine.stock = cycle.stock;
  request.machine.machine = spec.machine;
  request.machine.spindle_rpm = spec.spindle_rpm;
  if (const char* seed = std::getenv("FEEDPLAN_FAMILY_SEED")) {
    const std::string text = seed;
    std::uint64_t value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
      std::fprintf(stderr, "FEEDPLAN_FAMILY_SEED = \"%s\": must be a whole number ≥ 0 (the noise's seed)\n", seed);
      std::exit(2);
    }
    request.machine.sensors.seed = value;
  }
  if (std::getenv("FEEDPLAN_FAMILY_NO_NOISE")) request.machine.sensors.dynamometer.noise_n = 0.0;
  if (std::getenv("FEEDPLAN_FAMILY_IDEAL_SENSOR")) {
    request.machine.sensors.dynamometer.bandwidth_hz = 100000.0;
    request.machine.sensors.dynamometer.damping_ratio = 0.7;
    request.machine.sensors.dynamometer.noise_n = 0.0;
    request.sensor.reset();
  }
  return request;
}

// The file of family machine `machine` ("01" …): in FEEDPLAN_FAMILY_DIR, else data/machines/family.
std::string machine_path(const std::string& machine) {
  const char* dir = std::getenv("FEEDPLAN_FAMILY_DIR");
  return (dir && *dir ? std::string(dir) : std::string(FEEDPLAN_DATA_DIR) + "/machines/family") + "/family-" + machine +
         ".yaml";
}

// The force floor of the loop's cycle on its machine: the largest true per-revolution peak in the cut with
// every engaged sample planned at the machine's minimum feed (a target of 1 N, which no feed meets), N.
double force_floor_n(const trial::LoopRequest& loop) {
  planner::PlanSettings settings = loop.settings;
  settings.target_force_n = 1.0;
  const planner::PlanResult plan = planner::plan(loop.geometry, settings);
  trial::VirtualMachine machine = loop.machine;
  machine.keep_log = false;
  const trial::VirtualMachineRun run = trial::run_on_virtual_machine(plan.program, machine, plan, settings.target_force_n);
  double floor_n = 0.0;
  for (const planner::RevolutionComparison& r : run.comparison.revolutions) {
    if (r.in_cut) floor_n = std::max(floor_n, r.revolution.peak_n);
  }
  return floor_n;
}

// The revolution of `revolutions` (in path order) whose span holds s_mm, or null.
const planner::RevolutionComparison* revolution_at(const std::vector<planner::RevolutionComparison>& revolutions,
                                                   double s_mm) {
  auto after = std::upper_bound(revolutions.begin(), revolutions.end(), s_mm,
                                [](double s, const planner::RevolutionComparison& r) { return s < r.revolution.s_start_mm; });
  if (after == revolutions.begin()) return nullptr;
  const planner::RevolutionComparison& r = *(after - 1);
  return s_mm <= r.revolution.s_end_mm ? &r : nullptr;
}

// The mean signed error over the steady held revolutions, % (0 without one): a bias there is the
// dynamometer correction's or the model's, not the spindle's phase.
double steady_mean_error_percent(const planner::PeakComparison& comparison) {
  double sum = 0.0;
  int count = 0;
  for (const planner::RevolutionComparison& r : comparison.revolutions) {
    if (!r.steady) continue;
    sum += r.error_percent;
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

// The spread of the true peak at one place over cuts of one plan at other spindle phases (FEEDPLAN_FAMILY_PHASES),
// as counters `<prefix>p50%`, …, `<prefix>max%` and `<prefix>places`.
void count_spreads(benchmark::State& state, const std::string& prefix, std::vector<double> spreads) {
  std::sort(spreads.begin(), spreads.end());
  const auto at = [&](double q) {
    return spreads.empty() ? 0.0 : 100.0 * spreads[static_cast<std::size_t>(q * static_cast<double>(spreads.size() - 1))];
  };
  state.counters[prefix + "p50%"] = at(0.5);
  state.counters[prefix + "p90%"] = at(0.9);
  state.counters[prefix + "p99%"] = at(0.99);
  state.counters[prefix + "max%"] = at(1.0);
  state.counters[prefix + "places"] = static_cast<double>(spreads.size());
}

void BM_PeakSpreadOverSpindlePhases(benchmark::State& state, const std::string& sample, const std::string& path,
                                    double target_force_n, int phases) {
  constexpr double kPlaceStepMm = 0.02;
  constexpr double kSmallestPeakN = 100.0;
  const trial::LoopRequest loop = request_for(sample, path, target_force_n);
  std::vector<std::vector<planner::RevolutionComparison>> cuts;
  for (auto _ : state) {
    cuts.clear();
    for (int k = 0; k < phases; ++k) {
      planner::PlanSettings settings = loop.settings;
      settings.spindle_rpm *= 1.0 + 0.001 * k;
      const planner::PlanResult plan = planner::plan(loop.geometry, settings);
      trial::VirtualMachine machine = loop.machine;
      machine.keep_log = false;
      machine.spindle_rpm = settings.spindle_rpm;
      cuts.push_back(trial::run_on_virtual_machine(plan.program, machine, plan, settings.target_force_n).comparison.revolutions);
    }
  }
  std::vector<double> steady;
  std::vector<double> entry;
  const auto& first = cuts.front();
  if (!first.empty()) {
    for (double s_mm = first.front().revolution.s_start_mm; s_mm < first.back().revolution.s_end_mm; s_mm += kPlaceStepMm) {
      double lo = 0.0;
      double hi = 0.0;
      bool every = true;
      for (const auto& cut : cuts) {
        const planner::RevolutionComparison* r = revolution_at(cut, s_mm);
        if (!r || !r->in_cut || !(r->revolution.peak_n > kSmallestPeakN)) {
          every = false;
          break;
        }
        lo = lo > 0.0 ? std::min(lo, r->revolution.peak_n) : r->revolution.peak_n;
        hi = std::max(hi, r->revolution.peak_n);
      }
      const planner::RevolutionComparison* reference = revolution_at(first, s_mm);
      if (!every || !reference->held) continue;
      (reference->steady ? steady : entry).push_back(hi / lo - 1.0);
    }
  }
  count_spreads(state, "steady_", steady);
  count_spreads(state, "entry_", entry);
}

// The best plan (its force correction on the machine's own physics, as the search planned it) cut once more:
// its revolutions, which the search keeps only as figures.
planner::PeakComparison best_plan_cut_again(const trial::LoopRequest& loop, const trial::BestPlan& best) {
  planner::PlanSettings settings = trial::planned_with_own_physics(loop.settings, loop.machine);
  settings.force_correction = best.force_correction;
  const planner::PlanResult plan = planner::plan(loop.geometry, settings);
  return trial::run_on_virtual_machine(plan.program, loop.machine, plan, settings.target_force_n).comparison;
}

void write_table(const std::string& path, const std::string& text) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file || std::fputs(text.c_str(), file) < 0 || std::fclose(file) != 0) {
    std::fprintf(stderr, "FEEDPLAN_FAMILY_REVOLUTIONS: cannot write %s\n", path.c_str());
    std::exit(2);
  }
}

void BM_LearningAgainstBestAchievable(benchmark::State& state, const std::string& sample, const std::string& machine,
                                      double target_force_n) {
  trial::LoopRequest loop = request_for(sample, machine_path(machine), target_force_n);
  double floor_n = 0.0;
  if (const char* factor = std::getenv("FEEDPLAN_FAMILY_NEAR_FLOOR"); factor && *factor) {
    floor_n = force_floor_n(loop);
    loop.settings.target_force_n = std::atof(factor) * floor_n;
  }
  trial::BestPlan best;
  trial::LoopResult learned;
  for (auto _ : state) {
    trial::BestPlanRequest request;
    request.geometry = loop.geometry;
    request.settings = loop.settings;
    request.machine = loop.machine;
    if (!std::getenv("FEEDPLAN_FAMILY_NO_T_STAR")) best = trial::best_achievable_plan(request);
    if (std::getenv("FEEDPLAN_FAMILY_T_STAR_ONLY")) continue;
    loop.cycles = 3;
    if (const char* cycles = std::getenv("FEEDPLAN_FAMILY_CYCLES"); cycles && *cycles) {
      loop.cycles = std::atoi(cycles);
      if (loop.cycles < 1 || loop.cycles > 20) {
        std::fprintf(stderr, "FEEDPLAN_FAMILY_CYCLES = \"%s\": must be a whole number in [1, 20]\n", cycles);
        std::exit(2);
      }
    }
    learned = trial::run_learning_loop(loop);
  }
  const double t_star_s = best.best_cycle_time_s;
  std::string table;  // FEEDPLAN_FAMILY_REVOLUTIONS: the best plan's revolutions and every cycle's
  const char* table_dir = std::getenv("FEEDPLAN_FAMILY_REVOLUTIONS");
  if (table_dir && *table_dir) {
    table = planner::revolution_table_header();
    if (!best.force_correction.empty()) table += planner::revolution_table_rows("best", best_plan_cut_again(loop, best), loop.settings.target_force_n);
  }
  state.counters["target_N"] = loop.settings.target_force_n;
  state.counters["floor_N"] = floor_n;
  state.counters["T*_s"] = t_star_s;
  state.counters["infeasible"] = best.infeasible_samples;
  state.counters["T*_converged"] = best.converged ? 1.0 : 0.0;
  state.counters["T*_search"] = static_cast<double>(best.iterations.size());
  if (!best.iterations.empty()) state.counters["T*_last_over%"] = best.iterations.back().max_overshoot_percent;
  if (best.best_iteration >= 0) {  // the best plan's own largest held error
    const trial::BestPlanIteration& oracle = best.iterations[static_cast<std::size_t>(best.best_iteration)];
    state.counters["T*_held_max%"] = oracle.held_max_abs_error_percent;
    state.counters["T*_steady_max%"] = oracle.steady_max_abs_error_percent;
  }
  for (const trial::LoopCycle& c : learned.cycles) {
    std::string k = "c";  // built in place: GCC 12 warns (-Wrestrict, falsely) on "c" + std::to_string(…)
    k += std::to_string(c.cycle);
    state.counters[k + "_time/T*"] = t_star_s > 0.0 ? c.simulated_cycle_time_s / t_star_s : 0.0;
    state.counters[k + "_time_s"] = c.simulated_cycle_time_s;
    state.counters[k + "_max%"] = c.comparison.max_abs_error_percent;
    state.counters[k + "_rms%"] = c.comparison.rms_error_percent;
    state.counters[k + "_over%"] = c.comparison.max_overshoot_percent;
    state.counters[k + "_steady_max%"] = c.comparison.steady_max_abs_error_percent;
    state.counters[k + "_steady_mean%"] = steady_mean_error_percent(c.comparison);
    if (!table.empty()) table += planner::revolution_table_rows(std::to_string(c.cycle), c.comparison, loop.settings.target_force_n);
  }
  if (!table.empty()) write_table(std::string(table_dir) + "/" + sample + "-family-" + machine + ".csv", table);
}

int register_all() {
  const std::vector<std::string> machines =
      split(std::getenv("FEEDPLAN_FAMILY_MACHINES"), "01,02,03,04,05,06,07,08,09,10,11,12");
  const std::vector<std::string> samples = split(std::getenv("FEEDPLAN_FAMILY_SAMPLES"), "trochoid");
  const std::vector<std::string> targets = split(std::getenv("FEEDPLAN_FAMILY_TARGETS"), "");
  int phases = 0;
  if (const char* text = std::getenv("FEEDPLAN_FAMILY_PHASES"); text && *text) {
    phases = std::atoi(text);
    if (phases < 2 || phases > 20) {
      std::fprintf(stderr, "FEEDPLAN_FAMILY_PHASES = \"%s\": must be a whole number in [2, 20]\n", text);
      std::exit(2);
    }
  }
  if (const char* dir = std::getenv("FEEDPLAN_FAMILY_REVOLUTIONS"); dir && *dir && !fs::is_directory(dir)) {
    std::fprintf(stderr, "FEEDPLAN_FAMILY_REVOLUTIONS = \"%s\": not a directory (create it first)\n", dir);
    std::exit(2);
  }
  for (const std::string& machine : machines) {
    const std::string path = machine_path(machine);
    if (!fs::is_regular_file(path)) {
      std::fprintf(stderr,
                   "FEEDPLAN_FAMILY_MACHINES / FEEDPLAN_FAMILY_DIR: %s is not a file (expected family-NN.yaml for each "
                   "machine number; scripts/generate-machine-family.sh OUT_DIR SEED writes a family)\n",
                   path.c_str());
      std::exit(2);
    }
  }
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const double target_force_n = k < targets.size() ? std::atof(targets[k].c_str()) : 0.0;
    for (const std::string& machine : machines) {
      if (phases > 0) {
        std::string name = "phases/";
        name += samples[k] + "/family-" + machine;
        benchmark::RegisterBenchmark(name.c_str(), BM_PeakSpreadOverSpindlePhases, samples[k], machine_path(machine),
                                     target_force_n, phases)
            ->Iterations(1)
            ->Unit(benchmark::kSecond);
        continue;
      }
      std::string name = "learning/";
      name += samples[k] + "/family-" + machine;
      benchmark::RegisterBenchmark(name.c_str(),
                                   BM_LearningAgainstBestAchievable, samples[k], machine, target_force_n)
          ->Iterations(1)
          ->Unit(benchmark::kSecond);
    }
  }
  return 0;
}

const int registered = register_all();

}  // namespace

BENCHMARK_MAIN();
