// Programs no CAM system writes but a file can hold: what fuzzing the reader (tests/fuzz/gcode_program)
// and a probe found. Each is refused with an InputError naming the line and the word or the limit,
// where the reader used to fail its own consistency assertion or hand the planner and the virtual
// machine a path that took gigabytes.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"

namespace feedplan::gcode {
namespace {

using ::testing::HasSubstr;

std::string problems_of(const std::string& text, const ReaderOptions& options = {}) {
  try {
    read_program(text, "test", options);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(accepted)";
}

// Found by the fuzzer: I with 60 digits made an arc whose end could not be put on its circle in
// double precision, and read_program's assertion that its path is consistent failed (abort).
TEST(ReaderHostileInput, NumbersBeyondAnyMachineAreRefused) {
  const std::string digits(60, '5');
  EXPECT_THAT(problems_of("G21 F100\nG0 X5 Y5\nG3 X0 Y0 I4" + digits + " J0\nM2\n"),
              HasSubstr("test line 3: word I4555555555555555555…: out of range: numbers are at most ±1000000"));
  EXPECT_THAT(problems_of("G21 G1 X-1000001 F100\nM2\n"), HasSubstr("line 1: word X-1000001: out of range"));
  EXPECT_EQ(problems_of("G21 G1 X-1000000 F100\nM2\n"), "(accepted)");
}

// G3 … P1000000: a million full turns, one move that the planner sampled into 6.9 GB.
TEST(ReaderHostileInput, ArcTurnsAreBoundedByTheOption) {
  EXPECT_THAT(problems_of("G21 F100\nG0 X5\nG3 X5 Y0 I-5 J0 P1000000\nM2\n"),
              HasSubstr("test line 3: word P1000000: more than 1000 turns in one arc (ReaderOptions::max_arc_turns)"));
  ReaderOptions options;
  options.max_arc_turns = 2000;
  EXPECT_EQ(problems_of("G21 F100\nG0 X5\nG3 X5 Y0 I-5 J0 P1500\nM2\n", options), "(accepted)");
}

// 10⁵ tiny moves took the planner and the virtual machine past 4 GB.
TEST(ReaderHostileInput, MovesAreBoundedByTheOption) {
  std::string program = "G21 F100\n";
  for (int i = 1; i <= 100001; ++i) program += "G1 X" + std::to_string(i % 2 == 0 ? 0.001 : 0.002) + "\n";
  program += "M2\n";
  EXPECT_THAT(problems_of(program),
              HasSubstr("test line 50002: more than 50000 moves (ReaderOptions::max_moves): "));
  ReaderOptions options;
  options.max_moves = 200000;
  EXPECT_EQ(problems_of(program, options), "(accepted)");
}

// A "line" of a megabyte is not a block: it is a file of another kind, or one without line breaks.
TEST(ReaderHostileInput, LongLinesAreRefusedByLength) {
  const std::string long_line = "G1 X1 F100 (" + std::string(5000, 'x') + ")";
  EXPECT_THAT(problems_of("G21\n" + long_line + "\nM2\n"),
              HasSubstr("test line 2: 5013 characters: more than 4096 on one line"));
}

// /dev/zero (or any endless stream) as the program: read until memory ran out.
TEST(ReaderHostileInput, FilesAreReadUpToTheirSizeLimit) {
  ReaderOptions options;
  options.max_file_bytes = 1 << 20;
  try {
    load_program("/dev/zero", options);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("/dev/zero is larger than 1 MiB: not a G-code program of a milling job (ReaderOptions::max_file_bytes)"));
  }
}

// M3 S0 reached the virtual machine as "no S given" (BlockCommand::spindle_rpm 0), which simulated the
// cut at the spec's spindle speed instead of a spindle that does not turn.
TEST(ReaderHostileInput, FeedMoveAtSZeroWithTheSpindleOnIsRefused) {
  EXPECT_THAT(problems_of("G21 F100 M3 S0\nG0 X5\nG1 X10\nG1 X20\nM2\n"),
              HasSubstr("test line 3: G1 with the spindle on at S0 (set on line 1): a feed move needs the spindle "
                        "turning; give S > 0"));
  EXPECT_EQ(problems_of("G21 F100 M3 S0\nG0 X5\nS2000\nG1 X10\nM2\n"), "(accepted)");
  EXPECT_EQ(problems_of("G21 F100 M3\nG1 X10\nM2\n"), "(accepted)");  // no S at all: the machine's own speed
}

// A plane arc of 1 km radius turning 1000 times would be 70 million chords, a peck drill with a
// micrometre Q a billion pecks: both are counted before they are made and refused like max_moves.
TEST(ReaderHostileInput, PlaneArcsAndDrillingCyclesAreBoundedByMaxMovesBeforeTheyAreMade) {
  EXPECT_THAT(problems_of("G21 F100 S1000 M3\nG0 X0 Y0 Z0\nG18 G2 X0 Z0 I1000000 K0 P1000\nM2\n"),
              HasSubstr("test line 3: more than 50000 moves (ReaderOptions::max_moves)"));
  EXPECT_THAT(problems_of("G21 F100 S1000 M3\nG0 X0 Y0 Z10\nG83 X1 Z-900000 R1 Q0.001 L10000\nM2\n"),
              HasSubstr("test line 3: more than 50000 moves (ReaderOptions::max_moves)"));
}

}  // namespace
}  // namespace feedplan::gcode
