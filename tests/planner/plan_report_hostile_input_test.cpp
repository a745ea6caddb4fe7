// Plan reports no planner wrote: what fuzzing the reader (tests/fuzz/plan_report) and hand-made
// reports found. Each input is refused with an InputError naming the source and what is wrong, where
// the reader used to crash or throw an exception the CLI does not expect.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/planner/plan_report.hpp"

namespace feedplan::planner {
namespace {

using ::testing::HasSubstr;

// The first problem of parsing `text`, or a failure when the reader accepts it.
InputProblem first_problem(const std::string& text) {
  try {
    parse_plan_report(text, "plan.json");
  } catch (const InputError& error) {
    if (!error.problems().empty()) return error.problems().front();
  }
  ADD_FAILURE() << "no InputError for " << text.substr(0, 80);
  return {};
}

// 100 000 nested arrays: the problem showed the value, and nlohmann's dump() recursed once per level
// until the stack overflowed (SIGSEGV in `feedplan learn`).
TEST(PlanReportHostileInput, DeeplyNestedArraysAreRefusedByTheirDepth) {
  const std::string nested = std::string(100000, '[') + std::string(100000, ']');
  const InputProblem problem = first_problem(nested);
  EXPECT_EQ(problem.field, "plan.json");
  EXPECT_THAT(problem.message, HasSubstr("line 1: nests arrays and objects deeper than 64 levels"));

  const std::string in_a_member = "{\"format\": \"feedplan-plan\",\n \"tool\": " + nested + "}";
  EXPECT_THAT(first_problem(in_a_member).message, HasSubstr("line 2: nests arrays and objects deeper than 64"));
}

// Brackets inside strings are text, not nesting: a deep-looking string is an ordinary bad value.
TEST(PlanReportHostileInput, BracketsInStringsDoNotCountAsNesting) {
  const std::string text = "{\"format\": \"" + std::string(1000, '[') + "\\\"\"}";
  const InputProblem problem = first_problem(text);
  EXPECT_EQ(problem.field, "format");
  EXPECT_THAT(problem.message, HasSubstr("must be 'feedplan-plan'"));
}

// A number beyond a double's range: nlohmann throws out_of_range (not a parse_error), which escaped
// the reader as an unexpected exception.
TEST(PlanReportHostileInput, NumberBeyondADoubleIsNotValidJson) {
  const InputProblem problem = first_problem("{\"format\": \"feedplan-plan\", \"format_version\": 1e400}");
  EXPECT_EQ(problem.field, "plan.json");
  EXPECT_THAT(problem.message, HasSubstr("is not valid JSON"));
  EXPECT_THAT(problem.message, HasSubstr("1e400"));
}

// A report file of 257 MiB (a sparse file of zeros here) is refused by its size before it is read whole.
TEST(PlanReportHostileInput, FilesAreReadUpToTheSizeLimit) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("feedplan_huge_report_" + std::to_string(::getpid()) + ".json");
  { std::ofstream create(path); }
  std::filesystem::resize_file(path, std::uintmax_t{257} << 20);
  try {
    read_plan_report(path);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.problems().at(0).field, path.string());
    EXPECT_THAT(error.problems().at(0).message, HasSubstr("is larger than 256 MiB: not a plan report"));
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace feedplan::planner
