// End-to-end tests of `feedplan plan --explain` and `--part-comments` on the trochoid and corner samples with
// the sample model of the Ø10 4-flute end mill in S50C. The truths: the plan CSV (`--csv`, the planner's own
// per-sample record, written independently of the comments) for every explained F, LinuxCNC's interpreter
// (rs274) for the program's motion, the program written without the flags for the bytes, and the spec for
// the trochoid's loops.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "../gcode/rs274_runner.hpp"
#include "plan_table.hpp"
#include "run_feedplan.hpp"
#include "text_lines.hpp"

namespace {

using namespace feedplan::cli_test;
namespace oracle = feedplan::gcode::oracle;
using feedplan::test_support::lines_of;

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;

class ExplainCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_model.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }

  std::string plan_args(const std::string& sample, const fs::path& program) const {
    return "plan " + kSamples + "/" + sample + " --db " + db_ + " -o " + program.string();
  }

  std::string db_;
};

// The CSV rows of one block: those the CSV assigns to it and the next row (the block's last sample, which the
// CSV assigns to the block after it; the block's smallest limit counts it).
struct BlockRows {
  double feed = 0.0;
  std::vector<std::size_t> rows;
};

std::vector<BlockRows> blocks_of(const CsvTable& csv) {
  std::map<int, BlockRows> by_block;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const int block = static_cast<int>(csv.number(r, "block"));
    BlockRows& b = by_block[block];
    b.feed = csv.number(r, "block_feed_mm_per_min");
    b.rows.push_back(r);
  }
  std::vector<BlockRows> blocks;
  for (auto& [index, b] : by_block) {
    if (b.rows.back() + 1 < csv.rows.size()) b.rows.push_back(b.rows.back() + 1);
    blocks.push_back(b);
  }
  return blocks;
}

// What the CSV says sets a block's F: the reasons of the rows with the smallest limit, and that limit.
struct CsvReason {
  double min_limit = INFINITY;
  std::set<std::string> reasons;
  std::vector<double> engagement_deg;  // of those rows
};

CsvReason csv_reason(const CsvTable& csv, const BlockRows& b) {
  CsvReason out;
  for (const std::size_t r : b.rows) {
    if (csv.cell(r, "limit_reason") == "rapid") continue;
    out.min_limit = std::min(out.min_limit, csv.number(r, "feed_limit_mm_per_min"));
  }
  for (const std::size_t r : b.rows) {
    if (csv.cell(r, "limit_reason") == "rapid") continue;
    if (csv.number(r, "feed_limit_mm_per_min") > out.min_limit + 1e-3) continue;
    out.reasons.insert(csv.cell(r, "limit_reason"));
    out.engagement_deg.push_back(csv.number(r, "engagement_deg"));
  }
  return out;
}

// Checks one explained F against the CSV rows of its block; returns the reason's first word(s) for counting.
// What the spec says that the numbers of a reason depend on.
struct SpecFigures {
  double target_force_n = 0.0;
  double flutes = 0.0;
  double spindle_rpm = 0.0;
  double feed_step = 0.0;  // the plan's F levels (--feed-step): F may lie one level under the limit it names
};

// The largest feed of the samples' machines (their `machine:` sections), mm/min: the top F level.
constexpr double kSamplesMaxFeed = 10000.0;

