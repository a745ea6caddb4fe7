// End-to-end tests of `feedplan optimize` on a program in the style of FreeCAD's linuxcnc post
// (tests/data/cli/optimize_slot.ngc: a G1 used as a rapid above the stock, a plunge beside the stock, a
// slot into it, an arc and a wall), with the sample model of the Ø10 4-flute end mill in S50C and the
// stock tests/data/cli/optimize_stock.yaml. The judge is the virtual machine (first-principles forces,
// not the model): the input, at its F500, overshoots the target; the re-fed program does not. Bad input
// exits 2 naming the flag, and the output is not touched.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "run_feedplan.hpp"
#include "text_lines.hpp"

namespace {

using namespace feedplan::cli_test;
using feedplan::test_support::lines_of;

const std::string kData = std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/";
const std::string kTool = " --tool diameter_mm=10,flutes=4,helix_deg=30 ";

class OptimizeCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + kData + "s50c_d10_model.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }

  std::string optimize_args(const fs::path& output) const {
    return "optimize " + kData + "optimize_slot.ngc -o " + output.string() + kTool + "--material S50C --stock " + kData +
           "optimize_stock.yaml --db " + db_;
  }

  // The largest per-revolution peak of `program` on the virtual machine, N.
  double simulated_peak_n(const fs::path& program) {
    const RunResult r = run_feedplan("simulate " + program.string() + kTool + "--material S50C --stock " + kData +
                                     "optimize_stock.yaml --log " + (dir_ / "log.csv").string() + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return nlohmann::json::parse(r.output)["max_revolution_peak_n"].get<double>();
  }

  std::string db_;
};

// The plunge beside the slot (X-10, Z 0 → −5 below the stock's top) runs at the tool's plunge feed: F ≤ f_z·Z·n,
// 0.025 mm per tooth by default for a Ø10 cutter (0.0025·D) or the tool's own from --tool, and on the F level
// just under it (levels 2 % apart); a plunge feed the tool cannot have is bad input.
TEST_F(OptimizeCliTest, ThePlungeRunsAtTheToolsPlungeFeed) {
  const double flutes = 4.0, rpm = 2800.0;  // the program's S and the tool's teeth
  for (const double f_z : {0.025, 0.01}) {
    SCOPED_TRACE(f_z);
    const fs::path output = dir_ / "plunge.ngc";
    std::string args = optimize_args(output) + " --target-force 550";
    if (f_z != 0.025) {
      args.replace(args.find(kTool), kTool.size(),
                   " --tool diameter_mm=10,flutes=4,helix_deg=30,max_plunge_feed_per_tooth_mm=0.01 ");
    }
    const RunResult r = run_feedplan(args);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    double plunge_feed = 0.0;
    for (const std::string& line : lines_of(read_text(output))) {
      if (line.rfind("G1 X-10.000 Y0.000 Z-5.000", 0) == 0) plunge_feed = std::stod(line.substr(line.find('F') + 1));
    }
    const double limit = f_z * flutes * rpm;
    EXPECT_LE(plunge_feed, limit) << read_text(output);
    EXPECT_GE(plunge_feed, limit / 1.02 - 1.0) << read_text(output);
  }
  const RunResult bad = run_feedplan(
      "optimize " + kData + "optimize_slot.ngc -o " + (dir_ / "bad.ngc").string() +
      " --tool diameter_mm=10,flutes=4,max_plunge_feed_per_tooth_mm=12 --material S50C --stock " + kData +
      "optimize_stock.yaml --db " + db_ + " --target-force 550");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--tool max_plunge_feed_per_tooth_mm = 12: must be > 0 mm and at most the diameter"),
            std::string::npos)
      << bad.output;
  EXPECT_FALSE(fs::exists(dir_ / "bad.ngc"));
}

