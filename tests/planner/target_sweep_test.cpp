// The time-versus-target curve (planner/target_sweep.hpp, target_sweep_plot.hpp) on the trochoid sample with
// an S50C-like model. What is checked against something the sweep did not produce: each row is the plan
// `plan` makes at that target on its own; a larger allowed force never makes the cycle longer nor the
// predicted peak exceed its target where the plan is met; below the model's force floor the plan says the
// target is not met and names a target that is.

#include <gtest/gtest.h>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/planner/target_sweep.hpp"
#include "feedplan/planner/target_sweep_plot.hpp"
#include "test_models.hpp"

namespace feedplan::planner {
namespace {

TEST(TargetSweep, ParsesTheRangeAndNamesEveryBadOne) {
  const TargetRange r = parse_target_range("250:500:25", "--target-sweep");
  EXPECT_EQ(targets_of(r).size(), 11u);
  EXPECT_DOUBLE_EQ(targets_of(r).back(), 500.0);
  EXPECT_EQ(targets_of(parse_target_range("300:300:10", "f")), (std::vector<double>{300.0}));
  EXPECT_EQ(targets_of(parse_target_range("100:130:20", "f")), (std::vector<double>{100.0, 120.0}));
  for (const std::string bad : {"", "250:500", "250:500:25:1", "a:500:25", "250:500:", "0:500:25", "500:250:25",
                                "250:500:0", "250:500:-5", "1:1e6:1", "nan:500:25"}) {
    try {
      parse_target_range(bad, "--target-sweep");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--target-sweep = '" + bad + "'"), std::string::npos) << e.what();
    }
  }
}

TEST(TargetSweep, EachRowIsThePlanAtItsTargetAndMoreForceNeverCostsTime) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid.yaml");
  const cycles::Cycle cycle = cycles::generate(spec);
  const PlanGeometry geometry = analyse(cycle.path, cycle.stock, spec.tool, 0.05);
  PlanSettings settings;
  settings.model = testing::s50c_like_model();
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  settings.target_force_n = 400.0;
  const std::vector<TargetSweepRow> rows = sweep_targets(geometry, settings, parse_target_range("10:610:50", "f"));
  ASSERT_EQ(rows.size(), 13u);
  bool some_not_met = false, some_met = false;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const TargetSweepRow& row = rows[i];
    std::printf("target %5.0f N: %-14s cycle %7.2f s, largest predicted peak %6.1f N%s\n", row.target_n,
                to_string(row.status).c_str(), row.cycle_time_s, row.max_predicted_force_n,
                row.status == PlanStatus::kTargetNotMet ? (", met everywhere from " + std::to_string(row.target_needed_n)).c_str() : "");
    PlanSettings alone = settings;
    alone.target_force_n = row.target_n;
    const PlanResult single = plan(geometry, alone);
    EXPECT_EQ(row.status, single.status) << row.target_n;
    EXPECT_DOUBLE_EQ(row.cycle_time_s, single.summary.cycle_time_s) << row.target_n;
    EXPECT_DOUBLE_EQ(row.max_predicted_force_n, single.summary.max_predicted_force_n) << row.target_n;
    if (i > 0) {
      EXPECT_LE(row.cycle_time_s, rows[i - 1].cycle_time_s * (1 + 1e-9)) << row.target_n;
    }
    if (row.status == PlanStatus::kTargetNotMet) {
      some_not_met = true;
      EXPECT_GT(row.unreachable_samples, 0);
      EXPECT_GT(row.target_needed_n, row.target_n);
    } else {
      some_met = true;
      EXPECT_LE(row.max_predicted_force_n, row.target_n * (1 + 1e-3)) << row.target_n;
    }
  }
  EXPECT_TRUE(some_met);
  EXPECT_TRUE(some_not_met) << "the range should reach below the model's force floor";

  const std::string svg = target_sweep_svg(rows, "trochoid <sweep>");
  EXPECT_NE(svg.find("<g id=\"panel-time\">"), std::string::npos);
  EXPECT_NE(svg.find("<g id=\"panel-peak\">"), std::string::npos);
  EXPECT_NE(svg.find("<polyline class=\"cycle-time\""), std::string::npos);
  EXPECT_NE(svg.find("<line class=\"floor\""), std::string::npos);
  EXPECT_NE(svg.find("<circle class=\"not-met\""), std::string::npos);
  EXPECT_NE(svg.find("trochoid &lt;sweep&gt;"), std::string::npos);
}

}  // namespace
}  // namespace feedplan::planner
