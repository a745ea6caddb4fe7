// End-to-end tests of `feedplan plan` on a database holding the sample model for the Ø10 4-flute end
// mill in S50C (tests/data/cli/s50c_d10_model.json, exported from the sample database): the program,
// report and plot are written and read back; every kind of bad input exits 2 naming the field with no
// output touched; no model for the material and an unreachable target exit 1.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstddef>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/gcode/reader.hpp"
#include "run_feedplan.hpp"
#include "text_lines.hpp"

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

// Regression: the pocket's wall pass met up to 144° of material in the corners, more than any feed
// holds at 300 N with 10 mm depth ("target not met"). With the corner clean-up and the semi-finishing
// contour the sample plans at its own target.
TEST_F(PlanCliTest, PocketSamplePlansAtItsTarget) {
  const fs::path program = dir_ / "p.nc";
  const RunResult r = run_feedplan(plan_args("pocket.yaml", program) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The JSON summary on stdout; the notes on stderr follow it.
  const std::size_t begin = r.output.find('{');
  const std::size_t end = r.output.find("\n}\n", begin);
  ASSERT_NE(end, std::string::npos) << r.output;
  const auto summary = nlohmann::json::parse(r.output.substr(begin, end + 2 - begin));
  const std::string status = summary["status"].get<std::string>();
  EXPECT_TRUE(status == "ok" || status == "extrapolated") << status;
  EXPECT_EQ(summary["target_force_n"].get<double>(), 300.0);
  EXPECT_LE(summary["max_predicted_force_n"].get<double>(), 300.0 + 0.5);
  EXPECT_TRUE(fs::exists(program));
}

// --target-sweep: one plan per target, printed as JSON, the curve drawn; no program. The cycle times fall as
// the target rises, and each matches a plan made at that target alone. Bad ranges, and flags that write a
// plan, are bad input.
TEST_F(PlanCliTest, TargetSweepPrintsTheCurveAndWritesNoProgram) {
  const fs::path plot = dir_ / "sweep.svg";
  const RunResult r = run_feedplan("plan " + kSamples + "/corner.yaml --db " + db_ + " --target-sweep 300:400:50 --json --plot " +
                                   plot.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto out = nlohmann::json::parse(r.output);
  ASSERT_EQ(out["targets"].size(), 3u);
  EXPECT_GT(out["targets"][0]["cycle_time_s"].get<double>(), out["targets"][2]["cycle_time_s"].get<double>());
  EXPECT_TRUE(fs::exists(plot));
  const fs::path program = dir_ / "at350.nc";
  const RunResult single = run_feedplan(plan_args("corner.yaml", program) + " --target-force 350 --json");
  ASSERT_EQ(single.exit_code, 0) << single.output;
  const auto one = nlohmann::json::parse(single.output.substr(single.output.find('{')));
  EXPECT_NEAR(out["targets"][1]["cycle_time_s"].get<double>(), one["cycle_time_s"].get<double>(), 1e-9);

  const RunResult bad = run_feedplan("plan " + kSamples + "/corner.yaml --db " + db_ + " --target-sweep 400:300:50");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--target-sweep = '400:300:50': TO must be ≥ FROM"), std::string::npos) << bad.output;
  const fs::path not_written = dir_ / "never.nc";
  const RunResult both = run_feedplan(plan_args("corner.yaml", not_written) + " --target-sweep 300:400:50");
  EXPECT_EQ(both.exit_code, 2) << both.output;
  EXPECT_NE(both.output.find("-o is not used with --target-sweep"), std::string::npos) << both.output;
  EXPECT_FALSE(fs::exists(not_written));
}

// Every dialect reads back, and ends with the return to the machine's Z home before the spindle stops;
// --no-safe-return writes the same program without those lines.
TEST_F(PlanCliTest, EveryDialect) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> endings = {
      {"linuxcnc", {"G53 G0 Z0.", "M5", "M2"}},
      {"fanuc", {"G91 G28 Z0.", "G90", "M05", "M30", "%"}},
      {"haas", {"G91 G28 Z0.", "G90", "M05", "M30", "%"}}};
  for (const auto& [dialect, ending] : endings) {
    SCOPED_TRACE(dialect);
    const fs::path program = dir_ / (dialect + ".nc");
    const RunResult r = run_feedplan(plan_args("corner.yaml", program) + " --dialect " + dialect);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NO_THROW(feedplan::gcode::load_program(program));
    const std::vector<std::string> lines = feedplan::test_support::lines_of(read_text(program));
    ASSERT_GT(lines.size(), ending.size());
    EXPECT_EQ(std::vector<std::string>(lines.end() - static_cast<std::ptrdiff_t>(ending.size()), lines.end()), ending);

    const fs::path plain = dir_ / (dialect + "_plain.nc");
    const RunResult without = run_feedplan(plan_args("corner.yaml", plain) + " --dialect " + dialect + " --no-safe-return");
    ASSERT_EQ(without.exit_code, 0) << without.output;
    std::vector<std::string> expected;
    for (const std::string& line : lines) {
      if (line != "G53 G0 Z0." && line != "G91 G28 Z0." && line != "G90") expected.push_back(line);
    }
    EXPECT_EQ(feedplan::test_support::lines_of(read_text(plain)), expected);
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

// The tool's own plunge feed per tooth from the spec: every move that descends below the stock top runs at
// most at f_z,plunge · Z · n · length / descent (recomputed from the program read back), it binds somewhere
// (the default 0.0025 · D would allow more there), and the report keeps it; beyond the diameter it is bad input.
// The program holds z to 0.001 mm, so moves descending less than 0.1 mm are left out (their written descent
// is off by up to 1 %; the planner limited the exact one).
TEST_F(PlanCliTest, TheSpecsPlungeFeedPerToothLimitsTheDescent) {
  std::string text = read_text(kSamples + "/helical_boring.yaml");
  const std::string tool = "tool: {diameter_mm: 10, flutes: 4,";
  ASSERT_NE(text.find(tool), std::string::npos);
  const fs::path spec = write_spec("slow_plunge.yaml", std::string(text).replace(text.find(tool), tool.size(),
                                                                                   tool + " max_plunge_feed_per_tooth_mm: 0.002,"));
  const fs::path program = dir_ / "p.nc";
  const fs::path report = dir_ / "p.json";
  const RunResult r = run_feedplan("plan " + spec.string() + " --db " + db_ + " -o " + program.string() + " --report " +
                                   report.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(read_text(report).find("\"max_plunge_feed_per_tooth_mm\": 0.002"), std::string::npos);
  const feedplan::geometry::Program read = feedplan::gcode::load_program(program);
  int descending = 0;
  int binding = 0;
  for (std::size_t m = 0; m < read.path.moves.size(); ++m) {
    const feedplan::geometry::Move& move = read.path.moves[m];
    const double descent_mm = move.start.z_mm - move.end.z_mm;
    if (move.kind == feedplan::geometry::MoveKind::kRapid || descent_mm < 0.1 || move.end.z_mm >= 0.0) continue;
    ++descending;
    const double limit = 0.002 * 4 * 2800 * feedplan::geometry::length_mm(move) / descent_mm;
    EXPECT_LE(read.blocks[m].feed_mm_per_min, limit * 1.01) << "move " << m;
    binding += read.blocks[m].feed_mm_per_min > 0.95 * limit;
  }
  EXPECT_GT(descending, 0);
  EXPECT_GT(binding, 0);

  const fs::path bad = write_spec("bad_plunge.yaml", std::string(text).replace(text.find(tool), tool.size(),
                                                                               tool + " max_plunge_feed_per_tooth_mm: 11,"));
  const RunResult refused = run_feedplan("plan " + bad.string() + " --db " + db_ + " -o " + (dir_ / "q.nc").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("tool.max_plunge_feed_per_tooth_mm (line 4) = 11: must be in (0, 10]"), std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(dir_ / "q.nc"));
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
