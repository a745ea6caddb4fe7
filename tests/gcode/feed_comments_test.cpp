// Feed comments (`--explain`) and part comments in the writer and the re-feed: the truth is LinuxCNC's
// interpreter (rs274) — the same moves and feeds as without them, the comments it reports in the order the
// test built them — and the text written without them.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/gcode/writer.hpp"
#include "program_builder.hpp"
#include "rs274_runner.hpp"
#include "text_lines.hpp"

namespace feedplan::gcode {
namespace {

using test_support::lines_of;
using testing_support::kPi;
using testing_support::ProgramBuilder;

// A rapid, two lines at F100 (the second in a new part: no F word, so no reason), a 270° arc at F200 (the
// writer makes two arcs of it: one F word), a line at F300, a rapid back in the first part.
geometry::Program parted_program() {
  ProgramBuilder b({0.0, 0.0, 5.0});
  b.spindle(2800.0, geometry::SpindleDirection::kClockwise);
  b.rapid({0.0, 0.0, 1.0}).line({0.0, 0.0, -1.0}, 100.0).line({10.0, 0.0, -1.0}, 100.0);
  b.arc({10.0, 5.0}, 1.5 * kPi, true, 0.0, 200.0).line({20.0, 20.0, -1.0}, 300.0).rapid({20.0, 20.0, 5.0});
  geometry::Program program = b.build();
  program.path.part_names = {"p0", "p1", "p2"};
  const std::vector<int> parts = {0, 0, 1, 1, 2, 0};
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) program.path.moves[i].part = parts[i];
  return program;
}

const std::vector<std::string> kReasons = {"", "plunge limit 0.025 mm/tooth", "force 300 N at 58 deg engagement",
                                           "acceleration (with (parens))", "air", ""};

// The comments rs274 reports that the options added, in order.
std::vector<std::string> added_comments(const oracle::OracleRun& run) {
  std::vector<std::string> added;
  for (const std::string& c : run.comments) {
    if (c.rfind("F: ", 0) == 0 || c.rfind("part: ", 0) == 0) added.push_back(c);
  }
  return added;
}

class WriterFeedComments : public oracle::Rs274Test {};

TEST_F(WriterFeedComments, EachFWordCarriesItsMovesReasonAndEachPartIsNamedOnce) {
  const geometry::Program program = parted_program();
  WriterOptions plain;
  WriterOptions commented;
  commented.feed_comments = kReasons;
  commented.part_comments = true;
  const std::string without = write_gcode(program, plain);
  const std::string with = write_gcode(program, commented);
  const oracle::OracleRun before = oracle::run_rs274_text(*rs274_, without);
  const oracle::OracleRun after = oracle::run_rs274_text(*rs274_, with);
  ASSERT_EQ(before.exit_code, 0) << before.messages;
  ASSERT_EQ(after.exit_code, 0) << after.messages << "\n" << with;
  EXPECT_EQ(after.feed_rates_mm_per_min, before.feed_rates_mm_per_min);
  ASSERT_EQ(after.moves.size(), before.moves.size());
  for (std::size_t i = 0; i < before.moves.size(); ++i) {
    EXPECT_EQ(after.moves[i].kind, before.moves[i].kind) << i;
    EXPECT_EQ(after.moves[i].feed_mm_per_min, before.moves[i].feed_mm_per_min) << i;
    EXPECT_EQ(after.moves[i].end.x_mm, before.moves[i].end.x_mm) << i;
    EXPECT_EQ(after.moves[i].end.y_mm, before.moves[i].end.y_mm) << i;
    EXPECT_EQ(after.moves[i].end.z_mm, before.moves[i].end.z_mm) << i;
  }
  EXPECT_EQ(added_comments(after),
            (std::vector<std::string>{"part: p0", "F: plunge limit 0.025 mm/tooth", "part: p1",
                                      "F: acceleration [with [parens]]", "part: p2", "F: air"}))
      << with;
  EXPECT_TRUE(added_comments(before).empty());
}

TEST(WriterFeedCommentsText, FanucAndHaasGetTheSameCommentsInUpperCaseAndNothingElseChanges) {
  const geometry::Program program = parted_program();
  for (const Dialect dialect : {Dialect::kLinuxCnc, Dialect::kFanuc, Dialect::kHaas}) {
    SCOPED_TRACE(to_string(dialect));
    WriterOptions plain;
    plain.dialect = dialect;
    WriterOptions commented = plain;
    commented.feed_comments = kReasons;
    commented.part_comments = true;
    const std::vector<std::string> without = lines_of(write_gcode(program, plain));
    std::vector<std::string> with = lines_of(write_gcode(program, commented));
    const bool iso = dialect != Dialect::kLinuxCnc;
    int feed_comments = 0;
    std::vector<std::string> kept;
    for (std::string line : with) {
      if (line.rfind(iso ? "(PART: " : "(part: ", 0) == 0) continue;
      const std::size_t at = line.find(" (F: ");
      if (at != std::string::npos) {
        ++feed_comments;
        EXPECT_EQ(line.back(), ')') << line;
        EXPECT_EQ(std::count(line.begin(), line.end(), '('), 1) << line;
        if (iso) {
          EXPECT_EQ(line.find_first_of("abcdefghijklmnopqrstuvwxyz"), std::string::npos) << line;
        }
        line.erase(at);
      }
      kept.push_back(line);
    }
    EXPECT_EQ(feed_comments, 3);
    EXPECT_EQ(kept, without);
  }
}

TEST(WriterFeedCommentsText, OneCommentPerMoveOrNone) {
  WriterOptions options;
  options.feed_comments = {"one"};
  try {
    write_gcode(parted_program(), options);
    FAIL() << "a feed comment list of the wrong size is refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("feed_comments"), std::string::npos) << e.what();
  }
}

// A program with a message, a semicolon comment and comments on both sides of a line's words.
const std::string kCommented =
    "G21 G90 G17\n"
    "G0 X0 Y0 Z1\n"
    "G1 Z-1 F100 (MSG, plunging)\n"
    "G1 X10 F200 ; a semicolon comment\n"
    "G1 (first) X20 F300 (second)\n"
    "G1 X30\n"
    "G1 (third) X40 F300\n"
    "M2\n";

// Every feed move but the last in two pieces, the second faster, each with a reason naming its move and piece;
// the last in one.
std::vector<FeedPiece> reasoned_pieces(const geometry::Program& program) {
  std::vector<FeedPiece> pieces;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    const geometry::Move& m = program.path.moves[i];
    if (m.kind == geometry::MoveKind::kRapid) continue;
    const int count = i + 1 == program.path.moves.size() ? 1 : 2;
    for (int k = 0; k < count; ++k) {
      geometry::Move piece = m;
      piece.start = geometry::point_at(m, static_cast<double>(k) / count);
      piece.end = k + 1 == count ? m.end : geometry::point_at(m, 0.5);
      pieces.push_back({static_cast<int>(i), piece, 400.0 + 100.0 * static_cast<double>(i) + 50.0 * k,
                        "move " + std::to_string(i) + " piece " + std::to_string(k)});
    }
  }
  return pieces;
}

