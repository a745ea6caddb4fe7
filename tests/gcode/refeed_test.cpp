// refeed_text on small programs in the styles CAM posts write (FreeCAD's linuxcnc post, Fusion-style R
// arcs with helical entries in inches, G90.1 absolute centres, modal motion lines, `;` comments and CR LF
// endings, G1 used as a rapid, incremental mode): every feed move cut into pieces at made-up feeds.
// The oracle is LinuxCNC's interpreter: it reads the input and the re-fed program into the same path to
// 1 µm — the re-fed moves end on the input's moves, arcs about the same centres — at the pieces' feeds
// rounded down; every line that is not a feed move comes through byte for byte.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "rs274_runner.hpp"
#include "text_lines.hpp"

namespace feedplan::gcode {
namespace {

using oracle::OracleMove;
using test_support::lines_of;

// The paths must agree to 1 µm; rs274 prints 4 decimals in the program's unit, which in inches is
// 2.54 µm, so a point it prints lies up to half of that per axis from where it is.
constexpr double kPathToleranceMm = 1e-3;
constexpr double kInchPrintMm = 0.5 * 0.0001 * 25.4 * 1.7320508;  // half a printed digit, on three axes

// Move `m` from fraction f0 to f1 (arcs: the same circle, the sweep shared out).
geometry::Move part_of(const geometry::Move& m, double f0, double f1) {
  geometry::Move piece = m;
  piece.start = geometry::point_at(m, f0);
  piece.end = f1 >= 1.0 ? m.end : geometry::point_at(m, f1);
  if (m.kind == geometry::MoveKind::kArc) piece.sweep_rad = m.sweep_rad * (f1 - f0);
  return piece;
}

// Every feed move in 1, 2 or 3 pieces (by its index) with feeds of its own.
std::vector<FeedPiece> made_up_pieces(const geometry::Program& program) {
  std::vector<FeedPiece> pieces;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    const geometry::Move& m = program.path.moves[i];
    if (m.kind == geometry::MoveKind::kRapid) continue;
    const int count = 1 + static_cast<int>(i % 3);
    for (int k = 0; k < count; ++k) {
      pieces.push_back({static_cast<int>(i), part_of(m, static_cast<double>(k) / count, static_cast<double>(k + 1) / count),
                        123.456 + 37.0 * static_cast<double>(i) + 101.0 * k});
    }
  }
  return pieces;
}

double tolerance_mm = kPathToleranceMm;

double distance_to_move(const OracleMove& m, const geometry::Point3& p) {
  if (m.kind != geometry::MoveKind::kArc) {
    const double dx = m.end.x_mm - m.start.x_mm, dy = m.end.y_mm - m.start.y_mm, dz = m.end.z_mm - m.start.z_mm;
    const double len2 = dx * dx + dy * dy + dz * dz;
    const double t = len2 > 0 ? std::clamp(((p.x_mm - m.start.x_mm) * dx + (p.y_mm - m.start.y_mm) * dy +
                                            (p.z_mm - m.start.z_mm) * dz) / len2, 0.0, 1.0)
                              : 0.0;
    return std::hypot(p.x_mm - m.start.x_mm - t * dx, p.y_mm - m.start.y_mm - t * dy, p.z_mm - m.start.z_mm - t * dz);
  }
  const double r = std::hypot(m.start.x_mm - m.center.x_mm, m.start.y_mm - m.center.y_mm);
  return std::abs(std::hypot(p.x_mm - m.center.x_mm, p.y_mm - m.center.y_mm) - r);
}

bool same_point(const geometry::Point3& a, const geometry::Point3& b) {
  return std::hypot(a.x_mm - b.x_mm, a.y_mm - b.y_mm, a.z_mm - b.z_mm) <= tolerance_mm;
}

// The re-fed run follows the input run: each input move is the output's moves until one ends where it
// ends; those end on it (arcs: about its centre, in its direction).
void expect_same_path(const oracle::OracleRun& input, const oracle::OracleRun& output) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < input.moves.size(); ++i) {
    const OracleMove& in = input.moves[i];
    SCOPED_TRACE("input move " + std::to_string(i));
    while (true) {
      ASSERT_LT(k, output.moves.size()) << "the re-fed program ends early";
      const OracleMove& out = output.moves[k++];
      EXPECT_EQ(out.kind, in.kind);
      EXPECT_LE(distance_to_move(in, out.end), tolerance_mm);
      if (in.kind == geometry::MoveKind::kArc) {
        EXPECT_LE(std::hypot(out.center.x_mm - in.center.x_mm, out.center.y_mm - in.center.y_mm), tolerance_mm);
        EXPECT_EQ(out.rotation > 0, in.rotation > 0);
      }
      if (same_point(out.end, in.end)) break;
    }
  }
  EXPECT_EQ(k, output.moves.size()) << "the re-fed program has moves the input does not";
}

