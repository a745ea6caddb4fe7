// `feedplan compare` from the command line. Its rows are checked against other paths of the product run by
// hand: the feed-forward row against `plan --simulate`, the constant-feed row against `simulate` of the
// program `plan --constant-feed` writes (judged here, from its per-revolution peaks CSV, by the rule the
// README states) — the machine 40 % harder than the model given as a materials file whose coefficients are
// written out here, not computed by the code under test. The Markdown table and the JSON must carry the
// same figures; bad flags exit 2 naming the flag; an output that cannot be written leaves the files there
// as they were.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hard_s50c_materials.hpp"
#include "run_feedplan.hpp"

namespace feedplan::cli_test {
namespace {

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;

constexpr double kTargetN = 350.0;  // the corner sample's

class CompareCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "models.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_model.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    hard_ = write_spec("hard.yaml", kHardS50C).string();
  }

  // The corner sample with a constant feed.
  fs::path corner_with_feed() {
    std::string text = read_text(kSamples + "/corner.yaml");
    text += "feed_mm_per_min: 1200\n";
    return write_spec("corner_feed.yaml", text);
  }

  std::string db_;
  std::string hard_;
};

nlohmann::json json_of(const std::string& text) {
  const std::size_t start = text.find('{');
  const std::size_t end = text.rfind("\n}");
  if (start == std::string::npos || end == std::string::npos) return nlohmann::json::object();
  return nlohmann::json::parse(text.substr(start, end + 2 - start));
}

const nlohmann::json& row_named(const nlohmann::json& out, const std::string& kind, int plan_cycle) {
  for (const nlohmann::json& row : out["rows"]) {
    if (row["kind"] == kind && row.value("plan_cycle", 0) == plan_cycle) return row;
  }
  static const nlohmann::json none = nlohmann::json::object();
  ADD_FAILURE() << "no row " << kind << " cycle " << plan_cycle;
  return none;
}

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// The figures of a peaks CSV (revolution,t_start_s,t_end_s,t_peak_s,peak_xy_n,mean_xy_n) by the README's
// rule: in cut at a true peak ≥ 20 % of the target, RMS of (peak − target) over those, share within ±5 %, and
// the summed length of the revolutions above the target.
struct CsvFigures {
  int in_cut = 0;
  double rms_n = 0.0;
  double within_share = 0.0;
  double above_s = 0.0;
};

CsvFigures figures_of_csv(const std::string& text, double target_n) {
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);  // header
  CsvFigures f;
  double squares = 0.0;
  int within = 0;
  while (std::getline(lines, line)) {
    std::vector<double> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(std::stod(cell));
    if (cells.size() < 6) continue;
    const double t_start = cells[1], t_end = cells[2], peak = cells[4];
    if (peak > target_n) f.above_s += t_end - t_start;
    if (peak < 0.2 * target_n) continue;
    ++f.in_cut;
    squares += (peak - target_n) * (peak - target_n);
    within += std::abs(peak - target_n) <= 0.05 * target_n ? 1 : 0;
  }
  if (f.in_cut > 0) {
    f.rms_n = std::sqrt(squares / f.in_cut);
    f.within_share = static_cast<double>(within) / f.in_cut;
  }
  return f;
}