class RefeedFeedComments : public oracle::Rs274Test {};

TEST_F(RefeedFeedComments, ReasonsGoBeforeTheLinesOwnCommentsAndChangeNothingElse) {
  std::vector<WrittenMove> written;
  const geometry::Program program = read_program(kCommented, "test", {}, written);
  std::vector<FeedPiece> pieces = reasoned_pieces(program);
  const std::string with = refeed_text(kCommented, program, written, pieces).text;
  for (FeedPiece& p : pieces) p.reason.clear();
  const std::string without = refeed_text(kCommented, program, written, pieces).text;
  // The message stays the line's last comment; the semicolon comment stays at the end; a reason goes before
  // the first comment of a line even when words follow it. Pieces after the first are new lines, with theirs.
  const auto line_with = [&](const std::string& part) {
    const std::vector<std::string> lines = lines_of(with);
    const auto it = std::find_if(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(part) != std::string::npos; });
    return it == lines.end() ? std::string() : *it;
  };
  EXPECT_NE(line_with("(MSG, plunging)").find(" (F: move 1 piece 0) (MSG, plunging)"), std::string::npos) << with;
  EXPECT_NE(line_with("; a semicolon comment").find(" (F: move 2 piece 0) ; a semicolon comment"), std::string::npos) << with;
  EXPECT_NE(line_with("(first)").find(" (F: move 3 piece 0) (first) (second)"), std::string::npos) << with;
  EXPECT_EQ(line_with("(third)").rfind("G1 (F: move 5 piece 0) (third) X40 F", 0), 0u) << with;
  for (const char* second : {"(F: move 1 piece 1)", "(F: move 2 piece 1)", "(F: move 3 piece 1)", "(F: move 4 piece 1)"}) {
    EXPECT_EQ(line_with(second).find(second) + std::string(second).size(), line_with(second).size()) << with;
  }
  const oracle::OracleRun before = oracle::run_rs274_text(*rs274_, without);
  const oracle::OracleRun after = oracle::run_rs274_text(*rs274_, with);
  ASSERT_EQ(before.exit_code, 0) << before.messages;
  ASSERT_EQ(after.exit_code, 0) << after.messages << "\n" << with;
  EXPECT_EQ(after.feed_rates_mm_per_min, before.feed_rates_mm_per_min);
  ASSERT_EQ(after.moves.size(), before.moves.size());
  for (std::size_t i = 0; i < before.moves.size(); ++i) {
    EXPECT_EQ(after.moves[i].end.x_mm, before.moves[i].end.x_mm) << i;
    EXPECT_EQ(after.moves[i].end.z_mm, before.moves[i].end.z_mm) << i;
    EXPECT_EQ(after.moves[i].feed_mm_per_min, before.moves[i].feed_mm_per_min) << i;
  }
  // LinuxCNC still shows the message and the lines' own last comments.
  EXPECT_EQ(std::count(after.calls.begin(), after.calls.end(), "MESSAGE"),
            std::count(before.calls.begin(), before.calls.end(), "MESSAGE"));
  EXPECT_EQ(std::count(after.calls.begin(), after.calls.end(), "MESSAGE"), 1);
  for (const std::string& c : before.comments) {
    EXPECT_NE(std::find(after.comments.begin(), after.comments.end(), c), after.comments.end()) << c;
  }
}

TEST(RefeedFeedCommentsText, UpperCaseWhenTheProgramsCommentsAre) {
  const std::string upper = "%\nO1000 (PART)\nG21 G90 G17\nG00 X0 Y0 Z1\nG01 Z-1 F100 (PLUNGE)\nG01 X10\nM30\n%\n";
  std::vector<WrittenMove> written;
  const geometry::Program program = read_program(upper, "test", {}, written);
  const std::string text = refeed_text(upper, program, written, reasoned_pieces(program)).text;
  EXPECT_NE(text.find("(F: MOVE 1 PIECE 0)"), std::string::npos) << text;
  EXPECT_EQ(text.find("(F: move"), std::string::npos) << text;
}

}  // namespace
}  // namespace feedplan::gcode
