// The learning loop on the virtual machine (the corner-rounding case): plan with
// the sample database's S50C model, cut on a virtual machine whose true cutting coefficients are 1.5 ×
// the material's (the model is 33 % soft), learn, re-plan. The truth the test judges by is the virtual
// machine's own per-revolution peak force — mechanistic physics, not the response-surface model.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <filesystem>
#include <unistd.h>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/trial/best_achievable_plan.hpp"
#include "feedplan/trial/learning_loop.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/material.hpp"

namespace feedplan::trial {
namespace {

namespace fs = std::filesystem;

class LearningLoop : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("feedplan_loop_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    auto store = model_db::Store::open(dir_ / "t.db", model_db::OpenMode::kCreate);
    model_db::import_from_file(store, fs::path(FEEDPLAN_TEST_DATA_DIR) / "cli" / "s50c_d10_model.json");
    record_ = *store.active_model("SC EM D10 Z4", "S50C");
  }
  void TearDown() override { fs::remove_all(dir_); }

  LoopRequest corner_request(double machine_scale, double target_force_n) {
    return request_for("corner.yaml", machine_scale, target_force_n);
  }

  LoopRequest request_for(const std::string& sample, double machine_scale, double target_force_n) {
    const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + sample);
    const cycles::Cycle cycle = cycles::generate(spec);
    LoopRequest request;
    request.geometry = planner::analyse(cycle.path, cycle.stock, spec.tool);
    request.settings.model = record_.model;
    request.settings.target_force_n = target_force_n;
    request.settings.spindle_rpm = spec.spindle_rpm;
    request.settings.machine = spec.machine;
    const sim::MaterialLibrary materials = sim::load_materials(std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/materials.yaml");
    request.machine.tool = spec.tool;
    request.machine.coefficients = sim::scaled(materials.get("S50C").coefficients, machine_scale);
    request.machine.stock = cycle.stock;
    request.machine.machine = spec.machine;
    request.machine.spindle_rpm = spec.spindle_rpm;
    request.start_fit_covariance = record_.fit.covariance;
    return request;
  }