std::string check_comment(const FeedWord& word, const CsvTable& csv, const BlockRows& block, const SpecFigures& spec) {
  const double target_force_n = spec.target_force_n;
  const CsvReason expected = csv_reason(csv, block);
  const std::string& c = word.comment;
  EXPECT_NEAR(word.feed, block.feed, 0.051) << "line " << word.line;
  // The smallest limit rounded down: onto the F levels max_feed·(1 + step)^−k (the samples' machines run
  // 10000 mm/min at most), then to 1 mm/min.
  double level = expected.min_limit;
  if (spec.feed_step > 0.0 && expected.min_limit < kSamplesMaxFeed) {
    const double k =
        std::ceil(std::log(kSamplesMaxFeed / expected.min_limit) / std::log1p(spec.feed_step) - 1e-9);
    level = std::min(level, kSamplesMaxFeed * std::exp(-k * std::log1p(spec.feed_step)));
  }
  const double rounded_limit = std::floor(level + 1e-6);
  if (c == "acceleration") {
    // The ramp: F below the smallest limit inside the block by more than the rounding down.
    EXPECT_LT(block.feed, rounded_limit - 0.5) << "line " << word.line << ": " << c;
    return c;
  }
  // The limit itself: F is the smallest limit, rounded down.
  EXPECT_LE(block.feed, expected.min_limit + 1e-3) << "line " << word.line << ": " << c;
  EXPECT_GE(block.feed, rounded_limit - 1.0) << "line " << word.line << ": " << c;
  const std::string force_prefix = "force " + std::to_string(static_cast<int>(target_force_n)) + " N at ";
  if (c.rfind(force_prefix, 0) == 0) {
    EXPECT_TRUE(expected.reasons.count("force")) << "line " << word.line << ": " << c;
    const double deg = std::stod(c.substr(force_prefix.size()));
    EXPECT_TRUE(std::any_of(expected.engagement_deg.begin(), expected.engagement_deg.end(),
                            [&](double e) { return std::abs(std::round(e) - deg) <= 0.5; }))
        << "line " << word.line << ": " << c << " — the engagement of the row with the smallest limit";
    EXPECT_NE(c.find(" deg engagement"), std::string::npos) << c;
    return "force";
  }
  const std::map<std::string, std::string> words = {{"machine max feed", "max feed"}, {"machine min feed", "min feed"},
                                                    {"air", "air"}};
  if (const auto it = words.find(c); it != words.end()) {
    EXPECT_TRUE(expected.reasons.count(it->second)) << "line " << word.line << ": " << c;
    return c;
  }
  if (c.rfind("model range, chip ", 0) == 0) {
    // t_m = k · f_z at the limit (f_z = F / (Z n); on a helix only the XY part of the feed makes the chip).
    EXPECT_TRUE(expected.reasons.count("model range")) << "line " << word.line << ": " << c;
    const double chip_mm = std::stod(c.substr(18));
    bool agrees = false;
    for (const std::size_t r : block.rows) {
      const double f_z = csv.number(r, "feed_limit_mm_per_min") / (spec.flutes * spec.spindle_rpm);
      const double along_path_mm = csv.number(r, "chip_factor") * f_z;
      agrees = agrees || (chip_mm <= along_path_mm + 0.0005 && chip_mm >= 0.95 * along_path_mm - 0.0005);
    }
    EXPECT_TRUE(agrees) << "line " << word.line << ": " << c;
    return "model range";
  }
  for (const auto& [prefix, reason] : std::map<std::string, std::string>{
           {"plunge limit ", "plunge"}, {"model range, chip ", "model range"}, {"arc R ", "centripetal"}}) {
    if (c.rfind(prefix, 0) == 0) {
      EXPECT_TRUE(expected.reasons.count(reason)) << "line " << word.line << ": " << c;
      return reason;
    }
  }
  ADD_FAILURE() << "line " << word.line << ": unknown reason '" << c << "'";
  return c;
}

// Every F word of the program carries a reason, and each agrees with the CSV rows of the block whose F it
// is: the k-th F word is the F of the k-th run of blocks with one F (F is modal: the writer writes it where it
// changes, rapids between keep it).
void expect_explained_feeds_agree(const std::string& program_text, const std::string& csv_text, const SpecFigures& spec,
                                  std::map<std::string, int>& counts) {
  const CsvTable csv = read_csv(csv_text);
  const std::vector<FeedWord> words = feed_words(program_text);
  std::vector<BlockRows> changes;
  std::optional<double> modal;
  for (const BlockRows& b : blocks_of(csv)) {
    if (!(b.feed > 0.0)) continue;  // a rapid
    if (modal && std::abs(*modal - b.feed) < 0.05) continue;
    modal = b.feed;
    changes.push_back(b);
  }
  ASSERT_EQ(words.size(), changes.size()) << "one F word per change of the blocks' F";
  for (std::size_t k = 0; k < words.size(); ++k) {
    ASSERT_FALSE(words[k].comment.empty()) << "line " << words[k].line << " writes F without a reason";
    ++counts[check_comment(words[k], csv, changes[k], spec)];
  }
}

