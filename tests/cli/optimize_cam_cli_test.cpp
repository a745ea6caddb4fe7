// `feedplan optimize` on a program in the style of Fusion's posts (tests/data/cli/optimize_fusion_style.ngc: G28 G91
// Z0., a helical entry of R arcs, a G18 lead-in arc, G41 cutter compensation with D), and on a real hand-written Haas program (../shared/cam/handwritten_nims_mill_hp_4.ngc beside the
// repository; skipped when absent): a profile and a slot under G41 cutter compensation, spot and peck drilling
// cycles, G28/G53 retracts, five tools (tests/data/cli/haas_tools.yaml), a block of 3.5 × 2.5 × 0.75 in taken as
// Al7075-T6 (the database's aluminium; the part's 6061 is softer, so the plan errs safe), with only the Ø6
// cutter's models (tests/data/cli/al7075_d6_models.json). The truths: LinuxCNC's interpreter reads the same path
// from input and output, and the drilling lines come through as written.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "../gcode/rs274_runner.hpp"
#include "run_feedplan.hpp"
#include "text_lines.hpp"

namespace {

using namespace feedplan::cli_test;
using feedplan::test_support::lines_of;
namespace oracle = feedplan::gcode::oracle;

const std::string kData = std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/";
// 1 µm, plus half of rs274's last printed digit (4 decimals of an inch) on each of three axes.
const double kToleranceMm = 0.001 + std::sqrt(3.0) * 0.5 * 0.0001 * 25.4;
const fs::path kHaas =
    fs::path(FEEDPLAN_TEST_DATA_DIR) / ".." / ".." / ".." / "shared" / "cam" / "handwritten_nims_mill_hp_4.ngc";

// `text` without what rs274 refuses: the lines M31 and M33 (Haas chip conveyor), the P of the G81 line.
std::string as_linuxcnc_reads_it(const std::string& text) {
  std::string out;
  for (std::string line : lines_of(text)) {
    if (line == "M31" || line == "M33") line.clear();
    if (line.rfind("G81", 0) == 0) {
      if (const std::size_t p = line.find(" P0.5"); p != std::string::npos) line.erase(p, 5);
    }
    out += line + "\n";
  }
  return out;
}

// Every end point of `before`'s moves is an end point of `after`'s, in order, to kToleranceMm: the output runs
// the same path, only with more points on it.
void expect_same_path(const oracle::OracleRun& before, const oracle::OracleRun& after) {
  std::size_t j = 0;
  for (std::size_t i = 0; i < before.moves.size(); ++i) {
    const auto& e = before.moves[i].end;
    const auto near = [&](const oracle::OracleMove& m) {
      return std::hypot(std::hypot(m.end.x_mm - e.x_mm, m.end.y_mm - e.y_mm), m.end.z_mm - e.z_mm) <= kToleranceMm;
    };
    while (j < after.moves.size() && !near(after.moves[j])) ++j;
    ASSERT_LT(j, after.moves.size()) << "input move " << i << " does not end where an output move does";
  }
}

// `line` without its F word.
std::string without_feed(const std::string& line) {
  const std::size_t f = line.find(" F");
  return f == std::string::npos ? line : line.substr(0, f);
}

TEST(OptimizeFusionStyle, LeadInArcsAndCompensatedMovesKeepTheirLinesAndLinuxCncReadsTheSamePath) {
  const fs::path dir = fs::temp_directory_path() / ("feedplan_fusion_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string db = (dir / "al.db").string();
  ASSERT_EQ(run_feedplan("db init --db " + db).exit_code, 0);
  ASSERT_EQ(run_feedplan("db import " + kData + "al7075_d6_models.json --db " + db).exit_code, 0);
  const fs::path output = dir / "fusion.ngc";
  const RunResult r = run_feedplan("optimize " + kData + "optimize_fusion_style.ngc -o " + output.string() +
                                   " --tool diameter_mm=6,flutes=2,helix_deg=30 --material Al7075-T6 --stock " + kData +
                                   "optimize_stock.yaml --target-force 250 --db " + db);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 arc in the XZ or YZ plane (G18, G19) became"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("lines 13–24 2D POCKET1: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("lines 27–43 2D CONTOUR1: "), std::string::npos) << r.output;
  const std::string input = read_text(kData + "optimize_fusion_style.ngc");
  const std::string refed = read_text(output);
  const std::vector<std::string> out = lines_of(refed);
  // The lead-in arc and the compensated moves are not split: only their F may change.
  for (const std::string& line : lines_of(input)) {
    if (line.rfind("G18", 0) == 0 || line.rfind("G41", 0) == 0 || line.rfind("G40", 0) == 0 || line == "G2 X7. Y25. R5.") {
      EXPECT_TRUE(std::any_of(out.begin(), out.end(), [&](const std::string& o) { return without_feed(o) == without_feed(line); }))
          << "'" << line << "' lost its words";
    }
  }
  const std::optional<fs::path> rs274 = oracle::find_rs274();
  if (!rs274) GTEST_SKIP() << "rs274 (linuxcnc-uspace) is not installed: the path comparison is not run";
  const std::string table = "T1 P1 D" + std::to_string(6.0 / 25.4) + "\n";  // rs274 reads tool tables in inches
  const oracle::OracleRun before = oracle::run_rs274_text(*rs274, input, table);
  const oracle::OracleRun after = oracle::run_rs274_text(*rs274, refed, table);
  ASSERT_EQ(before.exit_code, 0) << before.messages;
  ASSERT_EQ(after.exit_code, 0) << after.messages;
  ASSERT_GT(after.moves.size(), before.moves.size());
  expect_same_path(before, after);
  fs::remove_all(dir);
}

class OptimizeCamCliTest : public CliTest {
 protected:
  void SetUp() override {
    if (!fs::exists(kHaas)) GTEST_SKIP() << kHaas << " is absent (../shared/cam beside the repository)";
    CliTest::SetUp();
    db_ = (dir_ / "al.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + kData + "al7075_d6_models.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  std::string db_;
};

TEST_F(OptimizeCamCliTest, TheHaasProgramKeepsItsPathItsCyclesAndItsCompensation) {
  const fs::path output = dir_ / "hp4.ngc";
  const RunResult r = run_feedplan("optimize " + kHaas.string() + " -o " + output.string() + " --tools " + kData +
                                   "haas_tools.yaml --material Al7075-T6 --stock-box 0,0,-19.05,88.9,63.5,0 "
                                   "--target-force 700 --db " + db_);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* expected : {"T5, lines 54–64: drilling cycles, feeds kept as written", "lines 28–32 1ST LAP: ",
                               "lines 54–64 SPOT DRILL: feeds kept as written (drilling)",
                               "lines 100–149 POCKET MILLING. POINT 'C' TO POINT 'D': "}) {
    EXPECT_NE(r.output.find(expected), std::string::npos) << expected << "\n" << r.output;
  }
  const std::string input = read_text(kHaas);
  const std::string refed = read_text(output);
  const std::vector<std::string> out = lines_of(refed);
  // Drilling cycles, compensation switches and machine-position moves come through as written.
  for (const std::string& line : lines_of(input)) {
    if (line.rfind("G81", 0) == 0 || line.rfind("G83", 0) == 0 || line.rfind("G53", 0) == 0 || line == "G28" ||
        line.rfind("G40 X-1.0", 0) == 0) {
      EXPECT_NE(std::find(out.begin(), out.end(), line), out.end()) << "'" << line << "' is not in the output";
    }
  }
  // LinuxCNC reads the same path from both (with the tools' diameters for G41): every end point of the input
  // is an end point of the output, in order, to 1 µm; the output only adds points on the same moves.
  const std::optional<fs::path> rs274 = oracle::find_rs274();
  if (!rs274) GTEST_SKIP() << "rs274 (linuxcnc-uspace) is not installed: the path comparison is not run";
  const std::string table = "T1 P1 D0.5\nT2 P2 D0.375\nT5 P5 D0.25\nT7 P7 D0.25\nT8 P8 D0.3125\n";
  const oracle::OracleRun before = oracle::run_rs274_text(*rs274, as_linuxcnc_reads_it(input), table);
  const oracle::OracleRun after = oracle::run_rs274_text(*rs274, as_linuxcnc_reads_it(refed), table);
  ASSERT_EQ(before.exit_code, 0) << before.messages;
  ASSERT_EQ(after.exit_code, 0) << after.messages;
  ASSERT_GT(after.moves.size(), before.moves.size());
  expect_same_path(before, after);
}

}  // namespace
