// End-to-end tests of `feedplan plan` on a database holding the sample model for the Ø10 4-flute end
// mill in S50C (tests/data/cli/s50c_d10_model.json, exported from the sample database): the program,
// report and plot are written and read back; every kind of bad input exits 2 naming the field with no
// output touched; no model for the material and an unreachable target exit 1.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "feedplan/gcode/reader.hpp"
#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;

class PlanCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_model.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }

  std::string plan_args(const std::string& sample, const fs::path& program) {
    return "plan " + kSamples + "/" + sample + " --db " + db_ + " -o " + program.string();
  }

  std::string db_;
};

TEST_F(PlanCliTest, TrochoidProgramReportCsvAndPlot) {
  const fs::path program = dir_ / "t.nc";
  const fs::path report = dir_ / "t.json";
  const fs::path csv = dir_ / "t.csv";
  const fs::path plot = dir_ / "t.svg";
  const RunResult r = run_feedplan(plan_args("trochoid.yaml", program) + " --report " + report.string() + " --csv " +
                                   csv.string() + " --plot " + plot.string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"status\": \"ok\""), std::string::npos) << r.output;
  // The program reads back with the G-code reader, with F words inside the machine's range.
  const feedplan::geometry::Program read = feedplan::gcode::load_program(program);
  int feeds = 0;
  for (const auto& block : read.blocks) {
    if (block.feed_mm_per_min <= 0.0) continue;
    ++feeds;
    EXPECT_GE(block.feed_mm_per_min, 10.0);
    EXPECT_LE(block.feed_mm_per_min, 10000.0);
  }
  EXPECT_GT(feeds, 100);
  EXPECT_NE(read_text(program).find("(target force N: 300)"), std::string::npos);
  EXPECT_NE(read_text(report).find("\"format\": \"feedplan-plan\""), std::string::npos);
  EXPECT_EQ(read_text(csv).rfind("s_mm,x_mm,y_mm,engagement_deg,chip_thickness_mm,contact_length_mm,feed_mm_per_min,"
                                 "predicted_force_n,time_s",
                                 0),
            0u);
  EXPECT_NE(read_text(plot).find("<svg"), std::string::npos);
}

TEST_F(PlanCliTest, EveryDialect) {
  for (const char* dialect : {"linuxcnc", "fanuc", "haas"}) {
    const fs::path program = dir_ / (std::string(dialect) + ".nc");
    const RunResult r = run_feedplan(plan_args("corner.yaml", program) + " --dialect " + dialect);
    ASSERT_EQ(r.exit_code, 0) << dialect << "\n" << r.output;
    EXPECT_NO_THROW(feedplan::gcode::load_program(program)) << dialect;
  }
}

TEST_F(PlanCliTest, BadFlagsAreBadInputAndTouchNothing) {
  const fs::path program = write_spec("keep.nc", "(keep me)\n");
  const auto expect_bad = [&](const std::string& extra, const std::string& fragment) {
    const RunResult r = run_feedplan(plan_args("trochoid.yaml", program) + " " + extra);
    EXPECT_EQ(r.exit_code, 2) << extra << "\n" << r.output;
    EXPECT_NE(r.output.find(fragment), std::string::npos) << "expected '" << fragment << "' in:\n" << r.output;
    EXPECT_EQ(read_text(program), "(keep me)\n") << extra;
  };
  expect_bad("--dialect heidenhain", "--dialect");
  expect_bad("--mode fast", "--mode");
  expect_bad("--target-force -5", "--target-force");
  expect_bad("--decimals 12", "decimals");
  expect_bad("--merge-tolerance 7", "--merge-tolerance = 7");
  expect_bad("--constant-feed 50000", "--constant-feed");
  expect_bad("--report " + (dir_ / "no_such_dir" / "r.json").string(), "--report");
  expect_bad("--model-id 999", "--model-id");
}

TEST_F(PlanCliTest, NonsenseMachineLimitsInTheSpecAreBadInput) {
  const fs::path bad = write_spec("bad.yaml", read_text(kSamples + "/corner.yaml"));
  std::string text = read_text(bad);
  text.replace(text.find("min_feed_mm_per_min: 10"), std::string("min_feed_mm_per_min: 10").size(),
               "min_feed_mm_per_min: 20000");
  std::ofstream(bad) << text;
  const fs::path program = dir_ / "p.nc";
  const RunResult r = run_feedplan("plan " + bad.string() + " --db " + db_ + " -o " + program.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("min_feed_mm_per_min"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(program));
}

TEST_F(PlanCliTest, NoModelForTheMaterialFails) {
  std::string text = read_text(kSamples + "/corner.yaml");
  text.replace(text.find("material: S50C"), std::string("material: S50C").size(), "material: Al7075-T6");
  const fs::path aluminium = write_spec("al.yaml", text);
  const fs::path program = dir_ / "p.nc";
  const RunResult r = run_feedplan("plan " + aluminium.string() + " --db " + db_ + " -o " + program.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("no force model"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(program));
}

TEST_F(PlanCliTest, UnknownMaterialIsBadInput) {
  std::string text = read_text(kSamples + "/corner.yaml");
  text.replace(text.find("material: S50C"), std::string("material: S50C").size(), "material: Unobtainium");
  const RunResult r = run_feedplan("plan " + write_spec("u.yaml", text).string() + " --db " + db_ + " -o " + (dir_ / "p.nc").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("Unobtainium"), std::string::npos) << r.output;
}

TEST_F(PlanCliTest, TargetBelowTheForceAtTheMinimumFeedFailsWithoutAProgram) {
  const fs::path program = dir_ / "p.nc";
  const fs::path report = dir_ / "r.json";
  const RunResult r = run_feedplan(plan_args("corner.yaml", program) + " --target-force 5 --report " + report.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("not met"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(program));
  EXPECT_TRUE(fs::exists(report));  // to show where
}

TEST_F(PlanCliTest, SimulateComparesWithTheTargetOnStraightWalls) {
  const RunResult r = run_feedplan(plan_args("corner.yaml", dir_ / "c.nc") + " --simulate --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The sample model was fitted on straight cuts of this tool in this material: on the walls and the
  // steady arc the virtual machine's peaks are within 5 % of the target.
  const auto at = r.output.find("\"steady_max_abs_error_percent\": ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_LT(std::stod(r.output.substr(at + 32)), 5.0) << r.output;
}

}  // namespace