// `plan`'s default --feed-step (its --help says so).
constexpr double kDefaultFeedStep = 0.02;

TEST_F(ExplainCliTest, EveryExplainedFeedAgreesWithThePlanCsv) {
  // Both block rules: every acceleration ramp written out, and the default controller-friendly levels.
  for (const double feed_step : {0.0, kDefaultFeedStep}) {
    std::map<std::string, int> all_counts;  // a reason seen in one sample at least
    for (const char* sample : {"trochoid.yaml", "corner.yaml", "helical_boring.yaml", "spiral.yaml"}) {
      SCOPED_TRACE(std::string(sample) + (feed_step > 0.0 ? " (default blocks)" : " (--feed-step 0)"));
      const fs::path program = dir_ / "p.nc";
      const fs::path csv = dir_ / "p.csv";
      const std::string blocks = feed_step > 0.0 ? "" : " --feed-step 0";
      const RunResult r = run_feedplan(plan_args(sample, program) + blocks + " --explain --csv " + csv.string());
      ASSERT_EQ(r.exit_code, 0) << r.output;
      std::map<std::string, int> counts;
      const std::string text = read_text(kSamples + "/" + sample);  // the spec's target, flutes and speed
      const auto figure = [&](const std::string& key) {
        const std::size_t at = text.find(key);
        EXPECT_NE(at, std::string::npos) << key;
        return at == std::string::npos ? 0.0 : std::stod(text.substr(at + key.size()));
      };
      const SpecFigures spec{figure("\ntarget_force_n: "), figure("flutes: "), figure("\nspindle_rpm: "), feed_step};
      expect_explained_feeds_agree(read_text(program), read_text(csv), spec, counts);
      std::string seen;
      for (const auto& [reason, n] : counts) seen += reason + " " + std::to_string(n) + "; ";
      std::printf("%s, feed step %g: explained F words by reason: %s\n", sample, feed_step, seen.c_str());
      EXPECT_GT(counts["force"], 0) << seen;
      if (feed_step == 0.0) {
        EXPECT_GT(counts["acceleration"], 0) << seen;  // the ramps written out
      }
      all_counts.merge(counts);
    }
    for (const char* reason : {"air", "model range", "centripetal"}) EXPECT_GT(all_counts[reason], 0) << reason;
  }
}

TEST_F(ExplainCliTest, WithTheReasonsTakenOutTheProgramIsTheOneWrittenWithout) {
  for (const char* dialect : {"linuxcnc", "fanuc", "haas"}) {
    SCOPED_TRACE(dialect);
    const fs::path plain = dir_ / "plain.nc";
    const fs::path explained = dir_ / "explained.nc";
    const std::string flags = std::string(" --dialect ") + dialect;
    ASSERT_EQ(run_feedplan(plan_args("corner.yaml", plain) + flags).exit_code, 0);
    const RunResult r = run_feedplan(plan_args("corner.yaml", explained) + flags + " --explain");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string text = read_text(explained);
    EXPECT_EQ(without_feed_comments(text), read_text(plain));
    for (const std::string& line : lines_of(text)) {
      // One level of parentheses; Fanuc and Haas comments in upper case.
      int depth = 0;
      for (const char c : line) {
        depth += c == '(' ? 1 : c == ')' ? -1 : 0;
        EXPECT_TRUE(depth == 0 || depth == 1) << line;
      }
      EXPECT_EQ(depth, 0) << line;
      if (std::string(dialect) != "linuxcnc" && line.find("(F: ") != std::string::npos) {
        EXPECT_EQ(line.find_first_of("abcdefghijklmnopqrstuvwxyz"), std::string::npos) << line;
      }
    }
  }
}

