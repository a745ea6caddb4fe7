// The streaming force-log writer (force_log_file_writer.hpp): the file holds exactly what
// format_force_log gives for the same log (the whole-log writer is the truth), it appears only at
// finish(), and a path that cannot be written is known before any row and leaves nothing behind.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/force_log_file_writer.hpp"

namespace feedplan::force_log {
namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// 30 000 rows (several buffer flushes), currents on, a NaN cell, a metadata value with a line break.
ForceLog sample_log() {
  ForceLog log;
  log.metadata = {{"source", "test"}, {"note", "two\nlines"}};
  log.has_currents = true;
  for (int i = 0; i < 30000; ++i) {
    ForceLogRow row;
    row.t_s = i * 1e-4;
    row.x_mm = std::sin(i * 0.001) * 12.5;
    row.y_mm = -0.25 * i;
    row.fx_n = 100.0 * std::cos(i * 0.37);
    row.fy_n = i % 7 == 0 ? std::numeric_limits<double>::quiet_NaN() : -3.3333333;
    row.ix_a = 0.001 * i;
    log.rows.push_back(row);
  }
  return log;
}

TEST(ForceLogFileWriter, WritesTheBytesOfTheWholeLogWriterRowByRow) {
  const ForceLog log = sample_log();
  const auto path = std::filesystem::temp_directory_path() / "feedplan_streamed_log_test.csv";
  std::filesystem::remove(path);
  ForceLogFileWriter writer(path.string());
  ASSERT_EQ(writer.error(), "");
  ForceLog header = log;
  header.rows.clear();
  writer.begin(header);
  for (const auto& row : log.rows) writer.add(row);
  EXPECT_FALSE(std::filesystem::exists(path));  // complete or not there
  ASSERT_EQ(writer.finish(), "");
  EXPECT_EQ(writer.rows(), log.rows.size());
  EXPECT_EQ(read_file(path), format_force_log(log));
  std::filesystem::remove(path);
}

TEST(ForceLogFileWriter, AMissingDirectoryIsReportedBeforeAnyRowAndNothingIsLeft) {
  const auto directory = std::filesystem::temp_directory_path() / "feedplan_no_such_directory";
  std::filesystem::remove_all(directory);
  ForceLogFileWriter writer((directory / "log.csv").string());
  EXPECT_NE(writer.error().find("does not exist"), std::string::npos) << writer.error();
  writer.begin(ForceLog{});
  writer.add(ForceLogRow{});
  EXPECT_NE(writer.finish(), "");
  EXPECT_FALSE(std::filesystem::exists(directory));
}

TEST(ForceLogFileWriter, AWriterDroppedBeforeFinishLeavesTheTargetAsItWas) {
  const auto path = std::filesystem::temp_directory_path() / "feedplan_unfinished_log_test.csv";
  { std::ofstream(path) << "old"; }
  {
    ForceLogFileWriter writer(path.string());
    writer.begin(ForceLog{});
    writer.add(ForceLogRow{});
  }
  EXPECT_EQ(read_file(path), "old");
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path())) {
    EXPECT_EQ(entry.path().filename().string().find(".feedplan_unfinished_log_test.csv.tmp"), std::string::npos);
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace feedplan::force_log