TEST_F(OptimizeCliTest, TheReFedProgramHoldsTheTargetWhereTheInputOvershot) {
  constexpr double kTarget = 550.0;
  const fs::path output = dir_ / "refed.ngc";
  const RunResult r = run_feedplan(optimize_args(output) + " --target-force 550");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("wrote " + output.string()), std::string::npos) << r.output;
  // Every line that is not a feed move comes through; the feed moves' lines keep their words but F.
  const std::vector<std::string> in = lines_of(read_text(kData + "optimize_slot.ngc"));
  const std::vector<std::string> out = lines_of(read_text(output));
  for (const std::string& line : in) {
    if (line.rfind("G1", 0) == 0 || line.rfind("G3", 0) == 0) continue;
    EXPECT_NE(std::find(out.begin(), out.end(), line), out.end()) << "'" << line << "' is not in the output";
  }
  EXPECT_NE(std::find(out.begin(), out.end(), "G1 X-10.000 Y0.000 Z2.000 F10000. (G1 as a rapid, above the stock)"),
            out.end())
      << "the G1 above the stock runs at the machine's largest feed";
  const double input_peak = simulated_peak_n(kData + "optimize_slot.ngc");
  const double refed_peak = simulated_peak_n(output);
  std::printf("largest per-revolution peak on the virtual machine: input %.1f N, re-fed %.1f N (target %.0f N)\n",
              input_peak, refed_peak, kTarget);
  EXPECT_GT(input_peak, 1.05 * kTarget);
  EXPECT_LE(refed_peak, 1.05 * kTarget);
}

// A program of two tools (tests/data/cli/optimize_two_tools.ngc): each tool's moves are planned on the
// material the tools before it left, so the second tool, re-cutting the first one's slot, runs in air at the
// machine's largest feed. Without --tools the program's tools are named with their lines.
TEST_F(OptimizeCliTest, EachToolIsPlannedOnWhatTheToolsBeforeItLeft) {
  const fs::path output = dir_ / "two.ngc";
  const std::string args = "optimize " + kData + "optimize_two_tools.ngc -o " + output.string() +
                           " --material S50C --stock " + kData + "optimize_stock.yaml --target-force 550 --db " + db_;
  const RunResult r = run_feedplan(args + " --tools " + kData + "optimize_tools.yaml");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("T1, lines 8–12: SC EM D10 Z4"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("T2, lines 18–21"), std::string::npos) << r.output;
  const std::vector<std::string> out = lines_of(read_text(output));
  for (const char* kept : {"M6 T1", "G43 H1", "M6 T2", "G43 H2", "M5"}) {
    EXPECT_NE(std::find(out.begin(), out.end(), kept), out.end()) << kept;
  }
  // The second tool's slot: after its tool change, it runs at F10000 (in air); its plunge beside the stock,
  // below the stock's top, at the tool's plunge feed all the same.
  const auto change = std::find(out.begin(), out.end(), "M6 T2");
  ASSERT_NE(change, out.end());
  bool second_slot_in_air = false, plunge_at_plunge_feed = false;
  for (auto it = change; it != out.end(); ++it) {
    if (it->rfind("G1 X30.000 Y0.000 Z-5.000", 0) == 0) second_slot_in_air = it->find("F10000") != std::string::npos;
    if (it->rfind("G1 X-10.000 Y0.000 Z-5.000", 0) == 0) plunge_at_plunge_feed = it->find("F10000") == std::string::npos;
  }
  EXPECT_TRUE(second_slot_in_air) << read_text(output);
  EXPECT_TRUE(plunge_at_plunge_feed) << read_text(output);
  const RunResult without = run_feedplan(args + " --tool diameter_mm=10,flutes=4");
  EXPECT_EQ(without.exit_code, 2) << without.output;
  EXPECT_NE(without.output.find("--tools is required: the program changes tools (T1 from line 8, T2 from line 18)"),
            std::string::npos)
      << without.output;
}

