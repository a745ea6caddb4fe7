// The constant-feed program (planner/constant_feed.hpp) against truths it does not produce: the F it was
// given on every feed move of a sample cycle, and the cycle time the virtual machine's own motion planner
// (sim::plan_motion) takes for it on a path whose length is known by hand, with an acceleration limit
// so large that the time is the path length over the feed.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/planner/constant_feed.hpp"
#include "feedplan/sim/motion_profile.hpp"
#include "test_models.hpp"

namespace feedplan::planner {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(ConstantFeedProgram, EveryFeedMoveOfTheTrochoidRunsTheGivenFeed) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid.yaml");
  const cycles::Cycle cycle = cycles::generate(spec);
  const geometry::Program program = constant_feed_program(cycle.path, 600.0, 7000.0);

  ASSERT_EQ(program.path.moves.size(), cycle.path.moves.size());
  ASSERT_EQ(program.blocks.size(), cycle.path.moves.size());
  EXPECT_EQ(program.path.part_names, cycle.path.part_names);
  int rapids = 0, arcs = 0;
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    const geometry::Move& move = cycle.path.moves[i];
    const geometry::Move& written = program.path.moves[i];
    EXPECT_EQ(written.kind, move.kind) << "move " << i;
    EXPECT_EQ(written.end.x_mm, move.end.x_mm) << "move " << i;
    EXPECT_EQ(written.end.y_mm, move.end.y_mm) << "move " << i;
    EXPECT_EQ(written.end.z_mm, move.end.z_mm) << "move " << i;
    const geometry::BlockCommand& block = program.blocks[i];
    EXPECT_EQ(block.feed_mm_per_min, move.kind == geometry::MoveKind::kRapid ? 0.0 : 600.0) << "move " << i;
    EXPECT_EQ(block.spindle_rpm, 7000.0) << "move " << i;
    EXPECT_EQ(block.spindle, geometry::SpindleDirection::kClockwise) << "move " << i;
    rapids += move.kind == geometry::MoveKind::kRapid;
    arcs += move.kind == geometry::MoveKind::kArc;
  }
  // The sample has both, so both rules above were checked.
  EXPECT_GT(rapids, 0);
  EXPECT_GT(arcs, 0);
}

// A 6 mm rapid down, a 10 mm line along +x, a quarter circle of radius 10 mm (5π mm) about the origin.
geometry::ToolPath hand_path() {
  geometry::ToolPath path;
  geometry::Move rapid;
  rapid.kind = geometry::MoveKind::kRapid;
  rapid.start = {0.0, 0.0, 5.0};
  rapid.end = {0.0, 0.0, -1.0};
  geometry::Move line;
  line.kind = geometry::MoveKind::kLine;
  line.start = rapid.end;
  line.end = {10.0, 0.0, -1.0};
  line.cutting = true;
  geometry::Move arc;
  arc.kind = geometry::MoveKind::kArc;
  arc.start = line.end;
  arc.end = {0.0, 10.0, -1.0};
  arc.center = {0.0, 0.0};
  arc.ccw = true;
  arc.sweep_rad = 0.5 * kPi;
  arc.cutting = true;
  path.moves = {rapid, line, arc};
  path.part_names = {"all"};
  return path;
}

TEST(ConstantFeedProgram, CycleTimeIsLengthOverFeedWithoutAccelerationLimit) {
  const geometry::ToolPath path = hand_path();
  geometry::MachineLimits limits = sim::kVirtualMachineLimits;
  limits.max_accel_mm_per_s2 = 1e9;  // accelerating to 250 mm/s takes 0.25 µs
  limits.rapid_feed_mm_per_min = 15000.0;
  const sim::MotionProfile motion = sim::plan_motion(constant_feed_program(path, 600.0, 5000.0), limits);

  // 6 mm at 250 mm/s, then (10 + 5π) mm at 600 mm/min = 10 mm/s.
  EXPECT_NEAR(motion.duration_s(), 6.0 / 250.0 + (10.0 + 5.0 * kPi) / 10.0, 1e-5);
  EXPECT_NEAR(motion.time_in_cut_s(), (10.0 + 5.0 * kPi) / 10.0, 1e-5);
}

// The planner's prediction of the same program (what a spec's feed_mm_per_min is quoted with): the same
// length over feed by hand, and no force where nothing is cut (the stock lies far from the path).
TEST(ConstantFeedProgram, PredictedCycleTimeIsLengthOverFeedWithoutAccelerationLimit) {
  geometry::Stock stock;
  stock.regions.push_back({geometry::Contour::rectangle({100.0, 100.0}, {120.0, 120.0}), {}});
  stock.z_top_mm = 0.0;
  stock.z_bottom_mm = -20.0;
  geometry::Tool tool;
  const PlanGeometry geometry = analyse(hand_path(), stock, tool, 0.05);
  PlanSettings settings;
  settings.model = planner::testing::s50c_like_model();
  settings.target_force_n = 300.0;
  settings.spindle_rpm = 5000.0;
  settings.machine = sim::kVirtualMachineLimits;
  settings.machine.max_accel_mm_per_s2 = 1e9;
  settings.machine.rapid_feed_mm_per_min = 15000.0;
  const ConstantFeedPrediction p = predict_constant_feed(geometry, settings, 600.0, settings.machine.max_accel_mm_per_s2);
  EXPECT_EQ(p.feed_mm_per_min, 600.0);
  EXPECT_NEAR(p.cycle_time_s, 6.0 / 250.0 + (10.0 + 5.0 * kPi) / 10.0, 1e-4);
  EXPECT_EQ(p.peak_force_n, 0.0);
}

}  // namespace
}  // namespace feedplan::planner
