// read_input_file: what a reader says about the file it reads whole — a missing file, a directory, and
// a device that never ends (/dev/zero: read up to the ceiling and refused by its size, never "no such file").

#include "feedplan/core/bounded_read.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace feedplan {
namespace {

const InputFileKind kReport{"a plan report, JSON", 1024, "a plan of 100 blocks is about 20 KiB"};

std::string message_for(const std::filesystem::path& path) {
  try {
    read_input_file(path, kReport);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadInputFile, AMissingFileIsNamedWithWhatWasExpected) {
  EXPECT_EQ(message_for("/nonexistent/plan.json"),
            "/nonexistent/plan.json cannot be read: no such file (expected a plan report, JSON)");
}

TEST(ReadInputFile, ADirectoryIsNotTheFile) {
  const auto dir = std::filesystem::temp_directory_path();
  EXPECT_EQ(message_for(dir), dir.string() + " cannot be read: it is a directory, not a plan report, JSON");
}

TEST(ReadInputFile, ADeviceThatNeverEndsIsRefusedByItsSize) {
  if (!std::filesystem::exists("/dev/zero")) GTEST_SKIP() << "no /dev/zero on this system";
  EXPECT_EQ(message_for("/dev/zero"),
            "/dev/zero is larger than 1 KiB: not a plan report, JSON (a plan of 100 blocks is about 20 KiB)");
}

TEST(ReadInputFile, AFileUpToTheCeilingIsReadWhole) {
  const auto path = std::filesystem::temp_directory_path() / "feedplan_bounded_read_test.txt";
  const std::string text(1024, 'x');
  std::ofstream(path, std::ios::binary) << text;
  EXPECT_EQ(read_input_file(path, kReport), text);
  std::ofstream(path, std::ios::binary | std::ios::app) << 'y';
  EXPECT_NE(message_for(path).find("is larger than 1 KiB"), std::string::npos);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace feedplan
