// Force logs no data acquisition writes but a file can hold: what fuzzing the reader
// (tests/fuzz/force_log) and a probe found. Each is refused with an InputError naming the line and the
// value, where the reader used to accept nonsense into the log's header or read without bound.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "has_problem.hpp"

namespace feedplan::force_log {
namespace {

using test_support::has_problem;

const std::string kRows = "t_s,x_mm,y_mm,fx_n,fy_n\n0,0,0,1,2\n0.001,0,0,1,2\n";

std::vector<InputProblem> problems_of(const std::string& text) {
  try {
    read_force_log(text, "log.csv");
  } catch (const InputError& e) {
    return e.problems();
  }
  ADD_FAILURE() << "read_force_log accepted:\n" << text;
  return {};
}

// `# flutes: inf` was kept in the metadata as if the simulator had written it.
TEST(ForceLogHostileInput, NumbersInTheHeaderMustBeWhatTheWriterWrites) {
  EXPECT_TRUE(has_problem(problems_of("# flutes: inf\n" + kRows), "log.csv line 1 (# flutes)",
                          "= \"inf\": must be a whole number in [1, 100]"));
  EXPECT_TRUE(has_problem(problems_of("# tool: D10\n# flutes: 2.5\n" + kRows), "log.csv line 2 (# flutes)",
                          "must be a whole number in [1, 100]"));
  EXPECT_TRUE(has_problem(problems_of("# spindle_rpm: -2800\n" + kRows), "log.csv line 1 (# spindle_rpm)",
                          "= \"-2800\": must be a finite number ≥ 0"));
  EXPECT_TRUE(has_problem(problems_of("# helix_deg: 90\n" + kRows), "log.csv line 1 (# helix_deg)",
                          "= \"90\": must be a number in [0, 90)"));
  EXPECT_TRUE(has_problem(problems_of("# sample_rate_hz: 1e400\n" + kRows), "log.csv line 1 (# sample_rate_hz)",
                          "must be a finite number > 0"));
  const ForceLog log = read_force_log("# flutes: 4\n# spindle_rpm: 2800\n# note: free text 12\n" + kRows, "log.csv");
  EXPECT_EQ(log.metadata_value("flutes"), "4");
  EXPECT_EQ(log.metadata_value("note"), "free text 12");
}

// Header text goes into JSON (the import's notes, reports): bytes that are not UTF-8 broke it later.
TEST(ForceLogHostileInput, HeaderTextMustBeUtf8) {
  EXPECT_TRUE(has_problem(problems_of("# tool: Fr\xe4ser\n" + kRows), "log.csv line 1 (# tool)",
                          "= \"Fr?ser\": is not UTF-8 text (byte 3 is 0xE4)"));
  EXPECT_TRUE(has_problem(problems_of("DynoWare,Version 2.5\nFilename:,\xff.dwd\nTime,Fx,Fy\ns,N,N\n0,1,2\n"),
                          "log.csv line 2 (Filename)", "is not UTF-8 text (byte 1 is 0xFF)"));
}

// A problem quotes the input; bytes that are not UTF-8 are shown as '?' so that the message is UTF-8.
TEST(ForceLogHostileInput, ProblemsQuoteBytesThatAreNotUtf8AsQuestionMarks) {
  EXPECT_TRUE(has_problem(problems_of("t_s,x_mm,y_mm,fx_n,f\xe4_n\n0,0,0,1,2\n"), "log.csv line 1, column 5",
                          "= \"f?_n\": unknown column"));
  EXPECT_TRUE(has_problem(problems_of("t_s,x_mm,y_mm,fx_n,fy_n\n0,0,0,1,\xff\n"), "log.csv line 2, column 5 (fy_n)",
                          "= \"?\": not a number"));
}

// /dev/zero as the log: read until memory ran out.
TEST(ForceLogHostileInput, FilesAreReadUpToTheSizeLimit) {
  try {
    load_force_log("/dev/zero", 1 << 20);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "/dev/zero is larger than 1 MiB: not a force log (split the recording into parts of at most that size)");
  }
}

}  // namespace
}  // namespace feedplan::force_log
