// Cutter radius compensation (G41, G42, G40) against LinuxCNC's interpreter: programs in the style of a
// hand-written Haas program (profiles and slots with G41 D01, R and I/J arcs, inch and mm, with and
// without D) are read by the reader with ReaderOptions::tool_diameters_mm and by `rs274 -t` with a tool
// table of the same diameters; the tool-centre moves must agree move by move — ends and arc centres to
// 1 µm (plus half of rs274's printed digit in inch programs), arc direction and sweep, feed. And what
// LinuxCNC refuses (or the reader cannot know) is refused by line and word, saying what helps.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
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
constexpr double kInchPrintMm = 0.5 * 0.0001 * 25.4 * 1.7320508;  // half a printed digit, on three axes

double distance_mm(const geometry::Point3& a, const geometry::Point3& b) {
  return std::hypot(std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm), b.z_mm - a.z_mm);
}

// LinuxCNC's tool table for `diameters_mm` (it reads diameters in inches).
std::string tool_table(const std::map<int, double>& diameters_mm) {
  std::string table;
  for (const auto& [tool, diameter_mm] : diameters_mm) {
    char row[96];
    std::snprintf(row, sizeof row, "T%d P%d D%.9f Z0\n", tool, tool, diameter_mm / 25.4);
    table += row;
  }
  return table;
}

class CutterCompensationOracle : public oracle::Rs274Test {
 protected:
  // Reads `text` with the tool diameters and compares every move with rs274's.
  geometry::Program expect_as_linuxcnc(const std::string& text, const std::map<int, double>& diameters_mm,
                                       std::vector<WrittenMove>* written_out = nullptr) {
    ReaderOptions options;
    options.tool_diameters_mm = diameters_mm;
    std::vector<WrittenMove> written;
    geometry::Program ours;
    try {
      ours = read_program(text, "test", options, written);
    } catch (const InputError& error) {
      ADD_FAILURE() << "the reader rejects the program:\n" << error.what();
      return ours;
    }
    if (written_out != nullptr) *written_out = written;
    EXPECT_TRUE(geometry::consistency_defects(ours.path).empty());
    const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, text, tool_table(diameters_mm));
    EXPECT_EQ(run.exit_code, 0) << run.messages;
    const bool inch = text.find("G20") != std::string::npos;
    const double tolerance_mm = kToleranceMm + (inch ? kInchPrintMm : 0.0);
    EXPECT_EQ(ours.path.moves.size(), run.moves.size()) << "moves read by feedplan vs by LinuxCNC";
    for (std::size_t i = 0; i < std::min(ours.path.moves.size(), run.moves.size()); ++i) {
      SCOPED_TRACE("move " + std::to_string(i) + " (line " + std::to_string(ours.blocks[i].source_line) + ")");
      const geometry::Move& m = ours.path.moves[i];
      const oracle::OracleMove& o = run.moves[i];
      EXPECT_EQ(m.kind, o.kind);
      EXPECT_LE(distance_mm(m.end, o.end), tolerance_mm) << m.end.x_mm << " " << m.end.y_mm << " vs " << o.end.x_mm
                                                         << " " << o.end.y_mm;
      if (m.kind == MoveKind::kArc && o.kind == MoveKind::kArc) {
        EXPECT_LE(std::hypot(m.center.x_mm - o.center.x_mm, m.center.y_mm - o.center.y_mm), tolerance_mm);
        EXPECT_EQ(m.ccw, o.rotation > 0);
        const double radius = std::hypot(m.end.x_mm - m.center.x_mm, m.end.y_mm - m.center.y_mm);
        EXPECT_LE(std::abs(m.sweep_rad - oracle::oracle_sweep_rad(o)) * radius, 2.0 * tolerance_mm);
      }
      EXPECT_NEAR(ours.blocks[i].feed_mm_per_min, o.feed_mm_per_min, 0.01);
    }
    return ours;
  }
};

