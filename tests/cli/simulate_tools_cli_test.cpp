// End-to-end tests of `feedplan simulate PROGRAM --tools TOOLS.yaml`: a program of two tools
// (tests/data/cli/simulate_two_tools.ngc) where the second tool, narrower, runs along the first one's slot.
// The truths: each tool's run alone on the virtual machine (a program of one tool, --tool), and air — the
// second tool must find the slot already cut, which only the stock carried from the first tool gives. Bad
// flags exit 2 naming the flag and leave the log untouched. And, when ../shared/cam beside the repository
// holds it, the hand-written Haas program of five tools runs with a per-tool summary.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "run_feedplan.hpp"
#include "text_lines.hpp"

namespace {

using namespace feedplan::cli_test;
using feedplan::test_support::lines_of;

const std::string kData = std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/";
const std::string kProgram = kData + "simulate_two_tools.ngc";
const std::string kTools = kData + "simulate_tools.yaml";
const std::string kStock = " --stock " + kData + "optimize_stock.yaml ";
const std::string kMachines = std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/machines";

// Each tool's run of simulate_two_tools.ngc as a program of its own.
const std::string kFirstToolAlone =
    "G17 G21 G90\nM3 S6000\nG0 X-10 Y0 Z5\nG0 Z-3\nG1 X30 Y0 F600\nG0 Z5\nM5\nM30\n";
const std::string kSecondToolAlone =
    "G17 G21 G90\nM3 S8000\nG0 X-10 Y0 Z5\nG0 Z-3\nG1 X30 Y0 F600\nG0 Z5\nM5\nM30\n";

class SimulateToolsCliTest : public CliTest {
 protected:
  // The --json summary of `feedplan simulate <arguments>`, its force log written to `log_name` in the test's folder.
  nlohmann::json simulate_json(const std::string& arguments, const std::string& log_name) {
    const RunResult r = run_feedplan("simulate " + arguments + " --material Al7075-T6" + kStock + "--log-rate 2000 --log " +
                                     (dir_ / log_name).string() + " --json");
    EXPECT_EQ(r.exit_code, 0) << arguments << "\n" << r.output;
    if (r.exit_code != 0) return {};
    return nlohmann::json::parse(r.output.substr(r.output.find('{')));
  }

  // Runs `feedplan simulate <arguments> --log <existing log>`: exit 2, `fragment` in the message, log untouched.
  void expect_bad_input(const std::string& arguments, const std::string& fragment) {
    const fs::path log = dir_ / "existing.csv";
    std::ofstream(log) << "previous log\n";
    const RunResult r = run_feedplan("simulate " + arguments + " --log " + log.string());
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(fragment), std::string::npos) << "expected '" << fragment << "' in:\n" << r.output;
    EXPECT_EQ(read_text(log), "previous log\n") << arguments;
  }
};

