// The strategy comparison (`feedplan compare`'s runner): every row must be what running the same strategy
// alone on the same machine gives — the constant-feed program simulated, the plan simulated, the learning
// loop's own cycle N, a controller run on its own — with the figures taken from those runs (the simulator's
// summary, the loop's cycle) and the judging rule worked out here, not by the comparison. The corner sample
// at 350 N on a machine 40 % harder than the sample model, with a constant feed of 1200 mm/min.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/trial/comparison_plot.hpp"
#include "feedplan/trial/controlled_run.hpp"
#include "feedplan/trial/strategy_comparison.hpp"

namespace feedplan::trial {
namespace {

namespace fs = std::filesystem;

constexpr double kFeedMmPerMin = 1200.0;
constexpr double kScale = 1.4;

// The judging rule, written out here: in cut at ≥ 20 % of the target, within 5 %, time above the target.
struct Figures {
  double max_peak_n = 0.0;
  int in_cut = 0;
  double rms_n = 0.0;
  double within_share = 0.0;
  double above_s = 0.0;
};

Figures figures_of(const std::vector<force_log::RevolutionPeak>& revolutions, double target_n) {
  Figures f;
  double squares = 0.0;
  int within = 0;
  for (const auto& r : revolutions) {
    f.max_peak_n = std::max(f.max_peak_n, r.peak_xy_n);
    if (r.peak_xy_n > target_n) f.above_s += r.t_end_s - r.t_start_s;
    if (r.peak_xy_n < 0.2 * target_n) continue;
    ++f.in_cut;
    squares += (r.peak_xy_n - target_n) * (r.peak_xy_n - target_n);
    within += std::abs(r.peak_xy_n - target_n) <= 0.05 * target_n ? 1 : 0;
  }
  if (f.in_cut > 0) {
    f.rms_n = std::sqrt(squares / f.in_cut);
    f.within_share = static_cast<double>(within) / f.in_cut;
  }
  return f;
}

void expect_row_is_run(const StrategyRow& row, const sim::SimulationResult& alone, double target_n) {
  SCOPED_TRACE(row.name);
  const Figures f = figures_of(alone.revolutions, target_n);
  EXPECT_DOUBLE_EQ(row.judgement.max_peak_n, alone.summary.max_revolution_peak_n);
  EXPECT_DOUBLE_EQ(row.judgement.cycle_time_s, alone.summary.cycle_time_s);
  EXPECT_DOUBLE_EQ(row.judgement.max_overshoot_percent, (alone.summary.max_revolution_peak_n / target_n - 1.0) * 100.0);
  EXPECT_EQ(row.judgement.in_cut_revolutions, f.in_cut);
  EXPECT_NEAR(row.judgement.rms_error_n, f.rms_n, 1e-9 * target_n);
  EXPECT_DOUBLE_EQ(row.judgement.within_5_percent_share, f.within_share);
  EXPECT_NEAR(row.judgement.time_above_target_s, f.above_s, 1e-9);
  EXPECT_EQ(row.revolutions.size(), alone.revolutions.size());
}

class StrategyComparisonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("feedplan_compare_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    auto store = model_db::Store::open(dir_ / "t.db", model_db::OpenMode::kCreate);
    model_db::import_from_file(store, fs::path(FEEDPLAN_TEST_DATA_DIR) / "cli" / "s50c_d10_model.json");
    record_ = *store.active_model("SC EM D10 Z4", "S50C");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The corner at its target on the harder machine; programs run as planned (in memory).
  ComparisonRequest corner_request() {
    const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/corner.yaml");
    const cycles::Cycle cycle = cycles::generate(spec);
    ComparisonRequest request;
    request.geometry = planner::analyse(cycle.path, cycle.stock, spec.tool);
    request.settings.model = record_.model;
    request.settings.target_force_n = spec.target_force_n;
    request.settings.spindle_rpm = spec.spindle_rpm;
    request.settings.machine = spec.machine;
    const sim::MaterialLibrary materials = sim::load_materials(std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/materials.yaml");
    request.machine.tool = spec.tool;
    request.machine.coefficients = sim::scaled(materials.get("S50C").coefficients, kScale);
    request.machine.stock = cycle.stock;
    request.machine.machine = spec.machine;
    request.machine.spindle_rpm = spec.spindle_rpm;
    request.machine.keep_log = false;
    request.constant_feed_mm_per_min = kFeedMmPerMin;
    request.learning_cycles = 2;
    request.start_fit_covariance = record_.fit.covariance;
    return request;
  }

  fs::path dir_;
  model_db::ModelRecord record_;
};

TEST_F(StrategyComparisonTest, EveryRowIsWhatItsStrategyGivesAlone) {
  const ComparisonRequest request = corner_request();
  double last_progress = 0.0;
  int progress_calls = 0;
  ComparisonRequest with_progress = request;
  with_progress.progress = [&](double fraction) {
    EXPECT_GE(fraction, last_progress);
    last_progress = fraction;
    ++progress_calls;
  };
  const StrategyComparison comparison = compare_strategies(with_progress);
  const double target_n = request.settings.target_force_n;
  EXPECT_GT(progress_calls, 0);
  EXPECT_DOUBLE_EQ(last_progress, 1.0);

  // The rows, in order: constant, cycle 1, cycle N, seven controllers alone, the hybrid on cycle 1 and on N.
  ASSERT_EQ(comparison.rows.size(), 12u);
  const StrategyKind kinds[] = {StrategyKind::kConstantFeed, StrategyKind::kFeedForward, StrategyKind::kFeedForward,
                                StrategyKind::kFeedback,     StrategyKind::kFeedback,    StrategyKind::kFeedback,
                                StrategyKind::kFeedback,     StrategyKind::kFeedback,    StrategyKind::kFeedback,
                                StrategyKind::kFeedback,     StrategyKind::kHybrid,      StrategyKind::kHybrid};
  for (std::size_t k = 0; k < comparison.rows.size(); ++k) EXPECT_EQ(comparison.rows[k].kind, kinds[k]) << k;
  EXPECT_EQ(comparison.rows[1].plan_cycle, 1);
  EXPECT_EQ(comparison.rows[2].plan_cycle, 2);
  EXPECT_EQ(comparison.rows[11].plan_cycle, 2);
  EXPECT_EQ(comparison.rows[3].controller, ControllerKind::kIntegral);
  EXPECT_EQ(comparison.rows[6].controller, ControllerKind::kRobustServo);
  EXPECT_EQ(comparison.rows[7].controller, ControllerKind::kModelReference);
  EXPECT_EQ(comparison.rows[8].controller, ControllerKind::kMultiModel1);
  EXPECT_EQ(comparison.rows[9].controller, ControllerKind::kMultiModel2);
  EXPECT_EQ(comparison.rows[10].controller, ControllerKind::kRobustServo);

  VirtualMachine machine = request.machine;
  // Constant feed: the program at one F, simulated.
  const geometry::Program constant =
      planner::constant_feed_program(request.geometry.path, kFeedMmPerMin, request.settings.spindle_rpm);
  expect_row_is_run(comparison.rows[0], simulate_on(constant, machine), target_n);
  // Cycle 1: the plan of the settings, simulated.
  const planner::PlanResult first = planner::plan(request.geometry, request.settings);
  expect_row_is_run(comparison.rows[1], simulate_on(first.program, machine), target_n);
  EXPECT_DOUBLE_EQ(comparison.rows[1].planned_cycle_time_s, first.summary.cycle_time_s);

  // Cycle N: the learning loop's own cycle 2, run here from the same start.
  LoopRequest loop;
  loop.geometry = request.geometry;
  loop.settings = request.settings;
  loop.machine = request.machine;
  loop.machine.keep_log = true;
  loop.cycles = 2;
  loop.start_fit_covariance = record_.fit.covariance;
  const LoopResult learned = run_learning_loop(loop);
  ASSERT_EQ(learned.cycles.size(), 2u);
  const LoopCycle& second = learned.cycles[1];
  const StrategyRow& row_n = comparison.rows[2];
  EXPECT_DOUBLE_EQ(row_n.planned_cycle_time_s, second.planned_cycle_time_s);
  EXPECT_DOUBLE_EQ(row_n.judgement.cycle_time_s, second.simulated_cycle_time_s);
  double loop_max_n = 0.0;
  for (const auto& r : second.comparison.revolutions) loop_max_n = std::max(loop_max_n, r.revolution.peak_n);
  EXPECT_DOUBLE_EQ(row_n.judgement.max_peak_n, loop_max_n);
  EXPECT_EQ(row_n.revolutions.size(), second.comparison.revolutions.size());
  // The loop's cycles before N are reported as the loop reports them.
  ASSERT_EQ(comparison.learning.size(), 1u);
  EXPECT_DOUBLE_EQ(comparison.learning[0].simulated_cycle_time_s, learned.cycles[0].simulated_cycle_time_s);
  // Learning on a machine 40 % harder brings the largest peak down from cycle 1's.
  EXPECT_LT(row_n.judgement.max_peak_n, comparison.rows[1].judgement.max_peak_n);

  // A controller alone on the constant-feed program: the robust servo, run on its own.
  OverrideControlSettings alone;
  alone.sensor.sensor = ForceSensor::kDynamometer;
  alone.sensor.tool_radius_mm = machine.tool.radius_mm();
  alone.target_force_n = target_n;
  ControllerSettings servo;
  servo.kind = ControllerKind::kRobustServo;
  servo.target_force_n = target_n;
  servo.min_ratio = alone.min_ratio;
  servo.max_ratio = alone.max_ratio;
  const ControlledRun servo_run = run_under_control(constant, machine, alone, make_control_law(servo));
  expect_row_is_run(comparison.rows[6], servo_run.simulation, target_n);
  // Seed 004's scheme 1 alone, told the machine's spindle speed and flutes.
  ControllerSettings froh = servo;
  froh.kind = ControllerKind::kMultiModel1;
  froh.spindle_rpm = machine.spindle_rpm;
  froh.flutes = machine.tool.flutes;
  const ControlledRun froh_run = run_under_control(constant, machine, alone, make_control_law(froh));
  expect_row_is_run(comparison.rows[8], froh_run.simulation, target_n);
  // The hybrid on cycle 1: the robust servo within 70–130 % on the plan's program.
  const OverrideControlSettings trim = hybrid_override_settings(alone.sensor, target_n);
  servo.min_ratio = trim.min_ratio;
  servo.max_ratio = trim.max_ratio;
  const ControlledRun hybrid_run = run_under_control(first.program, machine, trim, make_control_law(servo));
  expect_row_is_run(comparison.rows[10], hybrid_run.simulation, target_n);
}

TEST_F(StrategyComparisonTest, ProgramsGoThroughAsReceived) {
  ComparisonRequest request = corner_request();
  request.controllers = {ControllerKind::kIntegral};
  request.hybrid_on_learned = false;
  // A machine that receives every program at half its feeds: the constant feed's cycle must be the
  // half-feed program's.
  request.as_received = [](const geometry::Program& program) {
    geometry::Program slow = program;
    for (geometry::BlockCommand& block : slow.blocks) block.feed_mm_per_min *= 0.5;
    return slow;
  };
  const StrategyComparison comparison = compare_strategies(request);
  ASSERT_EQ(comparison.rows.size(), 5u);  // constant, 1, N, integral, hybrid on 1
  EXPECT_EQ(comparison.rows[4].kind, StrategyKind::kHybrid);
  const geometry::Program half =
      planner::constant_feed_program(request.geometry.path, 0.5 * kFeedMmPerMin, request.settings.spindle_rpm);
  const sim::SimulationResult alone = simulate_on(half, request.machine);
  expect_row_is_run(comparison.rows[0], alone, request.settings.target_force_n);
}

TEST_F(StrategyComparisonTest, BadRequestsNameTheirFields) {
  ComparisonRequest request = corner_request();
  request.constant_feed_mm_per_min = 0.0;
  request.learning_cycles = 1;
  request.settings.target_force_n = std::nan("");
  try {
    compare_strategies(request);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("comparison.constant_feed_mm_per_min = 0"), std::string::npos) << text;
    EXPECT_NE(text.find("comparison.learning_cycles = 1"), std::string::npos) << text;
    EXPECT_NE(text.find("comparison.settings.target_force_n"), std::string::npos) << text;
  }
}

// The plot: one panel per row on the same axes, the target in every panel.
TEST(ComparisonPlot, OnePanelPerRowOnTheSameAxes) {
  StrategyComparison comparison;
  comparison.target_force_n = 150.0;
  for (const double peak_n : {100.0, 200.0, 50.0}) {
    StrategyRow row;
    row.name = "row at " + std::to_string(static_cast<int>(peak_n)) + " N";
    row.revolutions.push_back({0, 0.0, 0.5, peak_n, 0.25, 0.5 * peak_n, 10});
    row.revolutions.push_back({1, 0.5, 1.0, peak_n, 0.75, 0.5 * peak_n, 10});
    comparison.rows.push_back(row);
  }
  comparison.rows.back().revolutions.clear();  // a row without revolutions still gets its panel
  const std::string svg = comparison_plot_svg(comparison);
  auto count = [&svg](const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("<g id=\"panel-"), 3u);
  EXPECT_EQ(count("class=\"target\""), 3u);
  EXPECT_EQ(count(">no data</text>"), 1u);
  // Force axis 0–300 N in 100 N steps in every panel (1.1 × the largest peak, 220 N, rounded up to a tick).
  EXPECT_EQ(count("class=\"y-tick\""), 12u);
  EXPECT_EQ(count(">300</text>"), 3u);
  // Time labels once, under the last panel.
  EXPECT_EQ(count("time t [s]"), 1u);
  EXPECT_NE(svg.find("row at 200 N"), std::string::npos);
}

}  // namespace
}  // namespace feedplan::trial