class Refeed : public oracle::Rs274Test {
 protected:
  // Re-feeds `text` with made-up pieces and checks it against rs274 and the input's own lines.
  RefeedResult check(const std::string& text, double feed_step_mm_per_min) {
    std::vector<WrittenMove> written;
    const geometry::Program program = read_program(text, "test", {}, written);
    const bool inch = std::any_of(written.begin(), written.end(), [](const WrittenMove& w) { return w.inch; });
    tolerance_mm = kPathToleranceMm + (inch ? 2.0 * kInchPrintMm : 0.0);
    const std::vector<FeedPiece> pieces = made_up_pieces(program);
    const RefeedResult result = refeed_text(text, program, written, pieces);
    const oracle::OracleRun input = oracle::run_rs274_text(*rs274_, text);
    const oracle::OracleRun output = oracle::run_rs274_text(*rs274_, result.text);
    EXPECT_EQ(input.exit_code, 0) << input.messages;
    EXPECT_EQ(output.exit_code, 0) << output.messages << "\n" << result.text;
    expect_same_path(input, output);
    // Feeds: each output feed move runs its piece's feed, rounded down by less than one step.
    std::vector<double> expected;
    for (const FeedPiece& piece : pieces) {
      if (geometry::length_mm(piece.move) > 1e-6) expected.push_back(piece.feed_mm_per_min);
    }
    std::vector<double> ran;
    for (const OracleMove& m : output.moves) {
      if (m.kind != geometry::MoveKind::kRapid) ran.push_back(m.feed_mm_per_min);
    }
    if (std::none_of(written.begin(), written.end(), [](const WrittenMove& w) { return w.incremental; })) {
      EXPECT_EQ(ran.size(), expected.size());
      for (std::size_t k = 0; k < std::min(ran.size(), expected.size()); ++k) {
        EXPECT_LE(ran[k], expected[k] + 1e-6) << "piece " << k << ": never faster than planned";
        EXPECT_GT(ran[k], expected[k] - feed_step_mm_per_min - 1e-6) << "piece " << k;
      }
    }
    // Every line that is not a feed move's comes through as it was, in order.
    std::vector<bool> feed_line(lines_of(text).size() + 1, false);
    for (std::size_t m = 0; m < written.size(); ++m) feed_line[static_cast<std::size_t>(written[m].line)] = written[m].motion != 0;
    const std::vector<std::string> in_lines = lines_of(text), out_lines = lines_of(result.text);
    std::size_t at = 0;
    for (std::size_t i = 0; i < in_lines.size(); ++i) {
      if (feed_line[i + 1]) continue;
      const auto found = std::find(out_lines.begin() + static_cast<long>(at), out_lines.end(), in_lines[i]);
      EXPECT_NE(found, out_lines.end()) << "line " << i + 1 << " '" << in_lines[i] << "' is not in the output";
      if (found != out_lines.end()) at = static_cast<std::size_t>(found - out_lines.begin()) + 1;
    }
    return result;
  }
};

TEST_F(Refeed, FreeCadLinuxCncStyle) {
  const RefeedResult r = check(
      "(Exported by FreeCAD)\n"
      "(Post Processor: linuxcnc_post)\n"
      "G17 G54 G40 G49 G80 G90\n"
      "G21\n"
      "(begin operation: Pocket)\n"
      "M3 S2800\n"
      "G0 Z5.000\n"
      "G0 X-10.000 Y0.000\n"
      "G1 X-10.000 Y0.000 Z2.000 F600.000 (G1 as a rapid, above the stock)\n"
      "G1 X-10.000 Y0.000 Z-5.000 F100.000\n"
      "G1 X30.000 Y0.000 Z-5.000 F500.000\n"
      "G2 X40.000 Y10.000 Z-5.000 I0.000 J10.000 F500.000\n"
      "G3 X50.000 Y20.000 Z-5.000 I10.000 J0.000 F500.000\n"
      "G1 X70.000 Y20.000 Z-5.000 F500.000\n"
      "G0 Z5.000\n"
      "M5\n"
      "M2\n",
      0.1);
  EXPECT_GT(r.moves_split, 2);
  EXPECT_GT(r.lines_added, 4);
}

TEST_F(Refeed, FusionStyleRadiusArcsWithAHelicalEntryInInches) {
  check(
      "%\n"
      "O1001 (FUSION STYLE)\n"
      "N10 G90 G94 G17\n"
      "N15 G20\n"
      "N20 T1 M6\n"
      "N25 S9000 M3\n"
      "N30 G54\n"
      "N35 G0 X0.5 Y0.\n"
      "N40 G43 Z0.6 H1\n"
      "N45 G1 Z0.05 F20.\n"
      "N50 G3 X0. Y0.5 Z-0.05 R0.5 F15.\n"
      "N55 G3 X-0.5 Y0. Z-0.1 R0.5\n"
      "N60 G2 X0.5 Y0. R-0.5 F30.\n"
      "N65 G1 X1.5 F45.\n"
      "N70 G0 Z0.6\n"
      "N75 M5\n"
      "N80 M30\n"
      "%\n",
      0.001 * 25.4);
}