// Full-width slots of a 4 mm two-flute cutter in Al7075-T6 (tests/data/cli/optimize_al_slot.ngc), with only
// the Ø6 three-flute cutter's models in the database (tests/data/cli/al7075_d6_models.json: its response
// surface, fitted on side cuts of 26–66°, and its cutting mechanics). The slots leave the response surface's
// fitted contact lengths, so optimize plans with the cutting mechanics on this cutter's geometry. The judge
// is a virtual machine whose physics differ from the model in shape (data/machines/aluminium-two-flute.yaml:
// less edge force, a size effect, 5 µm runout, a helix 4° off, a 1 kHz dynamometer with noise): the input
// overshoots the target there, the re-fed program does not.
TEST_F(OptimizeCliTest, SlotsOutsideTheResponseSurfacePlanWithTheCuttingMechanicsOfAnotherCutter) {
  constexpr double kTarget = 130.0;
  const std::string al_db = (dir_ / "al.db").string();
  ASSERT_EQ(run_feedplan("db init --db " + al_db).exit_code, 0);
  const RunResult imported = run_feedplan("db import " + kData + "al7075_d6_models.json --db " + al_db);
  ASSERT_EQ(imported.exit_code, 0) << imported.output;
  const std::string tool = " --tool diameter_mm=4,flutes=2,helix_deg=30 ";
  const std::string stock = " --stock " + kData + "optimize_stock.yaml ";
  const fs::path output = dir_ / "al_refed.ngc";
  const RunResult r = run_feedplan("optimize " + kData + "optimize_al_slot.ngc -o " + output.string() + tool +
                                   "--material Al7075-T6" + stock + "--target-force 130 --db " + al_db);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("kind: mechanistic: the path's contact lengths leave the response surface's fitted"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("identified on SC EM D6 Z3: its cutting and edge coefficients, with this cutter's helix 30°"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("meets material"), std::string::npos) << "the retract from the slot's end is no collision\n"
                                                                  << r.output;
  const auto peak_on_machine = [&](const std::string& program) {
    const RunResult run = run_feedplan("simulate " + program + tool + "--machine " + std::string(FEEDPLAN_SAMPLES_DIR) +
                                       "/../data/machines/aluminium-two-flute.yaml" + stock + "--log " +
                                       (dir_ / "al_log.csv").string() + " --json");
    EXPECT_EQ(run.exit_code, 0) << run.output;
    const auto summary = nlohmann::json::parse(run.output.substr(run.output.find('{')));
    return std::make_pair(summary["max_revolution_peak_n"].get<double>(), summary["cycle_time_s"].get<double>());
  };
  const auto [input_peak, input_s] = peak_on_machine(kData + "optimize_al_slot.ngc");
  const auto [refed_peak, refed_s] = peak_on_machine(output.string());
  std::printf("aluminium-two-flute machine: input %.1f N in %.2f s, re-fed %.1f N in %.2f s (target %.0f N)\n",
              input_peak, input_s, refed_peak, refed_s, kTarget);
  EXPECT_GT(input_peak, 1.05 * kTarget);
  EXPECT_LE(refed_peak, 1.05 * kTarget);
}

TEST_F(OptimizeCliTest, BadInputExitsTwoNamingTheFlagAndLeavesTheOutput) {
  const fs::path output = dir_ / "kept.ngc";
  { std::ofstream(output) << "old"; }
  struct Case {
    std::string extra;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"", "--target-force is required"},
      {" --target-force 0", "--target-force = 0"},
      {" --target-force 500 --stock-box 0,0,-10,60,40,0", "give one of --stock STOCK.yaml and --stock-box"},
      {" --target-force 500 --spindle-rpm -5", "--spindle-rpm = -5"},
      {" --target-force 500 --tool diameter_mm=abc", "--tool"},
      {" --target-force 500 --tools " + kData + "optimize_tools.yaml", "give one of --tool"},
  };
  for (const Case& c : cases) {
    const RunResult r = run_feedplan(optimize_args(output) + c.extra);
    EXPECT_EQ(r.exit_code, 2) << c.extra << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.extra << "\n" << r.output;
    EXPECT_EQ(read_text(output), "old") << c.extra;
  }
  const RunResult box = run_feedplan("optimize " + kData + "optimize_slot.ngc -o " + output.string() + kTool +
                                     "--material S50C --stock-box 0,0,-10,60,40 --target-force 500 --db " + db_);
  EXPECT_EQ(box.exit_code, 2) << box.output;
  EXPECT_NE(box.output.find("--stock-box = '0,0,-10,60,40': 5 numbers; expected six"), std::string::npos) << box.output;
  EXPECT_EQ(read_text(output), "old");
}

}  // namespace
