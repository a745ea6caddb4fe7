// Drilling canned cycles (G73, G81, G82, G83, G85, G86, G89 with G98/G99, R, Z, P, Q, L) against
// LinuxCNC's interpreter: the reader expands each hole into the moves rs274 makes — rapids, feeds,
// dwells, the spindle stop of G86 — which must agree move by move (ends to 1 µm, plus half a printed digit
// in inches; feed, dwell and spindle equal); every such move is kept whole with its feed fixed.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "rs274_runner.hpp"

namespace feedplan::gcode {
namespace {

using geometry::MoveKind;
using ::testing::HasSubstr;

constexpr double kToleranceMm = 1e-3;
constexpr double kInchPrintMm = 0.5 * 0.0001 * 25.4 * 1.7320508;

double distance_mm(const geometry::Point3& a, const geometry::Point3& b) {
  return std::hypot(std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm), b.z_mm - a.z_mm);
}

class DrillCycleOracle : public oracle::Rs274Test {
 protected:
  geometry::Program expect_as_linuxcnc(const std::string& text) {
    std::vector<WrittenMove> written;
    geometry::Program ours;
    try {
      ours = read_program(text, "test", {}, written);
    } catch (const InputError& error) {
      ADD_FAILURE() << error.what();
      return ours;
    }
    EXPECT_TRUE(geometry::consistency_defects(ours.path).empty());
    const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, text);
    EXPECT_EQ(run.exit_code, 0) << run.messages;
    const double tol = kToleranceMm + (text.find("G20") != std::string::npos ? kInchPrintMm : 0.0);
    EXPECT_EQ(ours.path.moves.size(), run.moves.size());
    for (std::size_t i = 0; i < std::min(ours.path.moves.size(), run.moves.size()); ++i) {
      SCOPED_TRACE("move " + std::to_string(i) + " (line " + std::to_string(ours.blocks[i].source_line) + ")");
      const geometry::Move& m = ours.path.moves[i];
      const oracle::OracleMove& o = run.moves[i];
      EXPECT_EQ(m.kind, o.kind);
      EXPECT_LE(distance_mm(m.end, o.end), tol) << m.end.x_mm << " " << m.end.y_mm << " " << m.end.z_mm << " vs "
                                                << o.end.x_mm << " " << o.end.y_mm << " " << o.end.z_mm;
      EXPECT_NEAR(ours.blocks[i].feed_mm_per_min, o.feed_mm_per_min, 0.01);
      EXPECT_NEAR(ours.blocks[i].dwell_before_s, o.dwell_before_s, 1e-9);
      EXPECT_EQ(ours.blocks[i].spindle, o.spindle);
    }
    EXPECT_NEAR(ours.dwell_at_end_s, run.dwell_at_end_s, 1e-9);
    written_ = written;
    return ours;
  }
  std::vector<WrittenMove> written_;
};

TEST_F(DrillCycleOracle, EveryCycleWithG98AndG99AndModalHolesInMillimetres) {
  const geometry::Program program = expect_as_linuxcnc(
      "G21 G17 G90\n"
      "S1000 M3\n"
      "G0 X0 Y0 Z20\n"
      "G98 G83 X5 Y5 Z-10 R2 Q4 F100 (pecks retract to R)\n"
      "G99 X10\n"
      "G80\n"
      "G0 Z20\n"
      "G98 G85 X20 Y0 Z-5 R3 F50\n"
      "G99 X25\n"
      "G98 G89 X30 Z-5 R3 P1.5\n"
      "G86 X35 Z-5 R3 P0.5\n"
      "G73 X40 Q2 Z-5 R3\n"
      "G99 G82 X45 P2 Z-4 R1\n"
      "X50 Y10 (another hole)\n"
      "G81 X55 Z-3 R1\n"
      "G0 X60 (G0 cancels the cycle)\n"
      "M2\n");
  ASSERT_FALSE(program.path.moves.empty());
  int fixed = 0;
  for (std::size_t i = 0; i < written_.size(); ++i) {
    if (program.blocks[i].source_line >= 4 && program.blocks[i].source_line <= 15 && program.blocks[i].source_line != 7) {
      EXPECT_TRUE(written_[i].fixed_feed && written_[i].keep_whole) << "move " << i;
      ++fixed;
    }
  }
  EXPECT_GT(fixed, 40);
}

