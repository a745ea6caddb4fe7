// End-to-end tests of `feedplan optimize --report --csv --plot --explain` on the FreeCAD-style slot
// (tests/data/cli/optimize_slot.ngc) and the program of two tools (optimize_two_tools.ngc), with the sample
// model of the Ø10 4-flute end mill in S50C. The truths: the summary optimize prints (its cycle time and
// peaks, computed apart from the files), the program re-fed without --explain, LinuxCNC's interpreter
// (rs274) for the motion, and the files as they were before a run that fails.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "../gcode/rs274_runner.hpp"
#include "plan_table.hpp"
#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;
namespace oracle = feedplan::gcode::oracle;

const std::string kData = std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/";
const std::string kTool = " --tool diameter_mm=10,flutes=4,helix_deg=30 ";

class OptimizeOutputsCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + kData + "s50c_d10_model.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }

  std::string slot_args(const fs::path& output) const {
    return "optimize " + kData + "optimize_slot.ngc -o " + output.string() + kTool + "--material S50C --stock " + kData +
           "optimize_stock.yaml --target-force 550 --db " + db_;
  }

  std::string two_tool_args(const fs::path& output) const {
    return "optimize " + kData + "optimize_two_tools.ngc -o " + output.string() + " --tools " + kData +
           "optimize_tools.yaml --material S50C --stock " + kData + "optimize_stock.yaml --target-force 550 --db " + db_;
  }

  std::string db_;
};

// Every number the summary prints after `label` ("planned cycle time 12.34 s" → 12.34), in order.
std::vector<double> printed_numbers(const std::string& output, const std::string& label) {
  std::vector<double> numbers;
  for (std::size_t at = output.find(label); at != std::string::npos; at = output.find(label, at + 1)) {
    numbers.push_back(std::stod(output.substr(at + label.size())));
  }
  return numbers;
}

double largest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

// The report's operations add up to the cycle times the summary prints; the CSV's largest predicted force is
// the summary's largest predicted peak (of the planned runs: "planned: …, predicted peak X N").
void expect_files_agree_with_the_summary(const RunResult& r, const fs::path& report, const fs::path& csv,
                                         std::size_t runs) {
  const std::vector<double> cycle = printed_numbers(r.output, "planned cycle time ");
  ASSERT_EQ(cycle.size(), 1u) << r.output;
  const std::vector<double> peaks = printed_numbers(r.output, " s), predicted peak ");
  ASSERT_EQ(peaks.size(), runs) << r.output;
  const std::vector<double> input_cycles = printed_numbers(r.output, "input: cycle time ");
  ASSERT_EQ(input_cycles.size(), runs) << r.output;

  const nlohmann::json json = nlohmann::json::parse(read_text(report));
  EXPECT_EQ(json["format"], "feedplan-optimize");
  EXPECT_EQ(json["runs"].size(), runs);
  double refed_s = 0.0, input_s = 0.0;
  for (const auto& op : json["operations"]) {
    refed_s += op["refed_time_s"].get<double>();
    input_s += op["input_time_s"].get<double>();
  }
  EXPECT_NEAR(refed_s, cycle.front(), 0.0051) << "the operations' re-fed times add up to the printed cycle time";
  double input_total = 0.0;
  for (const double s : input_cycles) input_total += s;
  EXPECT_NEAR(input_s, input_total, 0.0051 * static_cast<double>(runs));
  EXPECT_NEAR(json["summary"]["cycle_time_s"].get<double>(), cycle.front(), 0.0051);

  const CsvTable table = read_csv(read_text(csv));
  ASSERT_FALSE(table.rows.empty());
  double csv_peak = 0.0;
  for (std::size_t i = 0; i < table.rows.size(); ++i) csv_peak = std::max(csv_peak, table.number(i, "predicted_force_n"));
  EXPECT_NEAR(csv_peak, largest(peaks), 0.051) << "the CSV's largest predicted force is the summary's";
}