TEST_F(SimulateToolsCliTest, TheSecondToolFindsTheFirstToolsSlotCut) {
  const nlohmann::json both = simulate_json(kProgram + " --tools " + kTools + " --peaks " + (dir_ / "peaks.csv").string(), "log.csv");
  ASSERT_TRUE(both.contains("tool_runs"));
  const nlohmann::json first = simulate_json(write_spec("t1.ngc", kFirstToolAlone).string() +
                                             " --tool diameter_mm=10,flutes=2,helix_deg=30", "t1.csv");
  const nlohmann::json second = simulate_json(write_spec("t2.ngc", kSecondToolAlone).string() +
                                              " --tool diameter_mm=8,flutes=2,helix_deg=30", "t2.csv");
  ASSERT_FALSE(first.is_null());
  ASSERT_FALSE(second.is_null());
  const auto& runs = both["tool_runs"];
  ASSERT_EQ(runs.size(), 2u) << both.dump(2);
  EXPECT_EQ(runs[0]["name"], "T1");
  EXPECT_EQ(runs[0]["first_line"], 7);
  EXPECT_EQ(runs[1]["name"], "T2");
  EXPECT_EQ(runs[1]["kind"], "milling");
  const double first_peak = first["max_revolution_peak_n"].get<double>();
  const double second_alone_peak = second["max_revolution_peak_n"].get<double>();
  std::printf("T1: %.1f N in the program, %.1f N alone; T2: %.1f N in the program, %.1f N alone on the full stock\n",
              runs[0]["max_revolution_peak_n"].get<double>(), first_peak, runs[1]["max_revolution_peak_n"].get<double>(),
              second_alone_peak);
  // The first tool cuts the same stock either way: the same forces and time.
  EXPECT_GT(first_peak, 50.0);
  EXPECT_NEAR(runs[0]["max_revolution_peak_n"].get<double>(), first_peak, 1e-6 * first_peak);
  EXPECT_NEAR(runs[0]["cycle_time_s"].get<double>(), first["cycle_time_s"].get<double>(), 1e-9);
  // Alone, the second tool slots full material; after the first, its slot lies inside the first one's: air.
  EXPECT_GT(second_alone_peak, 50.0);
  EXPECT_LT(runs[1]["max_revolution_peak_n"].get<double>(), 0.01 * second_alone_peak);
  // The whole program: its time is the runs' end to end, its peak the first tool's.
  EXPECT_NEAR(both["cycle_time_s"].get<double>(),
              first["cycle_time_s"].get<double>() + runs[1]["cycle_time_s"].get<double>(), 1e-9);
  EXPECT_NEAR(both["max_revolution_peak_n"].get<double>(), first_peak, 1e-6 * first_peak);
  EXPECT_NEAR(runs[1]["start_s"].get<double>(), first["cycle_time_s"].get<double>(), 1e-9);
  // The peaks CSV and the log cover the program on one clock: T2's revolutions start after T1's run.
  const std::vector<std::string> peaks = lines_of(read_text(dir_ / "peaks.csv"));
  ASSERT_GT(peaks.size(), 2u);
  EXPECT_EQ(peaks[0], "revolution,t_start_s,t_end_s,t_peak_s,peak_xy_n,mean_xy_n,tool");
  const auto t2_row = std::find_if(peaks.begin(), peaks.end(), [](const std::string& l) { return l.ends_with(",T2"); });
  ASSERT_NE(t2_row, peaks.end());
  EXPECT_GE(std::stod(t2_row->substr(t2_row->find(',') + 1)), first["cycle_time_s"].get<double>() - 1e-6);
  const std::string log = read_text(dir_ / "log.csv");
  EXPECT_NE(log.find("# tool_run_2: T2, lines 16–19, milling: EM D8 Z2"), std::string::npos) << log.substr(0, 1500);
  double last_t = -1.0;
  bool increasing = true;
  for (const std::string& line : lines_of(log)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    const double t = std::stod(line);
    increasing = increasing && t > last_t;
    last_t = t;
  }
  EXPECT_TRUE(increasing);
  EXPECT_GT(last_t, first["cycle_time_s"].get<double>());
}