TEST_F(DrillCycleOracle, HaasSpotAndPeckDrillingInInches) {
  expect_as_linuxcnc(
      "G17 G20 G40 G49 G80\n"
      "G00 G90 G54 X0.8 Y1.63\n"
      "S3820 M03\n"
      "G00 Z0.1\n"
      "G82 G99 Z-0.05 P0.5 R0.25 F11.46\n"
      "X2.71 Y0.76\n"
      "G80\n"
      "G00 Z0.1\n"
      "G00 X0.8 Y1.63\n"
      "G83 G99 Z-0.4922 R0.25 Q0.15 F7.64\n"
      "G80\n"
      "G00 Z1.0\n"
      "M30\n");
}

TEST_F(DrillCycleOracle, IncrementalRowsWithRepeatsAndAStartBelowR) {
  expect_as_linuxcnc(
      "G21 G17 G90\n"
      "S2000 M3\n"
      "G0 X0 Y0 Z1\n"
      "G98 G81 X10 Y0 Z-3 R5 F80 (below R: straight up first)\n"
      "G91 G81 X5 Y2 Z-4 R-10 L3\n"
      "G99 G83 X-5 Z-6 R-2 Q2.5 L2\n"
      "G90 G80 G0 Z10\n"
      "M2\n");
}

std::string problems_of(const std::string& text) {
  try {
    read_program(text, "test");
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(DrillCycleProblems, MissingWordsAndImpossibleCyclesAreRefusedByLineAndWord) {
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 Z5\nG81 X1 Z-2 F100\nM2\n"),
              HasSubstr("test line 4: word G81: the cycle starts here and needs R, its R plane"));
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 Z5\nG83 X1 Z-2 R1 F100\nM2\n"),
              HasSubstr("test line 4: word G83: the cycle starts here and needs Q, its peck depth"));
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 Z5\nG82 X1 Z-2 R1 F100\nM2\n"),
              HasSubstr("test line 4: word G82: the cycle starts here and needs P"));
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 Z5\nG81 X1 Z2 R1 F100\nM2\n"),
              HasSubstr("test line 4: G81: the R plane is below the bottom Z of the cycle"));
  EXPECT_THAT(problems_of("G21 G90\nG0 Z5\nG86 X1 Z-2 R1 P1 F100\nM2\n"),
              HasSubstr("test line 3: word G86: G86 needs the spindle turning"));
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 Z5\nG18 G81 X1 Z-2 R1 F100\nM2\n"),
              HasSubstr("test line 4: word G81: drilling cycles are read in the XY plane (G17) only"));
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 Z5\nG83 X1 Z-2 R1 Q0 F100\nM2\n"),
              HasSubstr("test line 4: word Q0: the peck depth Q must be > 0"));
  EXPECT_THAT(problems_of("G21 G90\nS1000 M3\nG0 Z5\nG84 X1 Z-2 R1 F100\nM2\n"),
              HasSubstr("test line 4: word G84: not supported (tapping"));
}

TEST(DrillCycleNotes, APOnACycleThatDoesNotDwellIsIgnoredWithANote) {
  const geometry::Program program = read_program("G20 G90\nS1000 M3\nG0 X0.8 Y1.63 Z0.1\nG81 G99 Z-0.05 P0.5 R0.25 F11.46\nG80\nM2\n", "test");
  bool noted = false;
  for (const std::string& n : program.notes) noted = noted || n.find("P0.5 on G81 is ignored") != std::string::npos;
  EXPECT_TRUE(noted);
  ASSERT_EQ(program.path.moves.size(), 4U);  // the G0, up to R (0.25 in above the start), drill, back to R
  EXPECT_NEAR(program.path.moves[3].end.z_mm, 0.25 * 25.4, 1e-9);
  EXPECT_DOUBLE_EQ(program.blocks[3].dwell_before_s, 0.0) << "no dwell: G81 does not read P";
}

}  // namespace
}  // namespace feedplan::gcode
