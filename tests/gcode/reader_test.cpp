// The G-code reader against values computed by hand, and its problem messages.

#include "feedplan/gcode/reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::gcode {
namespace {

using geometry::MoveKind;
using geometry::Program;
using geometry::SpindleDirection;
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;
constexpr double kTight = 1e-12;

Program read(const std::string& text, const ReaderOptions& options = {}) { return read_program(text, "test", options); }

// The problem text read_program throws for `text`, or "(accepted)".
std::string problems_of(const std::string& text, const ReaderOptions& options = {}) {
  try {
    read(text, options);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(accepted)";
}

TEST(Reader, QuarterArcWithIJHasCentreAndSweepFromHandCalculation) {
  // From (10, 0) counter-clockwise about (10 − 10, 0 + 0) = (0, 0) to (0, 10): a quarter circle.
  const Program p = read("G21 F100\nG0 X10 Y0\nG3 X0 Y10 I-10 J0\nM2\n");
  ASSERT_EQ(p.path.moves.size(), 2u);
  const auto& arc = p.path.moves[1];
  EXPECT_EQ(arc.kind, MoveKind::kArc);
  EXPECT_TRUE(arc.ccw);
  EXPECT_NEAR(arc.center.x_mm, 0.0, kTight);
  EXPECT_NEAR(arc.center.y_mm, 0.0, kTight);
  EXPECT_NEAR(arc.sweep_rad, kPi / 2, kTight);
  EXPECT_NEAR(arc.start.x_mm, 10.0, kTight);
  EXPECT_NEAR(arc.end.y_mm, 10.0, kTight);
  EXPECT_TRUE(arc.cutting);
  EXPECT_EQ(arc.axial_depth_mm, 0.0);
  EXPECT_EQ(p.blocks[1].feed_mm_per_min, 100.0);
  EXPECT_EQ(p.blocks[1].source_line, 3);
  EXPECT_EQ(p.path.moves[0].kind, MoveKind::kRapid);
  EXPECT_FALSE(p.path.moves[0].cutting);
  EXPECT_EQ(p.blocks[0].feed_mm_per_min, 0.0);
  ASSERT_EQ(p.path.part_names.size(), 1u);
  EXPECT_EQ(p.path.part_names[0], "program");
  EXPECT_TRUE(geometry::consistency_defects(p.path).empty());
}

TEST(Reader, ClockwiseArcOfThreeQuartersWithIJ) {
  // From (0, −5) clockwise about (0, 0) to (5, 0): −90° → 0° the long way round, 270°.
  const Program p = read("G21 F100\nG0 Y-5\nG2 X5 Y0 J5\nM2\n");
  const auto& arc = p.path.moves[1];
  EXPECT_FALSE(arc.ccw);
  EXPECT_NEAR(arc.center.x_mm, 0.0, kTight);
  EXPECT_NEAR(arc.center.y_mm, 0.0, kTight);
  EXPECT_NEAR(arc.sweep_rad, 1.5 * kPi, kTight);
}

// grbl posts (FreeCAD's among them) write K0 on XY arcs; grbl ignores it, and so does the reader, once noted.
TEST(Reader, AKWordOfAnXYArcIsIgnoredWithANote) {
  const Program with_k = read("G21 F100\nG0 Y-5\nG2 X5 Y0 J5 K0\nG2 X0 Y-5 I-5 K2.5\nM2\n");
  const Program without = read("G21 F100\nG0 Y-5\nG2 X5 Y0 J5\nG2 X0 Y-5 I-5\nM2\n");
  ASSERT_EQ(with_k.path.moves.size(), without.path.moves.size());
  for (std::size_t i = 0; i < with_k.path.moves.size(); ++i) {
    EXPECT_EQ(with_k.path.moves[i].center.x_mm, without.path.moves[i].center.x_mm);
    EXPECT_EQ(with_k.path.moves[i].center.y_mm, without.path.moves[i].center.y_mm);
    EXPECT_EQ(with_k.path.moves[i].sweep_rad, without.path.moves[i].sweep_rad);
  }
  ASSERT_EQ(with_k.notes.size(), 1u);
  EXPECT_THAT(with_k.notes[0], HasSubstr("line 3: K words of arcs in the XY plane are ignored"));
}

TEST(Reader, PositiveRGivesTheShortArcNegativeRTheLongOne) {
  // Chord (0, 0) → (10, 10), half length √50 = R / √2 for R = 10, so the centre is √50 from the
  // chord's middle (5, 5): (10, 0) on the right of the chord, (0, 10) on the left.
  const Program short_arc = read("G21 F100\nG2 X10 Y10 R10\nM2\n");
  EXPECT_NEAR(short_arc.path.moves[0].center.x_mm, 10.0, 1e-12);
  EXPECT_NEAR(short_arc.path.moves[0].center.y_mm, 0.0, 1e-12);
  EXPECT_NEAR(short_arc.path.moves[0].sweep_rad, kPi / 2, 1e-12);
  const Program long_arc = read("G21 F100\nG2 X10 Y10 R-10\nM2\n");
  EXPECT_NEAR(long_arc.path.moves[0].center.x_mm, 0.0, 1e-12);
  EXPECT_NEAR(long_arc.path.moves[0].center.y_mm, 10.0, 1e-12);
  EXPECT_NEAR(long_arc.path.moves[0].sweep_rad, 1.5 * kPi, 1e-12);
  const Program ccw_short = read("G21 F100\nG3 X10 Y10 R10\nM2\n");
  EXPECT_NEAR(ccw_short.path.moves[0].center.x_mm, 0.0, 1e-12);
  EXPECT_NEAR(ccw_short.path.moves[0].center.y_mm, 10.0, 1e-12);
  EXPECT_NEAR(ccw_short.path.moves[0].sweep_rad, kPi / 2, 1e-12);
}

TEST(Reader, RaHairShortOfHalfTheChordGivesTheHalfCircle) {
  // Half chord 5, R 4.999: 0.001 mm short, within the default 0.002 mm.
  const Program p = read("G21 F100\nG2 X10 Y0 R4.999\nM2\n");
  EXPECT_NEAR(p.path.moves[0].center.x_mm, 5.0, 1e-12);
  EXPECT_NEAR(p.path.moves[0].center.y_mm, 0.0, 1e-12);
  EXPECT_NEAR(p.path.moves[0].sweep_rad, kPi, 1e-12);
}

TEST(Reader, FullCircleHelixWithExtraTurns) {
  // Start == end with I/J: a full circle; P3 makes three turns; Z falls 6 mm along them.
  const Program p = read("G21 F100\nG0 X10\nG2 X10 Y0 Z-6 I-10 J0 P3\nM2\n");
  const auto& arc = p.path.moves[1];
  EXPECT_NEAR(arc.sweep_rad, 6 * kPi, 1e-12);
  EXPECT_FALSE(arc.ccw);
  EXPECT_EQ(arc.end.z_mm, -6.0);
  EXPECT_NEAR(geometry::length_mm(arc), std::hypot(3 * 2 * kPi * 10, 6.0), 1e-9);
  const Program one_turn = read("G21 F100\nG3 I5\nM2\n");
  EXPECT_NEAR(one_turn.path.moves[0].sweep_rad, 2 * kPi, 1e-12);
  EXPECT_NEAR(one_turn.path.moves[0].center.x_mm, 5.0, 1e-12);
}

TEST(Reader, HalfTurnHelixWithP2AddsATurn) {
  const Program p = read("G21 F100\nG0 X10\nG3 X-10 Y0 Z-3 I-10 J0 P2\nM2\n");
  EXPECT_NEAR(p.path.moves[1].sweep_rad, 3 * kPi, 1e-12);
}

TEST(Reader, IncrementalPositionsAndArcCentres) {
  // G91: every X Y Z adds to the position; I J are offsets from the start either way (G91.1).
  const Program p = read("G21 F100\nG0 X1 Y1\nG91\nG1 X5 Y5\nX5\nG3 X-10 Y0 I-5 J0 Z-2\nG90.1\nG2 X8 Y0 I5 J6\nM2\n");
  ASSERT_EQ(p.path.moves.size(), 5u);
  EXPECT_EQ(p.path.moves[1].end.x_mm, 6.0);
  EXPECT_EQ(p.path.moves[1].end.y_mm, 6.0);
  EXPECT_EQ(p.path.moves[2].end.x_mm, 11.0);
  EXPECT_EQ(p.path.moves[2].kind, MoveKind::kLine);
  const auto& arc = p.path.moves[3];
  EXPECT_NEAR(arc.end.x_mm, 1.0, kTight);
  EXPECT_NEAR(arc.end.y_mm, 6.0, kTight);
  EXPECT_NEAR(arc.end.z_mm, -2.0, kTight);
  EXPECT_NEAR(arc.center.x_mm, 6.0, kTight);
  EXPECT_NEAR(arc.sweep_rad, kPi, kTight);
  // G90.1: I J are the centre itself, (5, 6); from (1, 6) by X8 to (9, 6), clockwise over the top.
  const auto& absolute = p.path.moves[4];
  EXPECT_NEAR(absolute.center.x_mm, 5.0, kTight);
  EXPECT_NEAR(absolute.center.y_mm, 6.0, kTight);
  EXPECT_NEAR(absolute.end.x_mm, 9.0, kTight);
  EXPECT_NEAR(absolute.sweep_rad, kPi, kTight);
}

TEST(Reader, InchInputIsConvertedToMillimetres) {
  const Program p = read("G20\nF10\nG1 X1 Y2\nG2 X3 Y2 R1 Z-0.5\nG21\nG1 X100\nM2\n");
  ASSERT_EQ(p.path.moves.size(), 3u);
  EXPECT_NEAR(p.path.moves[0].end.x_mm, 25.4, kTight);
  EXPECT_NEAR(p.path.moves[0].end.y_mm, 50.8, kTight);
  EXPECT_NEAR(p.blocks[0].feed_mm_per_min, 254.0, kTight);
  EXPECT_NEAR(p.path.moves[1].center.x_mm, 50.8, 1e-9);
  EXPECT_NEAR(p.path.moves[1].center.y_mm, 50.8, 1e-9);
  EXPECT_NEAR(p.path.moves[1].end.z_mm, -12.7, kTight);
  // Back in mm: the feed set in inches keeps its speed (LinuxCNC converts F when it is read).
  EXPECT_EQ(p.path.moves[2].end.x_mm, 100.0);
  EXPECT_NEAR(p.blocks[2].feed_mm_per_min, 254.0, kTight);
}

TEST(Reader, DwellsGoBeforeTheNextMoveOrToTheEnd) {
  const Program p = read("G21 F100\nG4 P0.5\nG4 P0.25\nG1 X1\nG4 P1 G1 X2\nG1 X3\nG4 P2\nM2\n");
  ASSERT_EQ(p.path.moves.size(), 3u);
  EXPECT_DOUBLE_EQ(p.blocks[0].dwell_before_s, 0.75);
  EXPECT_DOUBLE_EQ(p.blocks[1].dwell_before_s, 1.0);
  EXPECT_DOUBLE_EQ(p.blocks[2].dwell_before_s, 0.0);
  EXPECT_DOUBLE_EQ(p.dwell_at_end_s, 2.0);
}

TEST(Reader, SpindleSpeedAndDirectionAreTracked) {
  const Program p = read("G21 F100\nG1 X1\nS1000 M3\nG1 X2\nM4 S2500.5\nG0 X3\nM5\nG1 X4\nM2\n");
  ASSERT_EQ(p.blocks.size(), 4u);
  EXPECT_EQ(p.blocks[0].spindle, SpindleDirection::kOff);
  EXPECT_EQ(p.blocks[0].spindle_rpm, 0.0);
  EXPECT_EQ(p.blocks[1].spindle, SpindleDirection::kClockwise);
  EXPECT_EQ(p.blocks[1].spindle_rpm, 1000.0);
  EXPECT_EQ(p.blocks[2].spindle, SpindleDirection::kCounterClockwise);
  EXPECT_EQ(p.blocks[2].spindle_rpm, 2500.5);
  EXPECT_EQ(p.blocks[2].feed_mm_per_min, 0.0);  // a rapid
  EXPECT_EQ(p.blocks[3].spindle, SpindleDirection::kOff);
  EXPECT_EQ(p.blocks[3].spindle_rpm, 2500.5);
}

TEST(Reader, FeedChangesApplyFromTheirBlockOn) {
  const Program p = read("G21\nG1 X1 F100\nG1 X2\nF250.5\nG2 X4 I1\nG0 X0\nG1 Y1\nM2\n");
  EXPECT_EQ(p.blocks[0].feed_mm_per_min, 100.0);
  EXPECT_EQ(p.blocks[1].feed_mm_per_min, 100.0);
  EXPECT_EQ(p.blocks[2].feed_mm_per_min, 250.5);
  EXPECT_EQ(p.blocks[3].feed_mm_per_min, 0.0);
  EXPECT_EQ(p.blocks[4].feed_mm_per_min, 250.5);
}

TEST(Reader, ZeroLengthMovesAndBareMotionWordsMakeNoMove) {
  const Program p = read("G21 F100\nG1\nG1 X0 Y0\nX5\nX5\nG0\nM2\n");
  ASSERT_EQ(p.path.moves.size(), 1u);
  EXPECT_EQ(p.blocks[0].source_line, 4);
}

TEST(Reader, StartsAtTheInitialPosition) {
  ReaderOptions options;
  options.initial_position = {1.0, 2.0, 30.0};
  const Program p = read("G21 F100\nG91 G1 X1\nM2\n", options);
  EXPECT_EQ(p.path.moves[0].start.z_mm, 30.0);
  EXPECT_EQ(p.path.moves[0].end.x_mm, 2.0);
  EXPECT_EQ(p.path.moves[0].end.y_mm, 2.0);
}

TEST(Reader, AcceptsTheFormatsACamPostWrites) {
  const Program p = read(
      "%\nO1000 (part)\nN5 g21 g17 g90 g40 g49 g80 g94 g54 G64 P0.01 ; header\n"
      "N10 T1 S 3000 M3 M8\nN15 G0 G40 G80 X 1 0 Y - 2 . 5\nN20 G1 Z-1 F 3 0 0 (plunge)\nN25 M9 M5\nN30 M30\n%\n");
  ASSERT_EQ(p.path.moves.size(), 2u);
  EXPECT_EQ(p.path.moves[0].end.x_mm, 10.0);
  EXPECT_EQ(p.path.moves[0].end.y_mm, -2.5);
  EXPECT_EQ(p.blocks[1].feed_mm_per_min, 300.0);
  EXPECT_EQ(p.blocks[1].spindle_rpm, 3000.0);
  EXPECT_TRUE(p.notes.empty());
}

TEST(Reader, WorkOffsetBeforeTheFirstMoveIsAccepted) {
  EXPECT_EQ(problems_of("G21 G55 F100\nG1 X1\nG55 G1 X2\nM2\n"), "(accepted)");
}

TEST(Reader, PercentClosesTheProgramWithoutM2) {
  const Program p = read("%\nG21 F100\nG1 X1\n%\nthis is not read\n");
  EXPECT_EQ(p.path.moves.size(), 1u);
  ASSERT_EQ(p.notes.size(), 1u);
  EXPECT_THAT(p.notes[0], HasSubstr("line 5 and later are not read"));
}

TEST(Reader, NotesTheAssumedUnitAndMovedCentres) {
  // End radius 5.001 vs start radius 5: within tolerance; the centre moves onto the bisector x = 5.0005.
  const Program p = read("F100\nG3 X10.001 I5\nM2\n");
  ASSERT_EQ(p.notes.size(), 2u);
  EXPECT_THAT(p.notes[0], HasSubstr("line 2: no G20 or G21 before the first move; lengths are read as mm"));
  EXPECT_EQ(p.notes[1], "1 arc centre was moved so that start and end lie on one circle (their radii differed within "
                       "ReaderOptions::arc_radius_tolerance_mm); the largest move is 0.0005 mm, on line 2");
  EXPECT_NEAR(p.path.moves[0].center.x_mm, 5.0005, 1e-12);
  EXPECT_TRUE(geometry::consistency_defects(p.path).empty());
}

TEST(Reader, ShortArcsKeepTheirProgrammedCentre) {
  // The flat bottom circle of a helical bore (radius 3 about the origin) as a planner writes it at 3
  // decimals: pieces whose rounded ends lie up to 0.36 µm off radius 3. Moving the centre of each
  // short piece onto the bisector of its chord would move it by 3.7 to 7.5 µm (radius 3 ± 0.0075);
  // LinuxCNC keeps every centre (0, 0) and drives spirals. The reader moves the centre of the first,
  // long piece by 0.14 µm (less than its end would move) and keeps the others' centre, moving their
  // ends onto the circle instead: every piece lies on one circle within a rounding of the written one.
  const Program p = read(
      "G21 G17 G90 G91.1 F1000\nG0 X3. Y0.\n"
      "G3 X0.657 Y2.927 I-3. J0.\n"
      "X0.312 Y2.984 I-0.657 J-2.927\n"
      "X0.062 Y2.999 I-0.312 J-2.984\n"
      "X-0.137 Y2.997 I-0.062 J-2.999\n"
      "X-0.287 Y2.986 I0.137 J-2.997\n"
      "M2\n");
  ASSERT_EQ(p.path.moves.size(), 6u);
  const double rounding_mm = 0.5e-3 * std::sqrt(2.0);  // half a last digit in X and in Y
  const double written_end[][2] = {{0.657, 2.927}, {0.312, 2.984}, {0.062, 2.999}, {-0.137, 2.997}, {-0.287, 2.986}};
  const geometry::Point2 first_center = p.path.moves[1].center;
  for (std::size_t i = 1; i < p.path.moves.size(); ++i) {
    SCOPED_TRACE("arc " + std::to_string(i));
    const auto& arc = p.path.moves[i];
    EXPECT_LE(std::hypot(arc.center.x_mm, arc.center.y_mm), rounding_mm);
    EXPECT_LE(std::abs(geometry::arc_radius_mm(arc) - 3.0), rounding_mm);
    EXPECT_LE(std::hypot(arc.end.x_mm - written_end[i - 1][0], arc.end.y_mm - written_end[i - 1][1]), rounding_mm);
    if (i > 1) {  // the short pieces: the programmed centre itself, on the first piece's circle
      EXPECT_NEAR(arc.center.x_mm, 0.0, kTight);
      EXPECT_NEAR(arc.center.y_mm, 0.0, kTight);
      EXPECT_NEAR(geometry::arc_radius_mm(arc), std::hypot(p.path.moves[1].end.x_mm, p.path.moves[1].end.y_mm), kTight);
    }
  }
  EXPECT_NEAR(std::hypot(first_center.x_mm, first_center.y_mm), 0.136e-3, 0.001e-3);
  EXPECT_TRUE(geometry::consistency_defects(p.path).empty());
  ASSERT_EQ(p.notes.size(), 2u);
  EXPECT_THAT(p.notes[0], HasSubstr("1 arc centre was moved so that start and end lie on one circle"));
  EXPECT_THAT(p.notes[1], HasSubstr("4 arc ends were moved onto the circle about the programmed centre"));
}

TEST(Reader, CoordinateResolutionIsTheFinestWrittenDigit) {
  EXPECT_EQ(read("G21 F100\nG1 X1 Y2.\nM2\n").coordinate_resolution_mm, 0.0);  // whole numbers only
  EXPECT_DOUBLE_EQ(read("G21 F100\nG1 X1.5 Y2.25\nG1 Z-0.125\nM2\n").coordinate_resolution_mm, 0.001);
  EXPECT_DOUBLE_EQ(read("G21 F100\nG0 X0 Y1.5\nG3 X0 Y-1.5 I0 J-1.5000\nM2\n").coordinate_resolution_mm, 1e-4);
  EXPECT_DOUBLE_EQ(read("G20\nF10\nG1 X1.25\nM2\n").coordinate_resolution_mm, 0.254);  // 0.01 in
  EXPECT_DOUBLE_EQ(read("G21 F100\nS1000.125 M3\nG1 X1.5\nM2\n").coordinate_resolution_mm, 0.1);  // S is no coordinate
}

TEST(Reader, SnippetsWithoutProgramEndAreAcceptedOnRequest) {
  ReaderOptions options;
  options.require_program_end = false;
  EXPECT_EQ(read("G21 G1 X1 F100", options).path.moves.size(), 1u);
  EXPECT_THAT(problems_of("G21 G1 X1 F100\n\n"),
              HasSubstr("test line 1: end of text: the program ends without M2, M30 or a closing %"));
}

TEST(Reader, ArcToleranceIsAnOption) {
  ReaderOptions options;
  options.arc_radius_tolerance_mm = 0.05;
  EXPECT_EQ(problems_of("G21 F100\nG3 X10 Y0 I5.01\nM2\n", options), "(accepted)");
  EXPECT_THAT(problems_of("G21 F100\nG3 X10 Y0 I5.01\nM2\n"),
              HasSubstr("line 2: G3 I5.01: end point is 0.02 mm off the circle"));
  options.arc_radius_tolerance_mm = -1;
  EXPECT_THAT(problems_of("G21 F100\nM2\n", options), HasSubstr("ReaderOptions::arc_radius_tolerance_mm = -1"));
}

// An inch post with 4 decimals rounds start, end and centre to 2.54 µm: radii that differ by a digit or
// two are its rounding (FreeCAD's mach3 post writes such arcs), not a wrong arc.
TEST(Reader, AnInchArcsToleranceCoversTwoOfItsLastDigits) {
  EXPECT_EQ(problems_of("G20\nF10\nG0 X1.0000 Y0.0000\nG3 X0.0000 Y1.0001 I-1.0000 J0.0000\nM2\n"), "(accepted)");
  EXPECT_EQ(problems_of("G20\nF10\nG0 X1.0000 Y0.0000\nG3 X0.0000 Y1.0002 I-1.0000 J0.0000\nM2\n"), "(accepted)");
  EXPECT_THAT(problems_of("G20\nF10\nG0 X1.0000 Y0.0000\nG3 X0.0000 Y1.0003 I-1.0000 J0.0000\nM2\n"),
              HasSubstr("end point is 0.00762 mm off the circle"));
  EXPECT_THAT(problems_of("G20\nF10\nG0 X1 Y0\nG3 X0 Y1.001 I-1.\nM2\n"), HasSubstr("off the circle"))
      << "coarser words are taken as meant";
}

// A program of two tools (FreeCAD's `M6 T3` then `G43 H3`): refused by default, read when the caller plans
// each tool's moves on its own, every move knowing the tool that makes it.
TEST(Reader, ToolChangesAnywhereWhenAskedEachMoveKnowsItsTool) {
  const std::string text =
      "G21\nM6 T2\nG43 H2\nM3 S10000\nG0 X0 Y0 Z5\nG1 Z-1 F100\nG1 X10\nG0 Z5\n"
      "M6 T3\nG43 H3\nG0 X20\nG1 Z-1\nG1 X30\nM2\n";
  EXPECT_THAT(problems_of(text), HasSubstr("line 9: word M6: not supported after the first move"));
  ReaderOptions options;
  options.tool_changes = true;
  std::vector<WrittenMove> written;
  const Program p = read_program(text, "test", options, written);
  ASSERT_EQ(written.size(), p.path.moves.size());
  std::vector<int> tools;
  for (const WrittenMove& w : written) tools.push_back(w.tool);
  EXPECT_EQ(tools, (std::vector<int>{2, 2, 2, 2, 3, 3, 3}));
  EXPECT_EQ(written[4].line, 11);
  EXPECT_THAT(p.notes.back(), HasSubstr("line 9: T3 M6: tool 3 from here"));
}

TEST(Reader, OneToolChangeBeforeTheFirstMoveIsReadAndNoted) {
  // T in the M6 block or before it; G43 with the tool's H in a rapid's block, or without H.
  for (const std::string head : {"T3 M6\nG43 H3\n", "T3\nM6\nG0 G43 H3 Z5\n", "T3 M6 G43\n", "T3 M6 G43 H3\n"}) {
    SCOPED_TRACE(head);
    const Program p = read("G21 F100\n" + head + "G0 X1 Z5\nG1 X2\nM2\n");
    ASSERT_EQ(p.path.moves.size(), head.find("Z5") != std::string::npos ? 3u : 2u);
    EXPECT_EQ(p.path.moves.back().end.x_mm, 2.0);
    EXPECT_EQ(p.path.moves.back().end.z_mm, 5.0);  // G43 leaves Z the programmed tool tip
    ASSERT_FALSE(p.notes.empty());
    EXPECT_THAT(p.notes.front(), HasSubstr("T3 M6: the program is for tool 3"));
  }
}

TEST(Reader, LengthOffsetWithoutToolChangeIsTakenToNameTheTool) {
  const Program p = read("G21 F100\nG0 G43 H7 X1 Z5\nG1 X2\nM2\n");
  ASSERT_EQ(p.path.moves.size(), 2u);
  ASSERT_EQ(p.notes.size(), 1u);
  EXPECT_THAT(p.notes[0], HasSubstr("line 2: G43 H7 with no tool change (T M6) before it: the program is taken to be "
                                    "for tool 7"));
}

// --- Bad input: every problem names the line and the word --------------------------------------

TEST(ReaderProblems, UnknownWordsAndCodes) {
  EXPECT_THAT(problems_of("G21 F100\nG1 X10 Q5\nM2\n"),
              HasSubstr("test line 2: word Q5: not supported here (Q is read only with G64, G73 and G83)"));
  EXPECT_THAT(problems_of("G21 F100\nG7\nM2\n"), HasSubstr("test line 2: word G7: not supported (lathe diameter mode)"));
  EXPECT_THAT(problems_of("G21 F100\nG12 X1\nM2\n"),
              HasSubstr("test line 2: word G12: not supported (not a G code the reader knows)"));
  EXPECT_THAT(problems_of("G21 F100\nM100\nM2\n"),
              HasSubstr("test line 2: word M100: not supported (not an M code the reader knows)"));
  EXPECT_THAT(problems_of("G21 F100\nG41 D1\nM2\n"), HasSubstr("test line 2: word D1: cutter compensation needs the diameter of tool 1, which is not given: give "
                                                              "the diameter of tool 1 (ReaderOptions::tool_diameters_mm; feedplan optimize --tools)"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1 A3\nM2\n"), HasSubstr("test line 2: word A3: not supported (rotary axes"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1 E3\nM2\n"), HasSubstr("test line 2: word E3: not supported"));
  EXPECT_THAT(problems_of("G21 F100\nG18.1\nM2\n"), HasSubstr("test line 2: word G18.1: not supported (arcs are read in the XY, XZ and YZ"));
}

TEST(ReaderProblems, ToolChangesAndLengthOffsets) {
  EXPECT_THAT(problems_of("G21 F100\nT1 M6\nT2 M6\nG1 X1\nM2\n"),
              HasSubstr("test line 3: word M6: a second tool change (T1 M6 on line 2) is not supported (tool change: "
                        "the path is planned for one tool; split the program per tool)"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1\nT1 M6\nM2\n"),
              HasSubstr("test line 3: word M6: not supported after the first move (tool change: the path is planned "
                        "for one tool"));
  EXPECT_THAT(problems_of("G21 F100\nM6\nM2\n"),
              HasSubstr("test line 2: word M6: no tool selected: a T word must come before M6 or with it"));
  EXPECT_THAT(problems_of("G21 F100\nT1 M6\nG43 H2\nM2\n"),
              HasSubstr("test line 3: word H2: G43 H2 is the length offset of tool 2, but tool 1 is in the spindle"));
  EXPECT_THAT(problems_of("G21 F100\nT1 M6 G43 H2\nM2\n"), HasSubstr("test line 2: word H2: G43 H2 is the length"));
  EXPECT_THAT(problems_of("G21 F100\nG0 X1 H1\nM2\n"),
              HasSubstr("test line 2: word H1: H is read only with G43 (the tool length offset number)"));
  EXPECT_THAT(problems_of("G21 F100\nG43\nM2\n"),
              HasSubstr("test line 2: word G43: without H and with no tool change (T M6) before it"));
  EXPECT_THAT(problems_of("G21 F100\nG43 H1.5\nM2\n"),
              HasSubstr("test line 2: word H1.5: a tool length offset number must be a whole number ≥ 0"));
  EXPECT_THAT(problems_of("G21 F100\nG43 H1\nT2 M6\nM2\n"),
              HasSubstr("test line 3: word M6: G43 H1 (line 2) stays in effect after the change"));
  EXPECT_THAT(problems_of("G21 F100\nT1 M6\nG43.1 Z1\nM2\n"),
              HasSubstr("test line 3: word G43.1: not supported (dynamic or added tool length offsets"));
}

TEST(ReaderProblems, FeedMoveWithoutPositiveFeed) {
  EXPECT_THAT(problems_of("G21\nG0 X1\nG1 X10\nM2\n"),
              HasSubstr("test line 3: G1 before any F word: feed moves need a positive F"));
  EXPECT_THAT(problems_of("G21 F0\nG2 X10 I5\nM2\n"),
              HasSubstr("test line 2: G2 with F0 in effect (set on line 1): feed moves need a positive F"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1\nG94\nG1 X2\nM2\n"),
              HasSubstr("test line 4: G1 with no F since G94 on line 3"));
  EXPECT_THAT(problems_of("G21\nG1 X1 F-5\nM2\n"), HasSubstr("test line 2: word F-5: a feed must be ≥ 0"));
  // Reported once, not on every later feed move.
  const std::string text = problems_of("G21\nG1 X1\nG1 X2\nG1 X3\nM2\n");
  EXPECT_EQ(text.find("line 3"), std::string::npos) << text;
}

TEST(ReaderProblems, ArcsThatDoNotCloseOrReach) {
  EXPECT_THAT(problems_of("G21 F100\nG3 X10 Y0 I5.1\nM2\n"),
              HasSubstr("test line 2: G3 I5.1: end point is 0.2 mm off the circle: radius 5.1 mm at the start, "
                        "4.9 mm at the end"));
  EXPECT_THAT(problems_of("G21 F100\nG2 X10 Y0 R4\nM2\n"),
              HasSubstr("test line 2: G2 R4: radius 4 mm is shorter than half the chord (5 mm)"));
  EXPECT_THAT(problems_of("G21 F100\nG2 X0 Y0 R5\nM2\n"),
              HasSubstr("test line 2: G2 R5: start and end are the same point"));
  EXPECT_THAT(problems_of("G21 F100\nG2 X0 Y0 I0 J0\nM2\n"), HasSubstr("test line 2: G2 I0 J0: zero radius"));
  EXPECT_THAT(problems_of("G21 F100\nG2 X1\nM2\n"),
              HasSubstr("test line 2: G2 without I, J or R: an arc needs its centre (I, J) or its radius (R)"));
  EXPECT_THAT(problems_of("G21 F100\nG2 X10 R5 I5\nM2\n"), HasSubstr("test line 2: word R5: R and I/J in one arc"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X10 K1\nM2\n"),
              HasSubstr("test line 2: word K1: K is read only with G2 or G3 (G1 in this block)"));
  EXPECT_THAT(problems_of("G21 F100\nG2 X10 I5 P0\nM2\n"),
              HasSubstr("test line 2: word P0: the number of turns of G2/G3 must be a whole number ≥ 1"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1 I5\nM2\n"),
              HasSubstr("test line 2: word I5: I is read only with G2 or G3 (G1 in this block)"));
}

TEST(ReaderProblems, NumbersThatAreNotPlainDecimals) {
  EXPECT_THAT(problems_of("G21 F100\nG1 X1..2\nM2\n"),
              HasSubstr("test line 2: word X1..2: \"1..2\" is not a number"));
  EXPECT_THAT(problems_of("G21 F100\nG1 Xabc\nM2\n"),
              HasSubstr("test line 2: word X: needs a number after the letter, found \"ABC\""));
  EXPECT_THAT(problems_of("G21 F100\nG1 X\nM2\n"), HasSubstr("test line 2: word X: needs a number after the letter"));
  EXPECT_THAT(problems_of("G21 F100\nG1 XNaN\nM2\n"),
              HasSubstr("test line 2: word X: needs a number after the letter, found \"NAN\""));
  EXPECT_THAT(problems_of("G21 F100\nG1 Xinf\nM2\n"),
              HasSubstr("test line 2: word X: needs a number after the letter, found \"INF\""));
  EXPECT_THAT(problems_of("G21 F100\nG1 X-\nM2\n"), HasSubstr("test line 2: word X-: \"-\" is not a number"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1" + std::string(400, '0') + "\nM2\n"),
              HasSubstr("test line 2: word X1000000000000000000…: out of range"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X#1\nM2\n"),
              HasSubstr("test line 2: word X: needs a number after the letter"));
  EXPECT_THAT(problems_of("G21 F100\n#1=5\nM2\n"),
              HasSubstr("test line 2: character '#': not supported (numbered and named parameters)"));
}

TEST(ReaderProblems, TwoWordsOfOneModalGroupOrLetter) {
  EXPECT_THAT(problems_of("G21 F100\nG0 G1 X1\nM2\n"),
              HasSubstr("test line 2: word G1: same modal group (motion) as G0 in this block; use one"));
  EXPECT_THAT(problems_of("G21 F100\nG90 G91\nM2\n"), HasSubstr("test line 2: word G91: same modal group (distance mode) as G90"));
  EXPECT_THAT(problems_of("G21 F100\nM3 M5\nM2\n"), HasSubstr("test line 2: word M5: same modal group (spindle) as M3"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1 X2\nM2\n"),
              HasSubstr("test line 2: word X2: a second X word in the block (the first is X1)"));
  EXPECT_EQ(problems_of("G21 F100\nG0 G40 G49 G80 G90 X3\nM2\n"), "(accepted)");
}

TEST(ReaderProblems, UnbalancedComments) {
  EXPECT_THAT(problems_of("G21 F100\nG1 X1 (comment\nM2\n"),
              HasSubstr("test line 2: comment: '(' at column 7 is not closed"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1 comment)\nM2\n"),
              HasSubstr("test line 2: comment: ')' at column 14 has no matching '('"));
  EXPECT_THAT(problems_of("G21 F100\n(a (b) c)\nM2\n"),
              HasSubstr("test line 2: comment: '(' at column 4 inside a comment; comments cannot be nested"));
  EXPECT_EQ(problems_of("G21 F100\nG1 X1 ; (not a comment opener\nM2\n"), "(accepted)");
}

TEST(ReaderProblems, WordsOutOfPlace) {
  EXPECT_THAT(problems_of("G21\nX5\nM2\n"),
              HasSubstr("test line 2: word X5: axis words need a motion mode, and no G0, G1, G2 or G3 is in effect"));
  EXPECT_THAT(problems_of("G21 F100\nG1 N10 X1\nM2\n"),
              HasSubstr("test line 2: word N10: a line number must be the first word of its block"));
  EXPECT_THAT(problems_of("G21\nG4 P-1\nM2\n"), HasSubstr("test line 2: word P-1: a G4 dwell must be ≥ 0 s"));
  EXPECT_THAT(problems_of("G21\nG4\nM2\n"), HasSubstr("test line 2: G4 without P: a dwell needs P, its time in seconds"));
  EXPECT_THAT(problems_of("G21\nG20 F10 G1 X1\nM2\n"), HasSubstr("test line 2: word F10: F in a block whose G20 changes the units"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1\nG55\nM2\n"), HasSubstr("test line 3: word G55: not supported after the first move"));
  EXPECT_THAT(problems_of("G21 F100\n/G1 X5\nM2\n"), HasSubstr("test line 2: character '/': not supported (block delete"));
  EXPECT_THAT(problems_of("O100 sub\nM2\n"), HasSubstr("test line 1: word O100: not supported here"));
  EXPECT_THAT(problems_of("o<probe> call\nM2\n"), HasSubstr("test line 1: word O: not supported (named O words"));
  EXPECT_THAT(problems_of("G21 F100\nG1 X1\n%\nM2\n"),
              HasSubstr("test line 3: '%': a closing % needs an opening % alone on the first line"));
}

TEST(ReaderProblems, EveryProblemIsCollectedInOneError) {
  const std::string text = "G21\nG1 X10\nG1 X1 Q5\nG3 X20 Y0 I5.1 F100\nG2 X1\nG1 X1..2\nG0 G1 X1\nG1 X1 (comment\nM2\n";
  try {
    read(text);
    FAIL() << "accepted";
  } catch (const InputError& error) {
    ASSERT_EQ(error.problems().size(), 7u) << error.what();
    const char* fields[] = {"test line 2:", "test line 3:", "test line 4:", "test line 5:",
                            "test line 6:", "test line 7:", "test line 8:"};
    for (std::size_t i = 0; i < 7; ++i) EXPECT_EQ(error.problems()[i].field, fields[i]);
  }
}

TEST(ReaderProblems, CollectingStopsAtTheCap) {
  std::string text = "G21\n";
  for (int i = 0; i < 100; ++i) text += "G1 X1 Q5\n";
  ReaderOptions options;
  options.max_problems = 10;
  try {
    read(text + "M2\n", options);
    FAIL() << "accepted";
  } catch (const InputError& error) {
    ASSERT_EQ(error.problems().size(), 11u);
    EXPECT_EQ(error.problems().back().message, "more problems follow; stopped after 10");
  }
}

TEST(ReaderFiles, LoadsAFileAndNamesItInProblems) {
  const std::filesystem::path path = std::filesystem::path(FEEDPLAN_TEST_DATA_DIR) / "gcode" / "bad" / "unknown_word.ngc";
  try {
    load_program(path);
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_THAT(std::string(error.what()), HasSubstr(path.string() + " line 2: word Q5: not supported"));
  }
  EXPECT_EQ(load_program(std::filesystem::path(FEEDPLAN_TEST_DATA_DIR) / "gcode" / "lines.ngc").path.moves.size(), 13u);
}

TEST(ReaderFiles, MissingFileOrDirectoryIsAnInputErrorNamingThePath) {
  const std::string missing = std::string(FEEDPLAN_TEST_DATA_DIR) + "/gcode/no_such_program.ngc";
  try {
    load_program(missing);
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), missing + " cannot be read: no such file (expected a G-code program of a milling job)");
  }
  try {
    load_program(FEEDPLAN_TEST_DATA_DIR);
    FAIL() << "accepted";
  } catch (const InputError& error) {
    EXPECT_THAT(std::string(error.what()), HasSubstr("is a directory"));
  }
}

}  // namespace
}  // namespace feedplan::gcode
