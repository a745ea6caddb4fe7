// Every program the planner emits for every bundled sample (the four cycles and the pocket), in every
// dialect, read by LinuxCNC's own interpreter (`rs274 -g`, docs/method.md §7): it must accept the program,
// its canonical path must pass through every planned block end within 1 µm, in order, with each arc's
// centre within 1 µm of the planned centre and the same turning sense, and the feed LinuxCNC sets for
// every move must equal the planned block's F.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../gcode/rs274_runner.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "test_models.hpp"

namespace feedplan::planner {
namespace {

using gcode::oracle::OracleMove;

constexpr double kToleranceMm = 1e-3;

double distance(const geometry::Point3& a, const geometry::Point3& b) {
  return std::sqrt((a.x_mm - b.x_mm) * (a.x_mm - b.x_mm) + (a.y_mm - b.y_mm) * (a.y_mm - b.y_mm) +
                   (a.z_mm - b.z_mm) * (a.z_mm - b.z_mm));
}

struct EmittedCase {
  const char* sample;
  gcode::Dialect dialect;
};

class EmittedProgram : public gcode::oracle::Rs274Test, public ::testing::WithParamInterface<EmittedCase> {};

TEST_P(EmittedProgram, LinuxCncRunsThePlannedPathAndFeeds) {
  const EmittedCase c = GetParam();
  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + c.sample);
  const cycles::Cycle cycle = cycles::generate(spec);
  const PlanGeometry geometry = analyse(cycle.path, cycle.stock, spec.tool);
  PlanSettings settings;
  settings.model = testing::s50c_like_model();
  settings.target_force_n = spec.target_force_n;
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  const PlanResult result = plan(geometry, settings);
  ASSERT_NE(result.status, PlanStatus::kTargetNotMet);

  gcode::WriterOptions options;
  options.dialect = c.dialect;
  options.coolant = true;
  options.line_numbers = c.dialect != gcode::Dialect::kLinuxCnc;
  options.header_comments = {{"cycle", spec.cycle}, {"tool", spec.tool.name}, {"target force N", "300"}};
  const std::string text = gcode::write_gcode(result.program, options);
  const gcode::oracle::OracleRun run = gcode::oracle::run_rs274_text(*rs274_, text);
  ASSERT_EQ(run.exit_code, 0) << run.messages;
  ASSERT_TRUE(run.oddities.empty()) << run.oddities.front();

  // Walk the planned moves; each is one or more canonical moves (arcs over 180° are split) ending at its
  // end point. Canonical moves before the first planned move's start bring the tool there.
  const auto& planned = result.program.path.moves;
  const auto& oracle = run.moves;
  std::size_t j = 0;
  while (j < oracle.size() && distance(oracle[j].end, planned.front().start) > kToleranceMm) ++j;
  ASSERT_LT(j, oracle.size()) << "LinuxCNC never reaches the program's start point";
  ++j;
  int arcs_checked = 0;
  int feeds_checked = 0;
  for (std::size_t k = 0; k < planned.size(); ++k) {
    const geometry::Move& move = planned[k];
    const double feed = result.program.blocks[k].feed_mm_per_min;
    bool reached = false;
    while (j < oracle.size() && !reached) {
      const OracleMove& m = oracle[j++];
      ASSERT_EQ(m.kind, move.kind) << "planned move " << k << " at line ~" << j;
      if (move.kind == geometry::MoveKind::kArc) {
        ASSERT_LE(std::hypot(m.center.x_mm - move.center.x_mm, m.center.y_mm - move.center.y_mm), kToleranceMm)
            << "arc centre of planned move " << k;
        ASSERT_EQ(m.rotation > 0, move.ccw) << "turning sense of planned move " << k;
        ++arcs_checked;
      }
      if (move.kind != geometry::MoveKind::kRapid) {
        ASSERT_EQ(m.feed_mm_per_min, feed) << "feed of planned move " << k;
        ++feeds_checked;
      }
      reached = distance(m.end, move.end) <= kToleranceMm;
    }
    ASSERT_TRUE(reached) << "LinuxCNC's path never reaches the end of planned move " << k << " ("
                         << move.end.x_mm << ", " << move.end.y_mm << ", " << move.end.z_mm << ")";
  }
  // After the program, the safe return alone: a rapid straight up to machine Z 0, which in the program's
  // coordinates is minus the offsets rs274 has in effect (work offset, G92, the tool length of G43 H1).
  ASSERT_EQ(oracle.size(), j + 1) << "after the program: only the safe return";
  const OracleMove& safe_return = oracle.back();
  EXPECT_EQ(safe_return.kind, geometry::MoveKind::kRapid);
  const geometry::Point3 end = planned.back().end;
  EXPECT_LE(distance(safe_return.end, {end.x_mm, end.y_mm, -(safe_return.origin_z_mm + safe_return.tool_length_z_mm)}),
            kToleranceMm);
  EXPECT_GT(safe_return.tool_length_z_mm, 0.0) << "rs274's tool 1 has a length";
  EXPECT_GT(feeds_checked, 10);
  if (spec.cycle != "corner") {
    EXPECT_GT(arcs_checked, 0);
  }
}

std::string case_name(const ::testing::TestParamInfo<EmittedCase>& info) {
  std::string name = info.param.sample;
  name = name.substr(0, name.find('.')) + "_" + gcode::to_string(info.param.dialect);
  return name;
}

INSTANTIATE_TEST_SUITE_P(
    Samples, EmittedProgram,
    ::testing::Values(EmittedCase{"corner.yaml", gcode::Dialect::kLinuxCnc}, EmittedCase{"corner.yaml", gcode::Dialect::kFanuc},
                      EmittedCase{"corner.yaml", gcode::Dialect::kHaas}, EmittedCase{"trochoid.yaml", gcode::Dialect::kLinuxCnc},
                      EmittedCase{"trochoid.yaml", gcode::Dialect::kFanuc}, EmittedCase{"trochoid.yaml", gcode::Dialect::kHaas},
                      EmittedCase{"spiral.yaml", gcode::Dialect::kLinuxCnc}, EmittedCase{"spiral.yaml", gcode::Dialect::kFanuc},
                      EmittedCase{"spiral.yaml", gcode::Dialect::kHaas},
                      EmittedCase{"helical_boring.yaml", gcode::Dialect::kLinuxCnc},
                      EmittedCase{"helical_boring.yaml", gcode::Dialect::kFanuc},
                      EmittedCase{"helical_boring.yaml", gcode::Dialect::kHaas}, EmittedCase{"pocket.yaml", gcode::Dialect::kLinuxCnc},
                      EmittedCase{"pocket.yaml", gcode::Dialect::kFanuc}, EmittedCase{"pocket.yaml", gcode::Dialect::kHaas}),
    case_name);

}  // namespace
}  // namespace feedplan::planner