TEST_F(CutterCompensationOracle, HaasProfileWithG41D01InInches) {
  std::vector<WrittenMove> written;
  const geometry::Program program = expect_as_linuxcnc(
      "%\n"
      "O1001\n"
      "G17 G20 G40 G49 G80\n"
      "T01 M06\n"
      "G00 G90 G17 G40 G49 G54 (Safe startup)\n"
      "G00 G54 X-1.0 Y-1.0\n"
      "S10000 M03\n"
      "G43 H01 Z0.1\n"
      "G01 Z-0.325 F108.0\n"
      "G41 D01 X0.25 (Cutter comp on)\n"
      "Y2.25\n"
      "X3.25\n"
      "Y0.25\n"
      "X0.25\n"
      "Y1.95\n"
      "G02 X0.55 Y2.25 R0.3\n"
      "G01 X1.15\n"
      "G03 X1.85 Y2.25 I0.35 J0.0\n"
      "G01 X2.75\n"
      "G02 X3.25 Y1.75 R0.5\n"
      "G01 Y0.7\n"
      "X2.75 Y0.25\n"
      "X0.8\n"
      "X0.25 Y0.6072\n"
      "X0.0 Y0.7695\n"
      "G40 X-1.0 (Cutter comp off)\n"
      "G00 Z0.1\n"
      "M30\n"
      "%\n",
      {{1, 12.7}}, &written);
  ASSERT_FALSE(program.path.moves.empty());
  // The corner arc at X0.25 Y2.25 belongs to the block that turns the corner, line 12 (X3.25).
  int moves_of_line_12 = 0;
  for (const WrittenMove& w : written) {
    if (w.line == 12) {
      ++moves_of_line_12;
      EXPECT_TRUE(w.keep_whole);
    }
  }
  EXPECT_EQ(moves_of_line_12, 2);
}

TEST_F(CutterCompensationOracle, HaasSlotWithG41D02InsideArcs) {
  expect_as_linuxcnc(
      "G17 G20 G40 G49 G80\n"
      "T02 M06\n"
      "G00 G90 G54 X1.7 Y1.52\n"
      "S10000 M03\n"
      "G43 H02 Z0.1\n"
      "G01 X1.7 Y0.75 Z-0.4 F40.0\n"
      "X1.7 Y1.52\n"
      "G41 D02 X1.475 Y0.765 (Cutter comp on)\n"
      "G01 Y0.75\n"
      "G03 X1.925 I0.225 J0.0\n"
      "G01 Y1.52\n"
      "G03 X1.475 I-0.225 J0.0\n"
      "G01 Y0.75\n"
      "G03 X1.925 I0.225 J0.0\n"
      "G40 G01 X1.7 Y1.52 (Cutter comp off)\n"
      "G00 Z0.1\n"
      "M30\n",
      {{2, 9.525}});
}

TEST_F(CutterCompensationOracle, MillimetresG42WithoutDConcaveCornersPlungeAndHelix) {
  // Tool 3 in the spindle; no D: its diameter. A pocket outline run on the right (G42) going clockwise
  // round the inside: every corner concave (line-line, line-arc, arc-line), a plunge inside
  // compensation and a helical arc.
  expect_as_linuxcnc(
      "G21 G17 G90 G40\n"
      "T3 M6\n"
      "S8000 M3\n"
      "G0 X0 Y0 Z5\n"
      "G1 Z1 F300\n"
      "G42 X10 Y10 F500\n"
      "G1 Z-2 F100\n"
      "G1 X10 Y40 F500\n"
      "X50\n"
      "G2 X60 Y30 I0 J-10\n"
      "G1 Y10\n"
      "G3 X50 Y0 Z-3 R10\n"
      "G1 X20\n"
      "X10 Y10\n"
      "G40 G1 X30 Y20\n"
      "G0 Z5\n"
      "M2\n",
      {{3, 6.0}});
}

TEST_F(CutterCompensationOracle, MillimetresG41EntryByRapidConvexCornersAndArcs) {
  // A contour on the left (G41) with D: an entry and a further move as rapids, a plunge, convex corners
  // rounded on arcs about the programmed corner, between lines and arcs and between two arcs.
  expect_as_linuxcnc(
      "G21 G17 G90\n"
      "T4 M6\n"
      "S6000 M3\n"
      "G0 X-20 Y-20 Z2\n"
      "G41 D4 G0 X0 Y-10\n"
      "G0 X0 Y0\n"
      "G1 Z-1 F200\n"
      "G1 X40 F600\n"
      "Y20\n"
      "G3 X20 Y20 R10\n"
      "G3 X0 Y20 R10\n"
      "G1 X0 Y0\n"
      "G1 X-5 Y-5\n"
      "G40 G0 X-20 Y-20\n"
      "G0 Z5\n"
      "M2\n",
      {{4, 8.0}});
}

TEST_F(CutterCompensationOracle, ScallopsMeetInConcaveCuspsArcToArcAndArcToLine) {
  // Half circles G2 side by side with the tool outside them (G41): their offset circles meet above each
  // cusp (arc-arc), and the last one meets the line after it (arc-line); a line into the first (line-arc).
  expect_as_linuxcnc(
      "G21 G17 G90\n"
      "T5 M6\n"
      "S6000 M3\n"
      "G0 X-10 Y-20 Z1\n"
      "G41 D5 G1 X-10 Y0 F400\n"
      "G1 X0 Y0\n"
      "G2 X20 Y0 R10\n"
      "G2 X40 Y0 I10 J0\n"
      "G2 X60 Y0 R10\n"
      "G1 X80 Y5\n"
      "G40 G1 X90 Y-20\n"
      "M2\n",
      {{5, 6.0}});
}