TEST_F(OptimizeOutputsCliTest, ReportCsvAndPlotAgreeWithTheSummary) {
  const fs::path output = dir_ / "refed.ngc";
  const fs::path report = dir_ / "r.json", csv = dir_ / "r.csv", plot = dir_ / "r.svg";
  const RunResult r = run_feedplan(slot_args(output) + " --report " + report.string() + " --csv " + csv.string() +
                                   " --plot " + plot.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_files_agree_with_the_summary(r, report, csv, 1);
  EXPECT_NE(read_text(plot).find("<svg"), std::string::npos);
  EXPECT_NE(read_text(plot).find("id=\"panel-force\""), std::string::npos);
  const nlohmann::json json = nlohmann::json::parse(read_text(report));
  EXPECT_EQ(json["material"], "S50C");
  EXPECT_EQ(json["target_force_n"].get<double>(), 550.0);
  EXPECT_EQ(json["runs"][0]["plan"]["format"], "feedplan-plan");
  EXPECT_EQ(json["runs"][0]["plan"]["tool"]["diameter_mm"].get<double>(), 10.0);
  // The CSV's line column names the input's lines of feed moves: the slot's G1 lines.
  const CsvTable table = read_csv(read_text(csv));
  std::set<int> lines;
  for (std::size_t i = 0; i < table.rows.size(); ++i) lines.insert(static_cast<int>(table.number(i, "line")));
  std::vector<std::string> text;
  {
    std::ifstream in(kData + "optimize_slot.ngc");
    for (std::string line; std::getline(in, line);) text.push_back(line);
  }
  for (const int line : lines) {
    ASSERT_GE(line, 1);
    ASSERT_LE(static_cast<std::size_t>(line), text.size());
    const std::string& t = text[static_cast<std::size_t>(line) - 1];
    EXPECT_TRUE(t.rfind("G0", 0) == 0 || t.rfind("G1", 0) == 0 || t.rfind("G2", 0) == 0 || t.rfind("G3", 0) == 0)
        << "line " << line << ": " << t;
  }
}

TEST_F(OptimizeOutputsCliTest, TwoToolsGiveOneCsvWithAToolColumnAndOneRunEachInTheReport) {
  const fs::path output = dir_ / "two.ngc";
  const fs::path report = dir_ / "r.json", csv = dir_ / "r.csv", plot = dir_ / "r.svg";
  const RunResult r = run_feedplan(two_tool_args(output) + " --report " + report.string() + " --csv " + csv.string() +
                                   " --plot " + plot.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_files_agree_with_the_summary(r, report, csv, 2);
  const nlohmann::json json = nlohmann::json::parse(read_text(report));
  EXPECT_EQ(json["runs"][0]["tool_number"].get<int>(), 1);
  EXPECT_EQ(json["runs"][1]["tool_number"].get<int>(), 2);
  const CsvTable table = read_csv(read_text(csv));
  std::vector<std::string> tools;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const std::string tool = table.cell(i, "tool");
    if (tools.empty() || tools.back() != tool) tools.push_back(tool);
  }
  EXPECT_EQ(tools, (std::vector<std::string>{"1", "2"})) << "the runs one after the other, in program order";
}

// An output that cannot be written: nothing is put in place, the existing program stays as it was.
TEST_F(OptimizeOutputsCliTest, AFailingOutputLeavesTheExistingProgramAsItWas) {
  const fs::path output = dir_ / "keep.ngc";
  const fs::path report = dir_ / "new.json";
  std::ofstream(output) << "(keep me)\n";
  if (fs::is_character_file("/dev/full")) {
    const RunResult full = run_feedplan(slot_args(output) + " --report " + report.string() + " --csv /dev/full");
    EXPECT_EQ(full.exit_code, 1) << full.output;
    EXPECT_NE(full.output.find("/dev/full"), std::string::npos) << full.output;
    EXPECT_EQ(read_text(output), "(keep me)\n");
    EXPECT_FALSE(fs::exists(report)) << "nothing is put in place when one output fails";
  }
  for (const char* flag : {"--csv", "--report", "--plot"}) {
    const RunResult bad = run_feedplan(slot_args(output) + " " + flag + " " + (dir_ / "no/such/dir/x").string());
    EXPECT_EQ(bad.exit_code, 2) << bad.output;
    EXPECT_NE(bad.output.find(std::string(flag) + " = '"), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find("does not exist"), std::string::npos) << bad.output;
    EXPECT_EQ(read_text(output), "(keep me)\n");
  }
  const RunResult same = run_feedplan(slot_args(output) + " --csv " + output.string());
  EXPECT_EQ(same.exit_code, 2) << same.output;
  EXPECT_NE(same.output.find("--csv"), std::string::npos) << same.output;
  EXPECT_EQ(read_text(output), "(keep me)\n");
}

// --explain changes nothing but comments: the program re-fed without it, and LinuxCNC's moves and feeds.
TEST_F(OptimizeOutputsCliTest, ExplainedReFeedIsTheSameProgramWithReasons) {
  for (const bool two_tools : {false, true}) {
    SCOPED_TRACE(two_tools ? "two tools" : "slot");
    const fs::path plain = dir_ / "plain.ngc";
    const fs::path explained = dir_ / "explained.ngc";
    const auto args = [&](const fs::path& out) { return two_tools ? two_tool_args(out) : slot_args(out); };
    ASSERT_EQ(run_feedplan(args(plain)).exit_code, 0);
    const RunResult r = run_feedplan(args(explained) + " --explain");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string text = read_text(explained);
    EXPECT_EQ(without_feed_comments(text), read_text(plain));
    const std::regex reason(
        "force 550 N at [0-9]+ deg engagement|plunge limit [0-9.]+ mm/tooth|model range, chip [0-9.]+ mm|"
        "machine max feed|machine min feed|air|acceleration|arc R [0-9.]+ mm, acceleration");
    const std::vector<FeedWord> words = feed_words(text);
    int explained_words = 0;
    for (const FeedWord& w : words) {
      if (std::isnan(w.feed)) continue;
      // Every F the re-feed wrote carries a reason; F words kept from the input (a drilling cycle's) have none.
      if (w.comment.empty()) continue;
      ++explained_words;
      EXPECT_TRUE(std::regex_match(w.comment, reason)) << "line " << w.line << ": " << w.comment;
    }
    EXPECT_GT(explained_words, 3);
    // The line that already had a comment keeps it last (LinuxCNC acts on the last comment of a line).
    if (!two_tools) {
      EXPECT_NE(text.find(") (G1 as a rapid, above the stock)"), std::string::npos) << text;
    }
    const std::optional<fs::path> rs274 = oracle::find_rs274();
    if (!rs274) GTEST_SKIP() << "rs274 (linuxcnc-uspace) is not installed: the LinuxCNC comparison is not run";
    const oracle::OracleRun before = oracle::run_rs274(*rs274, plain);
    const oracle::OracleRun after = oracle::run_rs274(*rs274, explained);
    ASSERT_EQ(before.exit_code, 0) << before.messages;
    ASSERT_EQ(after.exit_code, 0) << after.messages;
    EXPECT_EQ(after.feed_rates_mm_per_min, before.feed_rates_mm_per_min);
    ASSERT_EQ(after.moves.size(), before.moves.size());
    for (std::size_t i = 0; i < before.moves.size(); ++i) {
      EXPECT_EQ(after.moves[i].kind, before.moves[i].kind) << i;
      EXPECT_EQ(after.moves[i].feed_mm_per_min, before.moves[i].feed_mm_per_min) << i;
      EXPECT_EQ(after.moves[i].end.x_mm, before.moves[i].end.x_mm) << i;
      EXPECT_EQ(after.moves[i].end.y_mm, before.moves[i].end.y_mm) << i;
      EXPECT_EQ(after.moves[i].end.z_mm, before.moves[i].end.z_mm) << i;
    }
    // The input's own comments are still reported by LinuxCNC.
    for (const std::string& c : before.comments) {
      EXPECT_NE(std::find(after.comments.begin(), after.comments.end(), c), after.comments.end()) << c;
    }
  }
}

}  // namespace
