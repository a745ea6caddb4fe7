// Moves to machine positions (G28, G30, G53) read as retracts above the part: the reader has no machine
// coordinates, so each parks the tool — a rapid straight up from where it is to the park height (the
// highest Z reached before it plus 25 mm, or ReaderOptions::park_z_mm), X and Y kept; G28/G30 go to their
// intermediate point first, as LinuxCNC does. The expected positions are worked out by hand from that rule.
// And Haas' no-path M codes (M31, M33) are accepted without effect.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"

namespace feedplan::gcode {
namespace {

using geometry::MoveKind;
using ::testing::HasSubstr;

std::string problems_of(const std::string& text) {
  try {
    read_program(text, "test");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(MachinePositions, G28ParksStraightUpAboveTheHighestZPlus25) {
  std::vector<WrittenMove> written;
  const geometry::Program p = read_program(
      "G21 G90\nS1000 M3\nG0 X10 Y5 Z8\nG1 Z-2 F100\nG1 X20\nG28\nG0 X0 Y0\nG0 Z3\nM2\n", "test", {}, written);
  ASSERT_EQ(p.path.moves.size(), 6U);
  const geometry::Move& park = p.path.moves[3];
  EXPECT_EQ(park.kind, MoveKind::kRapid);
  EXPECT_DOUBLE_EQ(park.start.x_mm, 20.0);
  EXPECT_DOUBLE_EQ(park.end.x_mm, 20.0);
  EXPECT_DOUBLE_EQ(park.end.y_mm, 5.0);
  EXPECT_DOUBLE_EQ(park.end.z_mm, 33.0);  // the highest Z, 8, plus 25
  EXPECT_EQ(p.blocks[3].source_line, 6);
  EXPECT_TRUE(written[3].keep_whole);
  // The next rapid leaves the park height across, then down.
  EXPECT_DOUBLE_EQ(p.path.moves[4].end.z_mm, 33.0);
  EXPECT_DOUBLE_EQ(p.path.moves[5].end.z_mm, 3.0);
  bool noted = false;
  for (const std::string& n : p.notes) noted = noted || n.find("1 move to machine positions (G28, G30, G53) were read as retracts") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(MachinePositions, G30GoesToItsIntermediatePointFirstAndG53KeepsXY) {
  ReaderOptions options;
  options.park_z_mm = 100.0;
  const geometry::Program p = read_program(
      "G21 G90\nS1000 M3\nG0 X10 Y5 Z1\nG91 G30 Z4\nG90\nG0 X1 Y2\nG53 G0 Z0\nG53 X0 Y0\nG0 X7 Y7 Z1\nM2\n", "test", options);
  ASSERT_EQ(p.path.moves.size(), 5U);
  EXPECT_DOUBLE_EQ(p.path.moves[1].end.z_mm, 5.0) << "G91 G30 Z4: up 4 mm first";
  EXPECT_DOUBLE_EQ(p.path.moves[2].end.z_mm, 100.0);
  EXPECT_DOUBLE_EQ(p.path.moves[3].end.x_mm, 1.0);
  EXPECT_DOUBLE_EQ(p.path.moves[3].end.z_mm, 100.0);
  // G53 at the park height already: no move; G53 X0 Y0 keeps X and Y.
  EXPECT_DOUBLE_EQ(p.path.moves[4].start.x_mm, 1.0);
  EXPECT_DOUBLE_EQ(p.path.moves[4].end.x_mm, 7.0);
  EXPECT_DOUBLE_EQ(p.path.moves[4].start.z_mm, 100.0);
}

// The safe return the writer ends its programs with (LinuxCNC G53, Fanuc and Haas G91 G28 Z0. then G90):
// the same park, a rapid after the cut; with no move after it, no note (nothing leaves the guessed place).
TEST(MachinePositions, AParkAtTheEndIsARapidUpWithoutANote) {
  const std::string cut = "G21 G90\nS1000 M3\nG0 X10 Y5 Z8\nG1 Z-2 F100\nG1 X20\nG0 Z4\n";
  for (const std::string& end : {std::string("G53 G0 Z0.\nM5\nM2\n"), std::string("G91 G28 Z0.\nG90\nM05\nM30\n")}) {
    SCOPED_TRACE(end);
    const geometry::Program p = read_program(cut + end, "test");
    ASSERT_EQ(p.path.moves.size(), 5U);
    const geometry::Move& park = p.path.moves.back();
    EXPECT_EQ(park.kind, MoveKind::kRapid);
    EXPECT_FALSE(park.cutting);
    EXPECT_DOUBLE_EQ(park.start.z_mm, 4.0);
    EXPECT_DOUBLE_EQ(park.end.x_mm, 20.0);
    EXPECT_DOUBLE_EQ(park.end.y_mm, 5.0);
    EXPECT_DOUBLE_EQ(park.end.z_mm, 33.0);  // the highest Z, 8, plus 25
    for (const std::string& n : p.notes) EXPECT_EQ(n.find("machine position"), std::string::npos) << n;
  }
  // A park a move leaves from is noted, counting every park of the program.
  const geometry::Program p = read_program(cut + "G28\nG0 X0 Y0\nG53 G0 Z0\nM2\n", "test");
  bool noted = false;
  for (const std::string& n : p.notes) noted = noted || n.find("2 moves to machine positions (G28, G30, G53)") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST(MachinePositions, WhatTheReaderCannotFollowIsRefused) {
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 X1 Z1\nG28\nG1 X5 Z-1 F100\nM2\n"),
              HasSubstr("test line 5: G1 right after a move to a machine position (line 4)"));
  ReaderOptions options;
  options.tool_diameters_mm = {{1, 6.0}};
  try {
    read_program("G21 G90\nT1 M6\nS1000 M3\nG0 X-10 Y0 Z1\nG41 G1 X0 F100\nG53 G0 Z0\nG40 X-10\nM2\n", "test", options);
    ADD_FAILURE() << "G53 under compensation read";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("test line 6: word G53: a move to a machine position under cutter compensation"));
  }
  EXPECT_THAT(problems_of("G21 G90\nG28 G0 X1\nM2\n"), HasSubstr("test line 2: word G28: G0 in the same block"));
}

TEST(HaasMCodes, ChipConveyorCodesAreAcceptedWithoutEffect) {
  const geometry::Program p = read_program("G21 G90\nM31\nS1000 M3\nG0 X1\nG1 X2 F100\nM33\nM30\n", "test");
  EXPECT_EQ(p.path.moves.size(), 2U);
}

}  // namespace
}  // namespace feedplan::gcode