TEST_F(CutterCompensationOracle, InchesG42WithDAndR) {
  // G42 (the tool right of the path) clockwise round an outline in inches: R and I/J arcs, a chamfer.
  expect_as_linuxcnc(
      "G20 G17 G90\n"
      "T1 M6\n"
      "S8000 M3\n"
      "G0 X-1.0 Y-1.0 Z0.1\n"
      "G1 Z-0.2 F20.0\n"
      "G42 D1 G1 X0.0 Y-0.25 F60.0\n"
      "Y2.0\n"
      "G2 X0.5 Y2.5 R0.5\n"
      "G1 X2.5\n"
      "G2 X3.0 Y2.0 I0.0 J-0.5\n"
      "G1 Y0.5\n"
      "X2.5 Y0.0\n"
      "X-0.25\n"
      "G40 G1 X-1.0 Y-1.0\n"
      "G0 Z0.5\n"
      "M30\n",
      {{1, 6.35}});
}

// --- Refusals -------------------------------------------------------------------------------------

std::string problems_of(const std::string& text, const std::map<int, double>& diameters_mm) {
  ReaderOptions options;
  options.tool_diameters_mm = diameters_mm;
  try {
    read_program(text, "test", options);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(CutterCompensationProblems, AMissingDiameterNamesTheLineTheWordAndWhatHelps) {
  const std::string text = "G21 G90\nT1 M6\nS5000 M3\nG0 X-10 Y-10 Z1\nG41 D01 G1 X0 Y0 F100\nG1 X10\nG40 X20\nM2\n";
  EXPECT_THAT(problems_of(text, {}), HasSubstr("test line 5: word D01: cutter compensation needs the diameter of tool 1, "
                                               "which is not given: give the diameter of tool 1 "
                                               "(ReaderOptions::tool_diameters_mm; feedplan optimize --tools)"));
  EXPECT_THAT(problems_of("G21 G90\nG0 X-10 Y-10 Z1\nG42 G1 X0 Y0 F100\nG40 X5\nM2\n", {{1, 6.0}}),
              HasSubstr("test line 3: word G42: no D word and no tool in the spindle"));
  EXPECT_EQ(problems_of(text, {{1, 6.0}}), "");
}

TEST(CutterCompensationProblems, WhatLinuxCncRefusesIsRefusedWithTheReason) {
  const std::map<int, double> tools = {{1, 10.0}};
  EXPECT_THAT(problems_of("G21 G90\nT1 M6\nS5000 M3\nG0 X0 Y0 Z1\nG41 G1 X3 Y0 F100\nG1 X20\nG40 X30\nM2\n", tools),
              HasSubstr("test line 5: G1 under cutter compensation (G41 on line 5): the entry move after G41/G42 is 3 mm "
                        "long in XY, not longer than the tool radius 5 mm"));
  EXPECT_THAT(problems_of("G21 G90\nT1 M6\nS5000 M3\nG0 X0 Y-20 Z1\nG41 G1 X0 Y0 F100\nG1 X10\n"
                          "G3 X10 Y8 I0 J4\nG1 X0\nG40 X-20\nM2\n",
                          tools),
              HasSubstr("test line 7: G3 under cutter compensation (G41 on line 5): the tool radius 5 mm is not smaller "
                        "than the radius 4 mm of the arc it runs inside"));
  // A step of 2 mm into a concave corner of a 10 mm tool: the tool would have to back up past its start.
  EXPECT_THAT(problems_of("G21 G90\nT1 M6\nS5000 M3\nG0 X-20 Y-20 Z1\nG42 G1 X0 Y0 F100\nG1 X0 Y30\n"
                          "X2\nY0\nX40\nG40 X50 Y-20\nM2\n",
                          tools),
              HasSubstr("concave corner"));
  EXPECT_THAT(problems_of("G21 G90\nT1 M6\nS5000 M3\nG0 X-20 Y-20 Z1\nG41 G1 X0 Y0 F100\nG1 X20\n"
                          "G40\nG2 X30 Y-10 R10\nM2\n",
                          tools),
              HasSubstr("test line 8: G2: the move just after G40 (line 7) must be straight, not an arc"));
  EXPECT_THAT(problems_of("G21 G90\nT1 M6\nS5000 M3\nG0 X-20 Y-20 Z1\nG41 G1 X0 Y0 F100\nG42 X20\nG40 X30\nM2\n", tools),
              HasSubstr("test line 6: word G42: cutter compensation is already on (G41 on line 5)"));
  EXPECT_THAT(problems_of("G21 G90\nG0 X1 D3\nM2\n", tools), HasSubstr("test line 2: word D3: D is read only with G41 or G42"));
}

}  // namespace
}  // namespace feedplan::gcode
