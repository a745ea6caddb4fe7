// End-to-end tests of the feedplan command: exit codes (0 done, 1 failed, 2 bad input), messages that
// name the field or flag, and outputs left untouched on bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;

TEST_F(CliTest, VersionAndHelp) {
  const RunResult version = run_feedplan("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.output.find("feedplan 0."), std::string::npos) << version.output;
  const RunResult help = run_feedplan("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("cycle"), std::string::npos);
}

TEST_F(CliTest, CycleWritesEngagementCsvWithOneRowPerSample) {
  const fs::path csv = dir_ / "trochoid.csv";
  const RunResult json = run_feedplan("cycle " + kSamples + "/trochoid.yaml --json --engagement " + csv.string());
  ASSERT_EQ(json.exit_code, 0) << json.output;
  const std::string text = read_text(csv);
  const std::string header = text.substr(0, text.find('\n'));
  for (const char* column : {"s_mm", "x_mm", "y_mm", "z_mm", "cutting", "engagement_deg", "entry_deg", "exit_deg",
                             "chip_factor", "contact_length_mm"}) {
    EXPECT_NE(header.find(column), std::string::npos) << column;
  }
  const auto rows = std::count(text.begin(), text.end(), '\n') - 1;
  const auto at = json.output.find("\"samples\": ");
  ASSERT_NE(at, std::string::npos) << json.output;
  EXPECT_EQ(rows, std::stol(json.output.substr(at + 11)));
}

TEST_F(CliTest, EverySampleRunsAndPrintsASummary) {
  for (const char* name : {"corner", "trochoid", "spiral", "helical_boring", "pocket"}) {
    const RunResult r = run_feedplan("cycle " + kSamples + "/" + name + ".yaml");
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.output;
    EXPECT_NE(r.output.find("engagement:"), std::string::npos) << name;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << name << ": " << r.output;
  }
}

TEST_F(CliTest, MissingSpecIsBadInput) {
  const RunResult r = run_feedplan("cycle " + (dir_ / "nope.yaml").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("nope.yaml"), std::string::npos) << r.output;
}

TEST_F(CliTest, BadSpecLeavesExistingOutputUntouched) {
  const fs::path csv = dir_ / "keep.csv";
  std::ofstream(csv) << "precious";
  const fs::path spec = write_spec("bad.yaml",
                                   "cycle: trochoid\n"
                                   "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30}\n"
                                   "axial_depth_mm: 10\n"
                                   "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 12}\n");
  const RunResult r = run_feedplan("cycle " + spec.string() + " --engagement " + csv.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("trochoid.pitch_mm"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("12"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(csv), "precious");
}

TEST_F(CliTest, BadDsIsBadInputNamingTheFlag) {
  for (const char* ds : {"0", "-1", "100"}) {
    const RunResult r = run_feedplan("cycle " + kSamples + "/trochoid.yaml --ds " + std::string(ds));
    EXPECT_EQ(r.exit_code, 2) << ds << ": " << r.output;
    EXPECT_NE(r.output.find("--ds"), std::string::npos) << r.output;
  }
  const RunResult nan = run_feedplan("cycle " + kSamples + "/trochoid.yaml --ds abc");
  EXPECT_EQ(nan.exit_code, 2) << nan.output;
}

TEST_F(CliTest, UnknownFlagOrNoCommandIsBadInput) {
  EXPECT_EQ(run_feedplan("cycle " + kSamples + "/trochoid.yaml --frobnicate").exit_code, 2);
  EXPECT_EQ(run_feedplan("").exit_code, 2);
  EXPECT_EQ(run_feedplan("plan-everything").exit_code, 2);
}

// Checked with the flags, before the engagement is computed (as plan does); a write that fails is exit 1
// (tests/cli/paths_cli_test.cpp).
TEST_F(CliTest, AnOutputInAMissingDirectoryIsBadInput) {
  const RunResult r = run_feedplan("cycle " + kSamples + "/trochoid.yaml --engagement " + (dir_ / "no_such_dir" / "x.csv").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--engagement"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no_such_dir' does not exist"), std::string::npos) << r.output;
}

}  // namespace
