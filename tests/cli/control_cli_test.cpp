// `feedplan control`: the feedback controllers on the virtual machine from the command line. The hybrid is
// judged against the plan alone as another path of the product runs it — `plan` writes the program,
// `simulate` cuts it on a materials file whose coefficients are 1.4 × the bundled S50C's (written out here,
// not computed by the code under test) — and bad flags exit 2 naming the flag, leaving outputs untouched.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "hard_s50c_materials.hpp"
#include "run_feedplan.hpp"

namespace feedplan::cli_test {
namespace {

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;

class ControlCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "models.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_model.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }

  // The corner sample with a constant feed for the controller alone.
  fs::path corner_with_feed() {
    std::string text = read_text(kSamples + "/corner.yaml");
    text += "feed_mm_per_min: 1200\n";
    return write_spec("corner_feed.yaml", text);
  }

  std::string db_;
};

nlohmann::json json_of(const RunResult& r) {
  // The summary on stdout; warnings, on stderr, follow it.
  const std::size_t start = r.output.find('{');
  const std::size_t end = r.output.find("\n}");
  if (start == std::string::npos || end == std::string::npos) return nlohmann::json::object();
  return nlohmann::json::parse(r.output.substr(start, end + 2 - start));
}

TEST_F(ControlCliTest, HybridOnAHarderMachineOvershootsLessThanThePlanAlone) {
  const fs::path program = dir_ / "corner.nc";
  const fs::path hard = write_spec("hard.yaml", kHardS50C);
  RunResult r = run_feedplan("plan " + kSamples + "/corner.yaml --db " + db_ + " -o " + program.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_feedplan("simulate " + program.string() + " --spec " + kSamples + "/corner.yaml --materials " + hard.string() +
                   " --log " + (dir_ / "alone.csv").string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const double alone_peak_n = json_of(r)["max_revolution_peak_n"].get<double>();

  r = run_feedplan("control " + kSamples + "/corner.yaml --controller robust-servo --hybrid --machine-scale 1.4 --db " + db_ +
                   " --json --log " + (dir_ / "hybrid.csv").string() + " --plot " + (dir_ / "hybrid.svg").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json out = json_of(r);
  const double target_n = out["target_force_n"].get<double>();
  const double hybrid_peak_n = out["result"]["max_peak_n"].get<double>();
  std::printf("corner, 350 N, machine × 1.4: plan alone (plan + simulate) largest peak %.1f N (%+.1f %%), "
              "hybrid %.1f N (%+.1f %%), control's own plan-alone run %.1f N; cycle %.3f s hybrid, %.3f s alone\n",
              alone_peak_n, 100.0 * (alone_peak_n / target_n - 1.0), hybrid_peak_n, 100.0 * (hybrid_peak_n / target_n - 1.0),
              out["plan_alone"]["max_peak_n"].get<double>(), out["result"]["cycle_time_s"].get<double>(),
              out["plan_alone"]["cycle_time_s"].get<double>());
  // The plan alone does overshoot on this machine (else the comparison says nothing) …
  ASSERT_GT(alone_peak_n, 1.15 * target_n);
  // … and the feedback trims it.
  EXPECT_LT(hybrid_peak_n, alone_peak_n);
  // control's own plan-alone run is the same cut as plan + simulate (the program in memory rather than
  // read back from its text).
  EXPECT_NEAR(out["plan_alone"]["max_peak_n"].get<double>(), alone_peak_n, 0.02 * alone_peak_n);
  EXPECT_GT(out["controller_steps"].get<int>(), 0);
  EXPECT_NE(read_text(dir_ / "hybrid.svg").find("panel-override"), std::string::npos);
  EXPECT_NE(read_text(dir_ / "hybrid.csv").find("fx_n"), std::string::npos);
}

TEST_F(ControlCliTest, ControllerAloneRunsTheSpecsConstantFeedProgram) {
  const fs::path spec = corner_with_feed();
  const RunResult r = run_feedplan("control " + spec.string() + " --controller integral --sensor spindle --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json out = json_of(r);
  EXPECT_EQ(out["controller"], "integral");
  EXPECT_EQ(out["sensor"], "spindle");
  EXPECT_FALSE(out["hybrid"].get<bool>());
  EXPECT_GT(out["result"]["in_cut_revolutions"].get<int>(), 10);
  EXPECT_GT(out["result"]["cycle_time_s"].get<double>(), 0.0);
}

// Every bad flag: exit 2, the flag named with its value or what is expected.
TEST_F(ControlCliTest, BadFlagsExitTwoNamingTheFlag) {
  const std::string corner = kSamples + "/corner.yaml";
  const std::string spec = corner_with_feed().string();
  const std::pair<std::string, std::string> cases[] = {
      {"control " + spec + " --controller pid", "--controller = 'pid': must be one of integral, variable-gain"},
      {"control " + spec + " --controller integral --sensor strain", "--sensor = 'strain'"},
      {"control " + spec + " --controller integral --target-force -5", "--target-force = -5"},
      {"control " + spec + " --controller integral --target-force nan", "--target-force"},
      {"control " + spec + " --controller integral --machine-scale 0", "--machine-scale = 0"},
      {"control " + spec + " --controller integral --machine-scale 1.2 --machine " + kSamples + "/../data/machines/steel-mild.yaml",
       "--machine-scale conflicts with --machine"},
      {"control " + spec + " --controller integral --tool diameter_mm=10,flutes=4,helix_deg=30", "--tool only applies to a PROGRAM"},
      {"control " + corner + " --controller integral", "feed_mm_per_min is not in the spec"},
      {"control " + spec + " --controller integral --db " + db_, "--db only applies with --hybrid"},
      {"control " + kSamples + "/trochoid_constant_feed.ngc --controller integral --hybrid --tool "
       "diameter_mm=10,flutes=4,helix_deg=30 --material S50C --target-force 300",
       "--hybrid applies to a cycle spec"},
      {"control " + kSamples + "/trochoid_constant_feed.ngc --controller integral --material S50C --target-force 300",
       "--tool is required with a PROGRAM"},
      {"control " + kSamples + "/README.md --controller integral", "input = '"},
      {"control " + kSamples + "/trochoid_constant_feed.ngc --controller integral --tool diameter_mm=10,flutes=4,helix_deg=30 "
       "--material S50C --target-force 300 --depth-steps 1,2",
       "--depth-steps applies to a cycle spec"},
      {"control " + spec + " --controller integral --depth-steps 1", "--depth-steps = '1': must give at least 2 depths"},
      {"control " + spec + " --controller integral --depth-steps 1,x", "item 2 'x' is not a finite number"},
      {"control " + spec + " --controller integral --depth-steps 1,20", "--depth-steps [1] = 20: must be finite and in (0, 10]"},
      {"control " + spec + " --controller integral --depth-steps 1,2 --step-length 5", "--step-length = 5: must be finite and > 10"},
      {"control " + spec + " --controller integral --step-length 40", "--step-length only applies with --depth-steps"},
      {"control " + spec + " --controller integral --depth-steps 1,2 --hybrid", "--depth-steps conflicts with --hybrid"},
      {"control " + spec + " --controller integral --calibration x.json", "--calibration only applies with --sensor currents"},
  };
  for (const auto& [arguments, expected] : cases) {
    const RunResult r = run_feedplan(arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << arguments << "\n" << r.output;
  }
}

// --depth-steps: the slot's depths and steady windows as worked out by hand for the corner's Ø10 mm tool
// held 30 mm each (1 mm: x 0…30, steady from 15; a 2 mm ramp; 2 mm: x 32…62, steady from 47), each with
// revolutions in its window and a steady error no larger than the run's largest miss of the target.
TEST_F(ControlCliTest, DepthStepsCutASlotAndReportEachDepthsSteadyError) {
  const RunResult r =
      run_feedplan("control " + corner_with_feed().string() + " --controller multi-model-1 --depth-steps 1,2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json out = json_of(r);
  ASSERT_EQ(out["depth_steps"].size(), 2u) << r.output;
  const double windows[2][3] = {{1.0, 15.0, 30.0}, {2.0, 47.0, 62.0}};
  const double largest_miss = std::max(out["result"]["max_peak_n"].get<double>() - 350.0, 350.0);
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& d = out["depth_steps"][i];
    EXPECT_DOUBLE_EQ(d["depth_mm"].get<double>(), windows[i][0]);
    EXPECT_DOUBLE_EQ(d["steady_from_x_mm"].get<double>(), windows[i][1]);
    EXPECT_DOUBLE_EQ(d["steady_to_x_mm"].get<double>(), windows[i][2]);
    EXPECT_GT(d["revolutions"].get<int>(), 10);
    EXPECT_LE(d["steady_error_n"].get<double>(), largest_miss);
    EXPECT_LE(std::abs(d["mean_error_n"].get<double>()), d["steady_error_n"].get<double>() + 1e-9);
  }
  const RunResult text = run_feedplan("control " + corner_with_feed().string() + " --controller integral --depth-steps 1,2");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("depth 1 mm: steady error"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("depth 2 mm: steady error"), std::string::npos) << text.output;
}

// --calibration: a file with the virtual machine's own constants (seed 002 Eqs. 12–13) gives the run
// without it to the newton; one whose slopes are doubled reads half the force, so the controller cuts
// harder — the file is what the currents are read with.
TEST_F(ControlCliTest, CalibrationFileIsWhatTheCurrentsAreReadWith) {
  const auto calibration = [&](const char* name, double scale) {
    const fs::path path = dir_ / name;
    nlohmann::json doc{{"format", "feedplan-current-calibration"},
                       {"format_version", 1},
                       {"x", {{"a_a", 4.12}, {"b_a_per_n", 0.00362 * scale}}},
                       {"y", {{"a_a", 7.24}, {"b_a_per_n", 0.00450 * scale}}},
                       {"z", {{"a_a", 0.0}, {"b_a_per_n", 0.0}}}};
    std::ofstream(path) << doc.dump();
    return path.string();
  };
  const std::string base = "control " + corner_with_feed().string() + " --controller integral --sensor currents --json";
  const RunResult own = run_feedplan(base);
  const RunResult same = run_feedplan(base + " --calibration " + calibration("same.json", 1.0));
  const RunResult doubled = run_feedplan(base + " --calibration " + calibration("doubled.json", 2.0));
  ASSERT_EQ(own.exit_code, 0) << own.output;
  ASSERT_EQ(same.exit_code, 0) << same.output;
  ASSERT_EQ(doubled.exit_code, 0) << doubled.output;
  const double own_peak = json_of(own)["result"]["max_peak_n"].get<double>();
  EXPECT_NEAR(json_of(same)["result"]["max_peak_n"].get<double>(), own_peak, 1e-6);
  EXPECT_GT(json_of(doubled)["result"]["max_peak_n"].get<double>(), 1.2 * own_peak);
  EXPECT_NE(same.output.find("same.json"), std::string::npos) << same.output;
}

TEST_F(ControlCliTest, AnOutputThatCannotBeWrittenIsBadInputAndLeavesTheOthersUntouched) {
  const fs::path plot = dir_ / "plot.svg";
  std::ofstream(plot) << "old plot";
  const RunResult r = run_feedplan("control " + corner_with_feed().string() + " --controller integral --plot " +
                                   plot.string() + " --log " + (dir_ / "missing" / "log.csv").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--log"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(plot), "old plot");
}

}  // namespace
}  // namespace feedplan::cli_test
