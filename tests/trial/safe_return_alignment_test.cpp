// `feedplan plan --simulate` reads the written program back and places every simulated revolution on the
// plan's path by path length. The writer ends each program with a return to the machine's Z home, which the
// reader reads as a rapid up to a park height after the cut: the revolutions must stay where the plan's own
// program puts them (run on the virtual machine without G-code in between: the truth here), and the return
// may only add its rapid's time to the cycle.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "feedplan/trial/plan_check.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"

#include <unistd.h>

namespace feedplan::trial {
namespace {

namespace fs = std::filesystem;

constexpr double kTargetForceN = 300.0;
// Path lengths on the plan's path: the written program's points are within 1 µm of the plan's (3 decimals),
// which moves them by a few µm over the cut; a park counted in would move them by 25 mm and more.
constexpr double kPathLengthToleranceMm = 0.01;

TEST(SafeReturnAlignment, RevolutionsStayOnThePlanAndOnlyTheFinalRapidAddsTime) {
  const fs::path dir = fs::temp_directory_path() / ("feedplan_safe_return_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  model_db::ModelRecord record;
  {
    auto store = model_db::Store::open(dir / "t.db", model_db::OpenMode::kCreate);
    model_db::import_from_file(store, fs::path(FEEDPLAN_TEST_DATA_DIR) / "cli" / "s50c_d10_model.json");
    record = *store.active_model("SC EM D10 Z4", "S50C");
  }
  fs::remove_all(dir);

  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/corner.yaml");
  const cycles::Cycle cycle = cycles::generate(spec);
  planner::PlanSettings settings;
  settings.model = record.model;
  settings.target_force_n = kTargetForceN;
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  const planner::PlanResult plan = planner::plan(planner::analyse(cycle.path, cycle.stock, spec.tool), settings);
  const std::string materials = std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/materials.yaml";

  VirtualMachine machine = virtual_machine_for(spec, cycle, materials);
  machine.keep_log = false;
  const VirtualMachineRun truth = run_on_virtual_machine(plan.program, machine, plan, kTargetForceN);
  ASSERT_GT(truth.comparison.in_cut, 100);

  gcode::WriterOptions options;
  const std::string with_return = gcode::write_gcode(plan.program, options);
  ASSERT_NE(with_return.find("G53 G0 Z0."), std::string::npos);
  options.safe_return = false;
  const geometry::Program returning = gcode::read_program(with_return, "with the safe return");
  const geometry::Program plain = gcode::read_program(gcode::write_gcode(plan.program, options), "without it");
  const VirtualMachineRun returned_run = run_on_virtual_machine(returning, machine, plan, kTargetForceN);
  const VirtualMachineRun plain_run = run_on_virtual_machine(plain, machine, plan, kTargetForceN);

  // Where the cut begins and ends on the plan's path, as the plan's own program runs: the read programs
  // turn the spindle through their approach first, so their revolutions start at other phases — each
  // in-cut stretch lies within one revolution's length of the truth's.
  double revolution_mm = 0.0;
  for (const auto& r : truth.comparison.revolutions) {
    if (r.in_cut) revolution_mm = std::max(revolution_mm, r.revolution.s_end_mm - r.revolution.s_start_mm);
  }
  const auto cut_span = [](const planner::PeakComparison& comparison) {
    std::pair<double, double> span{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const auto& r : comparison.revolutions) {
      if (!r.in_cut) continue;
      span.first = std::min(span.first, r.revolution.s_start_mm);
      span.second = std::max(span.second, r.revolution.s_end_mm);
    }
    return span;
  };
  const auto truth_span = cut_span(truth.comparison);
  for (const VirtualMachineRun* run : {&returned_run, &plain_run}) {
    SCOPED_TRACE(run == &returned_run ? "with the safe return" : "without it");
    const auto span = cut_span(run->comparison);
    EXPECT_NEAR(span.first, truth_span.first, revolution_mm + kPathLengthToleranceMm);
    EXPECT_NEAR(span.second, truth_span.second, revolution_mm + kPathLengthToleranceMm);
  }
  // With and without the return, the same revolutions at the same places until the cut is over.
  const auto& with_revolutions = returned_run.comparison.revolutions;
  const auto& plain_revolutions = plain_run.comparison.revolutions;
  ASSERT_GE(with_revolutions.size(), plain_revolutions.size());
  for (std::size_t i = 0; i < plain_revolutions.size(); ++i) {
    if (!plain_revolutions[i].in_cut) continue;
    ASSERT_TRUE(with_revolutions[i].in_cut) << "revolution " << i;
    ASSERT_NEAR(with_revolutions[i].revolution.s_start_mm, plain_revolutions[i].revolution.s_start_mm, 1e-9) << i;
    ASSERT_NEAR(with_revolutions[i].revolution.s_end_mm, plain_revolutions[i].revolution.s_end_mm, 1e-9) << i;
    ASSERT_EQ(with_revolutions[i].revolution.peak_n, plain_revolutions[i].revolution.peak_n) << i;
  }
  EXPECT_EQ(returned_run.comparison.in_cut, plain_run.comparison.in_cut);
  EXPECT_EQ(returned_run.comparison.held, plain_run.comparison.held);

  // The return is one rapid after the cut, straight up; it cuts nothing, so the cutting time stays and the
  // cycle grows by its time alone: at least its length at the rapid rate, at most that plus the time to
  // reach the rapid rate and stop from it (v / a).
  ASSERT_EQ(returning.path.moves.size(), plain.path.moves.size() + 1);
  const geometry::Move& park = returning.path.moves.back();
  EXPECT_EQ(park.kind, geometry::MoveKind::kRapid);
  EXPECT_FALSE(park.cutting);
  EXPECT_GT(park.end.z_mm, park.start.z_mm);
  const sim::SimulationSummary& with = returned_run.simulation.summary;
  const sim::SimulationSummary& without = plain_run.simulation.summary;
  EXPECT_NEAR(with.cutting_time_s, without.cutting_time_s, 1e-9);
  EXPECT_NEAR(with.time_in_contact_s, without.time_in_contact_s, 1e-9);
  EXPECT_DOUBLE_EQ(with.max_revolution_peak_n, without.max_revolution_peak_n);
  const double rapid_mm_per_s = spec.machine.rapid_feed_mm_per_min / 60.0;
  const double added_s = with.cycle_time_s - without.cycle_time_s;
  EXPECT_NEAR(with.air_time_s - without.air_time_s, added_s, 1e-9);
  EXPECT_GE(added_s, geometry::length_mm(park) / rapid_mm_per_s - 1e-9);
  EXPECT_LE(added_s, geometry::length_mm(park) / rapid_mm_per_s + rapid_mm_per_s / spec.machine.max_accel_mm_per_s2);
}

}  // namespace
}  // namespace feedplan::trial