TEST_F(CompareCliTest, RowsAgreeWithPlanSimulateAndSimulateAndTheTableWithTheJson) {
  const std::string spec = corner_with_feed().string();
  const fs::path out_dir = dir_ / "out";  // made by compare
  RunResult r = run_feedplan("compare " + spec + " --db " + db_ + " --materials " + hard_ +
                             " --machine-scale 1 --cycles 2 --json --out " + out_dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string json_text = read_text(out_dir / "compare.json");
  const nlohmann::json out = nlohmann::json::parse(json_text);
  EXPECT_EQ(json_of(r.output), out);  // --json prints the file's content
  ASSERT_EQ(out["rows"].size(), 12u);  // constant, cycles 1 and N, seven controllers, two hybrids
  EXPECT_EQ(out["learning_cycles"].get<int>(), 2);
  EXPECT_EQ(out["learning"].size(), 1u);
  EXPECT_DOUBLE_EQ(out["target_force_n"].get<double>(), kTargetN);

  // The feed-forward row is `plan --simulate` on the same machine.
  r = run_feedplan("plan " + spec + " --db " + db_ + " --materials " + hard_ + " --simulate --json -o " +
                   (dir_ / "plan.nc").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json plan = json_of(r.output);
  const nlohmann::json& first = row_named(out, "feed-forward", 1);
  EXPECT_DOUBLE_EQ(first["max_peak_n"].get<double>(), plan["virtual_machine"]["max_peak_n"].get<double>());
  EXPECT_DOUBLE_EQ(first["cycle_time_s"].get<double>(), plan["virtual_machine"]["cycle_time_s"].get<double>());
  std::printf("corner, 350 N, machine × 1.4: feed-forward cycle 1 %.1f N in %.2f s (plan --simulate: %.1f N, %.2f s)\n",
              first["max_peak_n"].get<double>(), first["cycle_time_s"].get<double>(),
              plan["virtual_machine"]["max_peak_n"].get<double>(), plan["virtual_machine"]["cycle_time_s"].get<double>());

  // The constant-feed row is `simulate` of the program `plan --constant-feed` writes, judged here.
  r = run_feedplan("plan " + spec + " --db " + db_ + " --constant-feed 1200 -o " + (dir_ / "constant.nc").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_feedplan("simulate " + (dir_ / "constant.nc").string() + " --spec " + spec + " --materials " + hard_ +
                   " --log " + (dir_ / "constant.csv").string() + " --peaks " + (dir_ / "peaks.csv").string() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json simulated = json_of(r.output);
  const CsvFigures f = figures_of_csv(read_text(dir_ / "peaks.csv"), kTargetN);
  const nlohmann::json& constant = row_named(out, "constant-feed", 0);
  EXPECT_DOUBLE_EQ(constant["max_peak_n"].get<double>(), simulated["max_revolution_peak_n"].get<double>());
  EXPECT_DOUBLE_EQ(constant["cycle_time_s"].get<double>(), simulated["cycle_time_s"].get<double>());
  EXPECT_EQ(constant["in_cut_revolutions"].get<int>(), f.in_cut);
  EXPECT_NEAR(constant["rms_error_n"].get<double>(), f.rms_n, 1e-3);  // the CSV has peaks to 0.001 N
  EXPECT_NEAR(constant["within_5_percent_share"].get<double>(), f.within_share, 1e-12);
  EXPECT_NEAR(constant["time_above_target_s"].get<double>(), f.above_s, 1e-4);

  // The Markdown table carries the JSON's figures, rounded as it says.
  const std::string markdown = read_text(out_dir / "compare.md");
  for (const nlohmann::json& row : out["rows"]) {
    const std::string name = row["name"].get<std::string>();
    const std::size_t at = markdown.find("| " + name + " |");
    ASSERT_NE(at, std::string::npos) << name << "\n" << markdown;
    const std::string line = markdown.substr(at, markdown.find('\n', at) - at);
    const double overshoot = row["max_overshoot_percent"].get<double>();
    std::string signed_overshoot = fixed(overshoot, 1);
    if (signed_overshoot == "-0.0") signed_overshoot = "0.0";
    if (signed_overshoot.front() != '-') signed_overshoot.insert(signed_overshoot.begin(), '+');
    signed_overshoot += " %";
    for (const std::string& cell :
         {fixed(row["max_peak_n"].get<double>(), 1), signed_overshoot,
          fixed(row["rms_error_n"].get<double>(), 1) + " (" + fixed(row["rms_error_percent"].get<double>(), 1) + " %)",
          fixed(100.0 * row["within_5_percent_share"].get<double>(), 0) + " %", fixed(row["cycle_time_s"].get<double>(), 2),
          fixed(row["time_above_target_s"].get<double>(), 2)}) {
      EXPECT_NE(line.find("| " + cell + " |"), std::string::npos) << cell << " in " << line;
    }
  }
  // The plot: a panel per row.
  const std::string svg = read_text(out_dir / "compare.svg");
  std::size_t panels = 0;
  for (std::size_t at = svg.find("<g id=\"panel-"); at != std::string::npos; at = svg.find("<g id=\"panel-", at + 1)) ++panels;
  EXPECT_EQ(panels, out["rows"].size());
}

TEST_F(CompareCliTest, BadFlagsExitTwoNamingTheFlag) {
  const std::string spec = corner_with_feed().string();
  const fs::path file = dir_ / "a_file";
  std::ofstream(file) << "not a directory";
  const fs::path taken = dir_ / "taken";
  fs::create_directories(taken / "compare.md");
  const std::pair<std::string, std::string> cases[] = {
      {"--cycles 1", "--cycles = 1: must be in [2, 20]"},
      {"--cycles 21", "--cycles = 21"},
      {"--cycles two", "--cycles"},
      {"--machine-scale 0", "--machine-scale = 0"},
      {"--machine-scale nan", "--machine-scale"},
      {"--machine-scale 1.2 --machine " + kSamples + "/../data/machines/steel-mild.yaml", "--machine-scale conflicts with --machine"},
      {"--target-force -5", "--target-force = -5"},
      {"--constant-feed 0", "--constant-feed = 0"},
      {"--constant-feed 20000", "--constant-feed = 20000"},
      {"--out " + file.string(), "--out = '" + file.string() + "': exists and is not a directory"},
      {"--out " + (dir_ / "missing" / "out").string(), "--out = '" + (dir_ / "missing" / "out").string() + "': directory"},
      {"--out " + taken.string(), "compare.md is a directory"},
      {"--frobnicate", "frobnicate"},
  };
  for (const auto& [flags, expected] : cases) {
    const RunResult r = run_feedplan("compare " + spec + " --db " + db_ + " " + flags);
    EXPECT_EQ(r.exit_code, 2) << flags << "\n" << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << flags << "\n" << r.output;
  }
  EXPECT_EQ(read_text(file), "not a directory");
  EXPECT_FALSE(fs::exists(dir_ / "missing"));
  EXPECT_FALSE(fs::exists(dir_ / "compare-corner_feed"));  // no default --out made for bad input
}

// An --out whose files cannot be written (a file-size limit of 64–128 kB, by the shell's block size: room for
// the database's shared-memory file, not for the SVG's 200 kB): exit 1 naming the file, and the files already
// there are left exactly as they were, no staged file left behind.
TEST_F(CompareCliTest, AnUnwritableOutLeavesTheExistingFilesAsTheyWere) {
  const std::string spec = corner_with_feed().string();
  const fs::path out_dir = dir_ / "out";
  fs::create_directories(out_dir);
  for (const char* name : {"compare.md", "compare.json", "compare.svg"}) std::ofstream(out_dir / name) << "old " << name;
  // SIGXFSZ ignored, so that a write past the limit fails with EFBIG rather than killing the process.
  const std::string command = "trap '' XFSZ; ulimit -f 128; " + std::string(FEEDPLAN_BINARY) + " compare " + spec +
                              " --db " + db_ + " --cycles 2 --out " + out_dir.string() + " 2>&1";
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status)) << output;
  EXPECT_EQ(WEXITSTATUS(status), 1) << output;
  std::string expected = "feedplan: failed: cannot write ";
  expected += (out_dir / "compare.svg").string();
  EXPECT_NE(output.find(expected), std::string::npos) << output;
  for (const char* name : {"compare.md", "compare.json", "compare.svg"}) {
    EXPECT_EQ(read_text(out_dir / name), std::string("old ") + name);
  }
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(out_dir)) ++entries;
  EXPECT_EQ(entries, 3);
}

}  // namespace
}  // namespace feedplan::cli_test