  //! The sample on a machine file of data/machines (its physics on the spec's catalogue tool), as `loop --machine`.
  LoopRequest request_on_machine(const std::string& sample, const std::string& machine_file, double target_force_n) {
    LoopRequest request = request_for(sample, 1.0, target_force_n);
    const sim::MaterialLibrary materials = sim::load_materials(std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/materials.yaml");
    const sim::MachineFile file =
        sim::load_machine_file(std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/machines/" + machine_file, materials);
    use_machine_file(request.machine, file, request.machine.tool);
    return request;
  }

  static void print_cycles(const std::string& machine, const LoopResult& result) {
    for (const LoopCycle& c : result.cycles) {
      std::printf("%s cycle %d: %.2f s, held RMS %.2f %%, max %.2f %% (steady %.2f %%), largest over %+.2f %%\n",
                  machine.c_str(), c.cycle, c.simulated_cycle_time_s, c.comparison.rms_error_percent,
                  c.comparison.max_abs_error_percent, c.comparison.steady_max_abs_error_percent,
                  c.comparison.max_overshoot_percent);
    }
  }

  //! Cycle 3 within 5 % of the best achievable plan's time (item 3's goal), and not faster than 0.95 T*.
  static void expect_within_five_percent_of_t_star(const std::string& machine, const LoopResult& result,
                                                   const BestPlan& best) {
    const BestPlanIteration& oracle = best.iterations[static_cast<std::size_t>(best.best_iteration)];
    std::printf("%s: T* %.2f s (held RMS %.2f %%, max %.2f %%), cycle 3 at %.3f × T*\n", machine.c_str(),
                best.best_cycle_time_s, oracle.held_rms_error_percent, oracle.held_max_abs_error_percent,
                result.cycles[2].simulated_cycle_time_s / best.best_cycle_time_s);
    EXPECT_LE(result.cycles[2].simulated_cycle_time_s, 1.05 * best.best_cycle_time_s);
    EXPECT_GE(result.cycles[2].simulated_cycle_time_s, 0.95 * best.best_cycle_time_s);
  }

  //! The search for T* on the loop's cycle, machine and settings.
  static BestPlanRequest search_for(const LoopRequest& loop) {
    BestPlanRequest search;
    search.geometry = loop.geometry;
    search.settings = loop.settings;
    search.machine = loop.machine;
    return search;
  }

  fs::path dir_;
  model_db::ModelRecord record_;
};

// Three machines of the family whose physics differ from the sample model in shape (family-02: 4 µm of
// runout, size effect 0.29, a 1743 Hz dynamometer; family-09: 5–6 µm of runout, helix 5° off, edge force K_re
// 37 N/mm, 558 Hz; family-11: 5.4 µm of runout, size effect 0.11, helix 3.6° off, 1221 Hz), the trochoid at 400 N
// for three cycles. The first overshoots by 15–29 % (mostly the runout, which the model does not have).
// Learning along the path searches the feed per place (learning/path_correction.hpp) on peaks less the
// noise's excess (learning/peak_noise_bias.hpp) and corrected for the dynamometer's mode as its tap test
// gives it (learning/sensor_dynamics.hpp); the program keeps its model. Held revolutions are those the plan
// runs at the target throughout (planner/peak_comparison.hpp).
//
// What cycle 3 reaches depends on the sensor's noise at a few places, so the bounds hold over six noise seeds
// (SensorOptions::seed 1–6, true peaks; build/bench/learning_convergence_bench with FEEDPLAN_FAMILY_SEED): held RMS
// 0.32–0.36 % (family-02), 0.47–0.55 % (-09), 1.11–1.32 % (-11); the largest held error 1.3–2.3, 1.6–2.3 and
// 2.2–3.0 %, every held revolution within ±3 % in all six draws on the three; the largest revolution over the
// target +0.7 … +6.5 % (entries, which the plan does not hold); cycle time 26.3–26.5, 36.0–36.4 and 24.8–24.9 s
// (0.99, 0.99–1.00 and 1.03 × T*). Cycle 2 overshot on all three (+3.4 … +10.7 %), so cycle 3 may be slower.
// Before held asked the plan to run the whole revolution at its limit (it asked one sample), loop exits the
// feed cannot follow counted too, and the largest held error was 2.0–3.3, 1.5–2.8 and 2.3–5.3 %.
TEST_F(LearningLoop, TrochoidOnThreeMachinesOfTheFamilyConvergesWithoutDraggingTheCycle) {
  struct Case {
    std::string machine;
    double third_rms_percent;  // bound on cycle 3's held RMS error
  };
  for (const Case& m : {Case{"family/family-02.yaml", 0.6}, Case{"family/family-09.yaml", 0.8},
                        Case{"family/family-11.yaml", 1.6}}) {
    SCOPED_TRACE(m.machine);
    LoopRequest request = request_on_machine("trochoid.yaml", m.machine, 400.0);
    request.cycles = 3;
    request.sensor = dynamometer_mode(request.machine.sensors.dynamometer);  // its tap test
    const LoopResult result = run_learning_loop(request);
    ASSERT_EQ(result.cycles.size(), 3u);
    print_cycles(m.machine, result);
    const planner::PeakComparison& third = result.cycles[2].comparison;
    EXPECT_GT(result.cycles[0].comparison.max_overshoot_percent, 10.0);
    EXPECT_LE(third.rms_error_percent, m.third_rms_percent);
    EXPECT_LE(third.max_abs_error_percent, 3.0);  // every held revolution within ±3 %
    EXPECT_GT(third.held, 600) << "most revolutions in the cut are held";
    // Cycle 2 still overshot here, so cycle 3 may be slower; by how much is bounded.
    EXPECT_GT(result.cycles[1].comparison.max_overshoot_percent, 0.0);
    EXPECT_LE(result.cycles[2].simulated_cycle_time_s, 1.45 * result.cycles[1].simulated_cycle_time_s);
    EXPECT_LE(third.max_overshoot_percent, 8.0);
    // Against the best achievable plan on the same machine (planned with its own physics, the feeds then
    // searched on its true peaks within ±0.5 % of the target): T* 26.64, 36.30 and 24.11 s.
    const BestPlan best = best_achievable_plan(search_for(request));
    ASSERT_GE(best.best_iteration, 0);
    expect_within_five_percent_of_t_star(m.machine, result, best);
  }
}

// Family-04 (7 µm of runout, a 605 Hz dynamometer at ζ 0.38) is where learning does not yet hold every
// revolution within ±3 % by cycle 3: over the six noise seeds its largest held error is 2.6–6.3 % (within ±3 % in
// two), each time a steady revolution just behind a loop front, run under the target after the dynamometer read
// the front through its mode and noise (through an ideal dynamometer 1.4 %, without the noise 2.8 %). Held RMS
// 0.54–0.66 %, cycle time 35.9–36.1 s (1.00–1.01 × T* 35.86 s, whose own largest held error is 0.8 %).
TEST_F(LearningLoop, TrochoidOnAResonantDynamometerConvergesInTimeAndWithinSevenPercent) {
  LoopRequest request = request_on_machine("trochoid.yaml", "family/family-04.yaml", 400.0);
  request.cycles = 3;
  request.sensor = dynamometer_mode(request.machine.sensors.dynamometer);
  const LoopResult result = run_learning_loop(request);
  ASSERT_EQ(result.cycles.size(), 3u);
  print_cycles("family-04", result);
  const planner::PeakComparison& third = result.cycles[2].comparison;
  EXPECT_GT(result.cycles[0].comparison.max_overshoot_percent, 15.0);
  EXPECT_LE(third.rms_error_percent, 1.0);
  EXPECT_LE(third.max_abs_error_percent, 7.0);
  EXPECT_GT(third.held, 600);
  EXPECT_LE(third.max_overshoot_percent, 8.0);
  const BestPlan best = best_achievable_plan(search_for(request));
  ASSERT_GE(best.best_iteration, 0);
  expect_within_five_percent_of_t_star("family-04", result, best);
}

// The learning history (planner/path_history.hpp) holds, per cycle, the plan's time and its predictions, and
// what the log measured at each place: on steady revolutions its largest value there is the virtual
// machine's true peak of that revolution (a truth the learner never sees) to within the sensor's noise.
TEST_F(LearningLoop, TheHistoryHoldsWhatEachCycleMeasuredWhereItWasMeasured) {
  LoopRequest request = corner_request(1.5, 600.0);
  request.cycles = 2;
  const LoopResult result = run_learning_loop(request);
  ASSERT_EQ(result.history.size(), 2u);
  const auto& samples = request.geometry.engagement.samples;
  for (std::size_t k = 0; k < 2; ++k) {
    const planner::PathHistoryCycle& h = result.history[k];
    const LoopCycle& c = result.cycles[k];
    EXPECT_EQ(h.cycle, c.cycle);
    EXPECT_DOUBLE_EQ(h.cycle_time_s, c.planned_cycle_time_s);
    ASSERT_EQ(h.measured_n.size(), samples.size());
    std::vector<double> errors;
    for (const auto& r : c.comparison.revolutions) {
      if (!r.steady) continue;
      double largest_n = 0.0;
      for (std::size_t i = 0; i < samples.size(); ++i) {
        if (samples[i].s_mm >= r.revolution.s_start_mm && samples[i].s_mm <= r.revolution.s_end_mm) {
          largest_n = std::max(largest_n, h.measured_n[i]);
        }
      }
      if (largest_n > 0.0) errors.push_back(std::abs(largest_n / r.revolution.peak_n - 1.0));
    }
    ASSERT_GT(errors.size(), 50u) << "cycle " << h.cycle;
    std::sort(errors.begin(), errors.end());
    const double median = errors[errors.size() / 2];
    std::printf("cycle %d: %zu steady revolutions, measured in the history vs true peak: median |error| %.2f %%, p90 %.2f %%\n",
                h.cycle, errors.size(), 100 * median, 100 * errors[errors.size() * 9 / 10]);
    EXPECT_LE(median, 0.01) << "cycle " << h.cycle;
  }
  // The first cycle ran over the target on a soft model, the second close to it.
  double first = 0.0, second = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    first = std::max(first, result.history[0].measured_n[i]);
    second = std::max(second, result.history[1].measured_n[i]);
  }
  EXPECT_GT(first, 1.2 * 600.0);
  EXPECT_LT(second, first);
}

TEST_F(LearningLoop, ThirdCycleHoldsTheTargetWithinFivePercentOnSteadyCuts) {
  LoopRequest request = corner_request(1.5, 600.0);
  request.cycles = 3;
  const LoopResult result = run_learning_loop(request);
  ASSERT_EQ(result.cycles.size(), 3u);
  // The first cycle is planned with a model 33 % soft: the true force overshoots by about 50 %.
  EXPECT_GT(result.cycles[0].comparison.steady_max_abs_error_percent, 30.0);
  EXPECT_EQ(result.cycles[0].update_status, learning::ModelUpdateStatus::kOk);
  const auto& third = result.cycles[2].comparison;
  EXPECT_GT(third.steady, 100);
  EXPECT_LE(third.steady_max_abs_error_percent, 5.0);
  EXPECT_LE(third.steady_rms_error_percent, 2.5);
  for (const LoopCycle& c : result.cycles) EXPECT_EQ(c.infeasible.revolutions, 0) << "cycle " << c.cycle;
}

// A target below what the machine cuts at its minimum feed (120 N on the corner, the machine 1.4 × the model):
// the log shows revolutions at the minimum feed above the target, learning says so, and the force it names as
// the floor is one the virtual machine's true peaks reach (within the sensor's noise), not an artefact.
TEST_F(LearningLoop, ATargetBelowTheForceAtTheMinimumFeedIsNamedWithItsFloor) {
  LoopRequest request = corner_request(1.4, 120.0);
  request.cycles = 2;
  const LoopResult result = run_learning_loop(request);
  const LoopCycle& second = result.cycles[1];
  double largest_true_n = 0.0;
  for (const auto& r : second.comparison.revolutions) largest_true_n = std::max(largest_true_n, r.revolution.peak_n);
  std::printf("%d revolutions at the minimum feed above 120 N, largest measured %.1f N; largest true peak %.1f N\n",
              second.infeasible.revolutions, second.infeasible.largest_peak_n, largest_true_n);
  EXPECT_GT(second.infeasible.revolutions, 10);
  EXPECT_GT(second.infeasible.largest_peak_n, 120.0 * 1.02);
  EXPECT_GE(largest_true_n, 0.95 * second.infeasible.largest_peak_n);
  bool said = false;
  for (const std::string& m : second.messages) said = said || m.find("at the machine's minimum feed still above") != std::string::npos;
  EXPECT_TRUE(said);
}

// A target the machine cannot hold everywhere: the corner at 350 N on family-06 (a radial edge force of
// 35.5 N/mm, size effect 0.24, 2.3 µm of runout, a 1235 Hz dynamometer with 10 N of noise), where the tool
// turns into the wall its force at the minimum feed is up to 399 N. Learning names those places and their
// floor, runs them at the minimum feed, and does not drag the rest of the cycle down: its third cycle takes
// at most 1.3 × T*, the best plan searched against the virtual machine's true peaks with the same places at
// the minimum feed. Measured: T* 70.6 s with 121 samples infeasible; cycle 3 71.6 s (1.01 T*), 129
// revolutions named with a floor of 394 N, held RMS 1.1 %.
TEST_F(LearningLoop, AnInfeasibleTargetIsNamedAndTheRestOfTheCycleIsNotDraggedDown) {
  LoopRequest loop = request_on_machine("corner.yaml", "family/family-06.yaml", 350.0);
  const BestPlan best = best_achievable_plan(search_for(loop));
  std::printf("T* %.2f s (search %d of %zu), %d samples infeasible\n", best.best_cycle_time_s, best.best_iteration + 1,
              best.iterations.size(), best.infeasible_samples);
  ASSERT_GE(best.best_iteration, 0);
  EXPECT_GT(best.infeasible_samples, 0);
  loop.cycles = 3;
  const LoopResult learned = run_learning_loop(loop);
  for (const LoopCycle& c : learned.cycles) {
    std::printf("cycle %d: %.2f s (%.3f × T*), %d revolutions infeasible, floor %.1f N, held RMS %.2f %%\n", c.cycle,
                c.simulated_cycle_time_s, c.simulated_cycle_time_s / best.best_cycle_time_s, c.infeasible.revolutions,
                c.infeasible.largest_peak_n, c.comparison.rms_error_percent);
  }
  const LoopCycle& third = learned.cycles[2];
  EXPECT_GT(third.infeasible.revolutions, 0);
  EXPECT_LT(third.infeasible.revolutions, third.comparison.in_cut / 4);  // a part of the cycle, not all of it
  EXPECT_GT(third.infeasible.largest_peak_n, 350.0);
  EXPECT_LE(third.comparison.rms_error_percent, 3.0);
  const std::string said = learning::describe(third.infeasible, 350.0);
  EXPECT_NE(said.find("at the machine's minimum feed still above"), std::string::npos) << said;
  EXPECT_LE(third.simulated_cycle_time_s, 1.3 * best.best_cycle_time_s);
}

TEST_F(LearningLoop, LearningAlongThePathHoldsTheWallEntryWithinFivePercentByTheThirdCycle) {
  // Where the tool enters the wall the response surface alone cannot be right (t_m and L pair unlike
  // any straight cut); the chip-load transfer (planner/feed_limit.hpp) carries most of it, and repeated
  // parts let the plan learn the rest at the place itself, on the model's terms at each place (the
  // measured force and the target both over the planner's transfer factor there).
  LoopRequest request = corner_request(1.5, 600.0);
  request.cycles = 4;
  request.path_correction = true;
  const LoopResult along_path = run_learning_loop(request);
  for (int cycle : {3, 4}) {
    const auto& c = along_path.cycles[static_cast<std::size_t>(cycle - 1)].comparison;
    EXPECT_LE(c.max_overshoot_percent, 5.0) << "cycle " << cycle;  // every revolution in the material
    EXPECT_LE(c.max_abs_error_percent, 5.0) << "cycle " << cycle;
  }
}

TEST_F(LearningLoop, TrochoidLoopEntriesWithinFivePercentByTheThirdCycle) {
  // Ten entries into the material per part, each rising from nothing to the target within a
  // revolution or two — the case learning per tooth period is for (seed 003, Table 2). By the third
  // cycle the held revolutions are within 0.9 % RMS of the target, the largest peak anywhere in the cut
  // (an entry revolution the plan does not hold at the target) within 6 % over it. Measured: RMS 0.89 %,
  // largest over +1.5 %, and one held revolution 7.3 % under (6.1 % by the fifth cycle): since the
  // virtual machine cuts each helical slice with its part inside the arc, its entry peaks no longer carry
  // the +2.5 % its slicing added, and learning along the path leaves one entry revolution short.
  LoopRequest request = request_for("trochoid.yaml", 1.5, 500.0);
  request.cycles = 3;
  const LoopResult result = run_learning_loop(request);
  EXPECT_GT(result.cycles[0].comparison.max_overshoot_percent, 50.0);
  const auto& third = result.cycles[2].comparison;
  EXPECT_GT(third.in_cut, 800);
  EXPECT_LE(third.max_overshoot_percent, 6.0);
  EXPECT_LE(third.max_abs_error_percent, 8.0);
  EXPECT_LE(third.rms_error_percent, 2.0);
}

TEST_F(LearningLoop, CautiousFirstCutStaysWithinFivePercentWhenTheModelIsFortyPercentSoft) {
  LoopRequest request = corner_request(1.0 / 0.6, 600.0);
  request.cycles = 2;
  request.first_cut_uncertainty = 0.35;
  request.sigmas = 2.0;
  const LoopResult cautious = run_learning_loop(request);
  ASSERT_GT(cautious.cycles[0].comparison.steady, 100);
  // Every revolution in the material — the wall entry too, where the straight-cut model is short by
  // the chip-area ratio — in the first cycle and in the next (entries held at max(ρ, measured)).
  for (const auto& cycle : cautious.cycles) {
    ASSERT_GT(cycle.comparison.in_cut, 100);
    EXPECT_LE(cycle.comparison.max_overshoot_percent, 5.0) << "cycle " << cycle.cycle;
  }
  // Without the bound the same first cut overloads the tool.
  request.cycles = 1;
  request.first_cut_uncertainty = 0.0;
  const LoopResult bold = run_learning_loop(request);
  EXPECT_GT(bold.cycles[0].comparison.steady_max_abs_error_percent, 40.0);
}

// The oracle plans with the machine's own physics (planned_with_own_physics): the simulator's force law, so
// its first plan, before any search, brings the true per-revolution peaks to the target; the truth here is
// the simulator's, which the kernel never reads. Family-04 (runout up to 7.2 µm, helix 3.8° off the
// catalogue's, size effect 0.19) and family-09 (runout up to 6.1 µm, helix 5° off, K_re 37 N/mm), the
// trochoid at 400 N. Measured: largest revolution over the target +1.35 and +0.99 %, held RMS 0.41 and 0.44 %.
// The same kernel without the runout (which tooth cuts deepest unknown) overshoots by 30.6 and 26.9 %; the
// sample response surface, the model learning starts from, by 17–30 %.
TEST_F(LearningLoop, APlanWithTheMachinesOwnPhysicsHoldsItsTruePeaksAtOnce) {
  for (const std::string machine : {"family/family-04.yaml", "family/family-09.yaml"}) {
    SCOPED_TRACE(machine);
    const LoopRequest loop = request_on_machine("trochoid.yaml", machine, 400.0);
    VirtualMachine quiet = loop.machine;
    quiet.keep_log = false;
    const auto cut = [&](const planner::PlanSettings& settings) {
      const planner::PlanResult plan = planner::plan(loop.geometry, settings);
      return run_on_virtual_machine(plan.program, quiet, plan, 400.0).comparison;
    };
    const planner::PlanSettings own = planned_with_own_physics(loop.settings, loop.machine);
    const planner::PeakComparison exact = cut(own);
    planner::PlanSettings without_runout = own;
    without_runout.mechanistic->runout_mm.clear();
    const planner::PeakComparison blind = cut(without_runout);
    std::printf("%s: own physics: largest over %+.2f %%, held RMS %.2f %% over %d; without runout: %+.2f %%\n",
                machine.c_str(), exact.max_overshoot_percent, exact.rms_error_percent, exact.held,
                blind.max_overshoot_percent);
    EXPECT_GT(exact.held, 600);
    EXPECT_LE(exact.max_overshoot_percent, 2.0);
    EXPECT_GE(exact.max_overshoot_percent, -1.0);
    EXPECT_LE(exact.rms_error_percent, 1.0);
    EXPECT_GT(blind.max_overshoot_percent, 5.0);
  }
}

// The best achievable plan (trial/best_achievable_plan.hpp) on family-02, the trochoid at 400 N: the feeds
// searched against the simulator's own true peaks. Its shortest plan that holds the target within its
// tolerance (0.5 %, or the settled plan's 2 %) is T*; no cycle of the learning loop within the same tolerance
// may be more than 2 % faster than it (or T* would not be the shortest), and learning's cycles are printed
// against it.
TEST_F(LearningLoop, BestAchievablePlanIsTheFloorOfWhatLearningReaches) {
  LoopRequest loop = request_on_machine("trochoid.yaml", "family/family-02.yaml", 400.0);
  const BestPlanRequest request = search_for(loop);
  const BestPlan best = best_achievable_plan(request);
  for (std::size_t i = 0; i < best.iterations.size(); ++i) {
    const BestPlanIteration& it = best.iterations[i];
    std::printf("search %zu: %.2f s, largest over %+.2f %%, held max |error| %.2f %%, RMS %.2f %%\n", i + 1,
                it.cycle_time_s, it.max_overshoot_percent, it.held_max_abs_error_percent, it.held_rms_error_percent);
  }
  std::printf("T* %.2f s (search %d), converged %s, %d samples infeasible\n", best.best_cycle_time_s,
              best.best_iteration + 1, best.converged ? "yes" : "no", best.infeasible_samples);
  ASSERT_GE(best.best_iteration, 0);
  const double t_star_overshoot = best.iterations[static_cast<std::size_t>(best.best_iteration)].max_overshoot_percent;
  const double tolerance = t_star_overshoot <= 100 * request.tolerance ? request.tolerance : kMaxSettledOvershoot;
  loop.cycles = 4;
  const LoopResult learned = run_learning_loop(loop);
  for (const LoopCycle& c : learned.cycles) {
    std::printf("learning cycle %d: %.2f s (%.3f × T*), largest over %+.2f %%\n", c.cycle, c.simulated_cycle_time_s,
                c.simulated_cycle_time_s / best.best_cycle_time_s, c.comparison.max_overshoot_percent);
    if (c.comparison.max_overshoot_percent <= 100 * tolerance) {
      EXPECT_GE(c.simulated_cycle_time_s, best.best_cycle_time_s * 0.98) << "cycle " << c.cycle;
    }
  }
}

}  // namespace
}  // namespace feedplan::trial