TEST_F(Refeed, AbsoluteCentresModalMotionSemicolonCommentsAndCrLf) {
  const RefeedResult r = check(
      "G21 G17 G90 G90.1 ; absolute arc centres\r\n"
      "S3000 M3\r\n"
      "G0 X0 Y0 Z1\r\n"
      "G1 Z-2 F80 ; plunge\r\n"
      "X20 F400\r\n"
      "G2 X30 Y-10 I20 J-10\r\n"
      "X20 Y-20 I20 J-10\r\n"
      "G1 X0 Y-20 ; back\r\n"
      "G0 Z5\r\n"
      "M2\r\n",
      0.1);
  EXPECT_NE(r.text.find("\r\n"), std::string::npos);
  EXPECT_EQ(r.text.find("\n\n"), std::string::npos);
  for (const std::string& line : lines_of(r.text)) EXPECT_TRUE(!line.empty() && line.back() == '\r') << line;
}

TEST_F(Refeed, IncrementalMovesRunAtTheirLowestFeedUnsplit) {
  const std::string text =
      "G21 G17 G90\n"
      "M3 S3000\n"
      "G0 X0 Y0 Z1\n"
      "G91\n"
      "G1 Z-3 F80\n"
      "G1 X20 F400\n"
      "G1 X10 Y10\n"
      "G90\n"
      "G0 Z5\n"
      "M2\n";
  const RefeedResult r = check(text, 0.1);
  EXPECT_EQ(r.moves_split, 0);
  EXPECT_EQ(r.lines_added, 0);
  EXPECT_GT(r.moves_at_lowest_feed, 0);
}

// The program read from `text` with its move `index` (an arc) cut into two moves of one line, as a line
// that carries several moves (a compensated corner, a linearised plane arc) is read.
geometry::Program with_move_in_two(const std::string& text, std::size_t index, std::vector<WrittenMove>& written) {
  geometry::Program program = read_program(text, "test", {}, written);
  const geometry::Move whole = program.path.moves.at(index);
  program.path.moves[index] = part_of(whole, 0.0, 0.5);
  program.path.moves.insert(program.path.moves.begin() + static_cast<long>(index) + 1, part_of(whole, 0.5, 1.0));
  program.blocks.insert(program.blocks.begin() + static_cast<long>(index) + 1, program.blocks[index]);
  written.insert(written.begin() + static_cast<long>(index) + 1, written[index]);
  return program;
}

using RefeedWholeLines = oracle::Rs274Test;

TEST_F(RefeedWholeLines, ALineOfSeveralMovesRunsAtTheLowestFeedOfAllTheirPieces) {
  const std::string text =
      "G21 G17 G90\n"
      "M3 S3000\n"
      "G0 X0 Y0 Z1\n"
      "G1 Z-1 F100\n"
      "G2 X10 Y0 I5 J0 F500 (half circle)\n"
      "G1 X20\n"
      "M2\n";
  std::vector<WrittenMove> written;
  const geometry::Program program = with_move_in_two(text, 2, written);
  ASSERT_EQ(program.path.moves.size(), 5U);
  ASSERT_EQ(written[2].line, 5);
  ASSERT_EQ(written[3].line, 5);
  std::vector<FeedPiece> pieces = {{1, program.path.moves[1], 90.0},
                                   {2, part_of(program.path.moves[2], 0.0, 0.5), 400.0},
                                   {2, part_of(program.path.moves[2], 0.5, 1.0), 350.0},
                                   {3, program.path.moves[3], 275.55},
                                   {4, program.path.moves[4], 600.0}};
  const RefeedResult r = refeed_text(text, program, written, pieces);
  const std::vector<std::string> out = lines_of(r.text);
  ASSERT_EQ(out.size(), 7U) << r.text;
  EXPECT_EQ(out[4], "G2 X10 Y0 I5 J0 F275.5 (half circle)");
  EXPECT_EQ(r.moves_split, 0);
  EXPECT_EQ(r.lines_added, 0);
  EXPECT_EQ(r.moves_at_lowest_feed, 2);
  const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, r.text);
  ASSERT_EQ(run.exit_code, 0) << run.messages;
  ASSERT_EQ(run.moves.size(), 4U);
  EXPECT_NEAR(run.moves[2].feed_mm_per_min, 275.5, 1e-6);
  EXPECT_NEAR(run.moves[3].feed_mm_per_min, 600.0, 1e-6);
}