TEST_F(SimulateToolsCliTest, TheTextSummaryGivesEachTool) {
  const RunResult r = run_feedplan("simulate " + kProgram + " --tools " + kTools + " --material Al7075-T6" + kStock +
                                   "--log-rate 1000 --log " + (dir_ / "log.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("per tool:\n  T1, lines 7–10: EM D10 Z2 (D10 mm, 2 flutes): "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("  T2, lines 16–19: EM D8 Z2 (D8 mm, 2 flutes): "), std::string::npos) << r.output;
}

TEST_F(SimulateToolsCliTest, BadToolFlagsNameTheFlag) {
  const std::string run = kProgram + " --material Al7075-T6" + kStock;
  expect_bad_input(run + " --tools " + kTools + " --tool diameter_mm=10,flutes=2", "--tool conflicts with --tools");
  expect_bad_input(run + " --tool diameter_mm=10,flutes=2",
                   "--tools is required: the program changes tools (T1 from line 7, T2 from line 16)");
  expect_bad_input(run + " --tools " + (dir_ / "missing.yaml").string(), "missing.yaml");
  const fs::path one = write_spec("one.yaml", "tools:\n  1: {diameter_mm: 10, flutes: 2}\n");
  expect_bad_input(run + " --tools " + one.string(), "--tools = " + one.string() + ": has no T2 (line 16); it has T1");
  expect_bad_input("--cutting-test --tools " + kTools + " --material Al7075-T6 --radial-depth-mm 1 --axial-depth-mm 5"
                   " --feed-mm-per-min 500 --spindle-rpm 3000",
                   "--tools only applies to a PROGRAM");
  // A machine file's runout has one value per flute of the tool it cuts with, as for one tool: checked for
  // every tool before anything runs.
  const fs::path three = write_spec("three.yaml", "tools:\n  1: {diameter_mm: 10, flutes: 2}\n  2: {diameter_mm: 8, flutes: 3}\n");
  expect_bad_input(kProgram + kStock + " --tools " + three.string() + " --machine " + kMachines + "/aluminium-two-flute.yaml",
                   "runout_mm has 2 values: must have one per flute, and the tool T2 has 3 (T2 of --tools " +
                       three.string() + ")");
}

// Cutter compensation offsets by the tool's diameter with --tool too (ReaderOptions::any_tool_diameter_mm): the
// compensated side cut along y = -5 runs with its centre at y = 0, one radius into the block.
TEST_F(SimulateToolsCliTest, CutterCompensationTakesTheToolsDiameter) {
  const fs::path program = write_spec("g41.ngc",
                                      "G17 G21 G90\nM3 S6000\nG0 X-20 Y-10 Z5\nG0 Z-3\nG41 D1 G1 X-5 Y-5 F600\n"
                                      "G1 X30\nG40 G1 X40 Y-20\nG0 Z5\nM5\nM30\n");
  const nlohmann::json out = simulate_json(program.string() + " --tool diameter_mm=10,flutes=2,helix_deg=30", "g41.csv");
  ASSERT_FALSE(out.is_null());
  EXPECT_GT(out["max_revolution_peak_n"].get<double>(), 50.0);
  int on_the_cut = 0;  // rows on the straight part of the cut: the centre at y = 0
  for (const std::string& line : lines_of(read_text(dir_ / "g41.csv"))) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    double t = 0.0, x = 0.0, y = 0.0, z = 0.0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf", &t, &x, &y, &z), 4) << line;
    if (z > -2.999 || x < 0.0 || x > 25.0) continue;
    ++on_the_cut;
    EXPECT_NEAR(y, 0.0, 1e-4) << line;
  }
  EXPECT_GT(on_the_cut, 100);
}

const fs::path kHaas =
    fs::path(FEEDPLAN_TEST_DATA_DIR) / ".." / ".." / ".." / "shared" / "cam" / "handwritten_nims_mill_hp_4.ngc";

// The hand-written Haas program: profile and slot under G41, spot and peck drilling, five tools.
TEST_F(SimulateToolsCliTest, TheHaasProgramRunsToolByTool) {
  if (!fs::exists(kHaas)) GTEST_SKIP() << kHaas << " is absent (../shared/cam beside the repository)";
  const fs::path stock = write_spec("block.yaml",
                                    "stock: {z_bottom_mm: -19.05, z_top_mm: 0, regions: [{outer: {polygon: "
                                    "[[0,0],[88.9,0],[88.9,63.5],[0,63.5]]}}]}\n");
  const RunResult r = run_feedplan("simulate " + kHaas.string() + " --tools " + kData + "haas_tools.yaml --material Al7075-T6 --stock " +
                                   stock.string() + " --log-rate 500 --log " + (dir_ / "haas.csv").string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto out = nlohmann::json::parse(r.output.substr(r.output.find('{')));
  std::vector<std::string> names;
  for (const auto& run : out["tool_runs"]) names.push_back(run["name"].get<std::string>() + " " + run["kind"].get<std::string>());
  for (const char* expected : {"T1 milling", "T5 drilling"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected << "\n" << out["tool_runs"].dump(2);
  }
  double sum_s = 0.0;
  for (const auto& run : out["tool_runs"]) sum_s += run["cycle_time_s"].get<double>();
  EXPECT_NEAR(out["cycle_time_s"].get<double>(), sum_s, 1e-6);
  EXPECT_GT(out["max_revolution_peak_n"].get<double>(), 0.0);
}

}  // namespace