// LinuxCNC reads the explained program as the same moves at the same feeds.
TEST_F(ExplainCliTest, LinuxCncRunsTheExplainedProgramAsTheOneWithout) {
  const std::optional<fs::path> rs274 = oracle::find_rs274();
  if (!rs274) GTEST_SKIP() << "rs274 (linuxcnc-uspace) is not installed: the LinuxCNC comparison is not run";
  const fs::path plain = dir_ / "plain.ngc";
  const fs::path explained = dir_ / "explained.ngc";
  ASSERT_EQ(run_feedplan(plan_args("trochoid.yaml", plain)).exit_code, 0);
  const RunResult r = run_feedplan(plan_args("trochoid.yaml", explained) + " --explain --part-comments");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const oracle::OracleRun before = oracle::run_rs274(*rs274, plain);
  const oracle::OracleRun after = oracle::run_rs274(*rs274, explained);
  ASSERT_EQ(before.exit_code, 0) << before.messages;
  ASSERT_EQ(after.exit_code, 0) << after.messages;
  EXPECT_EQ(after.feed_rates_mm_per_min, before.feed_rates_mm_per_min);
  ASSERT_EQ(after.moves.size(), before.moves.size());
  for (std::size_t i = 0; i < before.moves.size(); ++i) {
    const oracle::OracleMove& a = before.moves[i];
    const oracle::OracleMove& b = after.moves[i];
    EXPECT_EQ(a.kind, b.kind) << i;
    EXPECT_EQ(a.rotation, b.rotation) << i;
    EXPECT_EQ(a.feed_mm_per_min, b.feed_mm_per_min) << i;
    EXPECT_EQ(a.end.x_mm, b.end.x_mm) << i;
    EXPECT_EQ(a.end.y_mm, b.end.y_mm) << i;
    EXPECT_EQ(a.end.z_mm, b.end.z_mm) << i;
    EXPECT_EQ(a.center.x_mm, b.center.x_mm) << i;
    EXPECT_EQ(a.center.y_mm, b.center.y_mm) << i;
  }
  // rs274 reports each explain comment: one per F word.
  const auto explains = std::count_if(after.comments.begin(), after.comments.end(),
                                      [](const std::string& c) { return c.rfind("F: ", 0) == 0; });
  EXPECT_EQ(static_cast<std::size_t>(explains), feed_words(read_text(explained)).size());
}

// The trochoid's spec asks for loops from x 0 to 9 at 1 mm pitch: loops 1 to 10, each named once, in order.
TEST_F(ExplainCliTest, PartCommentsNameEachPartOnceInPathOrder) {
  const fs::path program = dir_ / "parts.nc";
  const RunResult r = run_feedplan(plan_args("trochoid.yaml", program) + " --part-comments");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::vector<std::string> lines = lines_of(read_text(program));
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("(part: ", 0) != 0) continue;
    parts.push_back(lines[i].substr(7, lines[i].size() - 8));
    ASSERT_LT(i + 1, lines.size());
    EXPECT_TRUE(!lines[i + 1].empty() && lines[i + 1].front() != '(')
        << "a part comment stands before a block: " << lines[i + 1];
  }
  std::vector<std::string> loops;
  for (const std::string& p : parts) {
    if (p.rfind("loop ", 0) == 0) loops.push_back(p);
  }
  std::vector<std::string> expected;
  for (int k = 1; k <= 10; ++k) expected.push_back("loop " + std::to_string(k));
  EXPECT_EQ(loops, expected);
  EXPECT_EQ(std::set<std::string>(parts.begin(), parts.end()).size(), parts.size()) << "each part once";
  // Without the flag, no part comment.
  const fs::path plain = dir_ / "plain.nc";
  ASSERT_EQ(run_feedplan(plan_args("trochoid.yaml", plain)).exit_code, 0);
  EXPECT_EQ(read_text(plain).find("(part: "), std::string::npos);
}

TEST_F(ExplainCliTest, ExplainWithATargetSweepIsBadInput) {
  const RunResult r = run_feedplan("plan " + kSamples + "/corner.yaml --db " + db_ + " --target-sweep 300:400:50 --explain");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--explain"), std::string::npos) << r.output;
}

}  // namespace