TEST_F(RefeedWholeLines, AMoveToKeepWholeIsNotSplitAndAFixedFeedIsNotChanged) {
  const std::string text =
      "G20 G17 G90\n"
      "M3 S3000\n"
      "G0 X0 Y0 Z0.1\n"
      "G1 Z-0.1 F10\n"
      "G1 X1 F40\n"
      "G1 Y1\n"
      "M2\n";
  std::vector<WrittenMove> written;
  const geometry::Program program = read_program(text, "test", {}, written);
  ASSERT_EQ(program.path.moves.size(), 4U);
  written[2].keep_whole = true;
  written[1].fixed_feed = true;
  const std::vector<FeedPiece> pieces = {{2, part_of(program.path.moves[2], 0.0, 0.3), 30.0 * 25.4},
                                         {2, part_of(program.path.moves[2], 0.3, 1.0), 20.0 * 25.4},
                                         {3, program.path.moves[3], 50.0 * 25.4}};
  const RefeedResult r = refeed_text(text, program, written, pieces);
  const std::vector<std::string> out = lines_of(r.text);
  ASSERT_EQ(out.size(), 7U) << r.text;
  EXPECT_EQ(out[3], "G1 Z-0.1 F10") << "a fixed feed stays as written";
  EXPECT_EQ(out[4], "G1 X1 F20.");
  EXPECT_EQ(out[5], "G1 Y1 F50.");
  EXPECT_EQ(r.moves_at_lowest_feed, 1);
  const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, r.text);
  ASSERT_EQ(run.exit_code, 0) << run.messages;
  ASSERT_EQ(run.moves.size(), 4U);
  EXPECT_NEAR(run.moves[1].feed_mm_per_min, 10.0 * 25.4, 1e-6);
  EXPECT_NEAR(run.moves[2].feed_mm_per_min, 20.0 * 25.4, 1e-6);
  EXPECT_NEAR(run.moves[3].feed_mm_per_min, 50.0 * 25.4, 1e-6);

  EXPECT_THROW(refeed_text(text, program, written, {{1, program.path.moves[1], 100.0}}), std::invalid_argument)
      << "a feed for a move whose feed is fixed";
}

TEST_F(RefeedWholeLines, ADrillingCycleLineStaysAsWrittenAndItsMovesTakeNoPieces) {
  const std::string text =
      "G21 G17 G90\n"
      "M3 S3000\n"
      "G0 X0 Y0 Z10\n"
      "G99 G83 X5 Y5 Z-10 R2 Q4 F100\n"
      "X15\n"
      "G80\n"
      "G1 X30 F300\n"
      "M2\n";
  std::vector<WrittenMove> written;
  const geometry::Program program = read_program(text, "test", {}, written);
  std::vector<FeedPiece> pieces;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    if (program.path.moves[i].kind == geometry::MoveKind::kRapid) continue;
    if (written[i].fixed_feed) {
      EXPECT_THROW(refeed_text(text, program, written, {{static_cast<int>(i), program.path.moves[i], 50.0}}),
                   std::invalid_argument);
      continue;
    }
    pieces.push_back({static_cast<int>(i), program.path.moves[i], 250.0});
  }
  ASSERT_EQ(pieces.size(), 1U) << "only the G1 is free";
  const RefeedResult r = refeed_text(text, program, written, pieces);
  const std::vector<std::string> out = lines_of(r.text);
  ASSERT_EQ(out.size(), 8U);
  EXPECT_EQ(out[3], "G99 G83 X5 Y5 Z-10 R2 Q4 F100");
  EXPECT_EQ(out[4], "X15");
  EXPECT_EQ(out[6], "G1 X30 F250.");
  const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, r.text);
  ASSERT_EQ(run.exit_code, 0) << run.messages;
  EXPECT_NEAR(run.moves.back().feed_mm_per_min, 250.0, 1e-6);
  EXPECT_NEAR(run.moves[run.moves.size() - 2].end.z_mm, 2.0, 1e-9) << "the second hole ends at R (G99)";
}

TEST(RefeedPieces, PiecesThatAreNotTheProgramsAreRefused) {
  std::vector<WrittenMove> written;
  const std::string text = "G21 G90\nM3 S1000\nG0 X1 Y0 Z5\nG1 X10 F100\nM2\n";
  const geometry::Program program = read_program(text, "test", {}, written);
  EXPECT_THROW(refeed_text(text, program, written, {{5, program.path.moves[1], 100.0}}), std::invalid_argument);
  EXPECT_THROW(refeed_text(text, program, written, {{0, program.path.moves[0], 100.0}}), std::invalid_argument)
      << "a feed for a rapid";
  EXPECT_THROW(refeed_text(text, program, written, {{1, program.path.moves[1], 0.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace feedplan::gcode
