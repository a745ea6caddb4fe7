// A real hand-written Haas program (../shared/cam/handwritten_nims_mill_hp_4.ngc: a profile and a slot
// with G41 D01 / D02, G81/G83 drilling with G99, G28, G53 retracts, M31/M33, O1001, five tools) read
// whole, as `feedplan optimize` reads it (tool changes anywhere, the end mills' diameters given); and its
// feed moves against LinuxCNC's: rs274 runs the same text with a tool table of the same diameters, less
// what it refuses (M31 and M33, which it does not know, and the P on G81, which it refuses), and every
// feed move — compensated profile, slot, drilling — must agree to 1 µm plus half of rs274's printed digit.
// G28 and G53 are not compared: rs274 goes to machine positions the reader does not know (it parks).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "rs274_runner.hpp"

namespace feedplan::gcode {
namespace {

namespace fs = std::filesystem;
using geometry::MoveKind;

constexpr double kToleranceMm = 1e-3 + 0.5 * 0.0001 * 25.4 * 1.7320508;  // 1 µm and half an inch digit

// ../shared/cam beside the repository, when it is there.
const fs::path kProgram =
    fs::path(FEEDPLAN_TEST_DATA_DIR) / ".." / ".." / ".." / "shared" / "cam" / "handwritten_nims_mill_hp_4.ngc";

std::string text_of(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `text` without what rs274 refuses: the lines M31 and M33, the P of the G81 line.
std::string as_linuxcnc_reads_it(const std::string& text) {
  std::stringstream in(text);
  std::string out;
  std::string line;
  while (std::getline(in, line)) {
    if (line == "M31" || line == "M33") line.clear();
    if (line.rfind("G81", 0) == 0) {
      const std::size_t p = line.find(" P0.5");
      if (p != std::string::npos) line.erase(p, 5);
    }
    out += line + "\n";
  }
  return out;
}

ReaderOptions haas_options() {
  ReaderOptions options;
  options.tool_changes = true;
  options.tool_diameters_mm = {{1, 12.7}, {2, 9.525}};
  return options;
}

class HaasProgram : public oracle::Rs274Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kProgram)) GTEST_SKIP() << kProgram << " is absent (../shared/cam beside the repository): the Haas program test is not run";
    oracle::Rs274Test::SetUp();
  }
};

TEST_F(HaasProgram, ReadsWholeWithTheEndMillsDiameters) {
  std::vector<WrittenMove> written;
  geometry::Program program;
  try {
    program = read_program(text_of(kProgram), kProgram.string(), haas_options(), written);
  } catch (const InputError& error) {
    FAIL() << error.what();
  }
  EXPECT_TRUE(geometry::consistency_defects(program.path).empty());
  auto noted = [&](const std::string& part) {
    for (const std::string& n : program.notes) {
      if (n.find(part) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(noted("moves to machine positions (G28, G30, G53) were read as retracts above the part"));
  EXPECT_TRUE(noted("4 holes of drilling cycles"));
  EXPECT_TRUE(noted("P0.5 on G81 is ignored"));
  // Tools 5, 7, 8 drill without compensation: no diameter needed. Without the end mills' diameters the
  // reader says which is missing.
  ReaderOptions without = haas_options();
  without.tool_diameters_mm.erase(2);
  try {
    read_program(text_of(kProgram), "hp4", without);
    ADD_FAILURE() << "read without the diameter of tool 2";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("word D02: cutter compensation needs the diameter of tool 2"), std::string::npos)
        << error.what();
  }
}

TEST_F(HaasProgram, FeedMovesMatchLinuxCnc) {
  const std::string text = text_of(kProgram);
  const geometry::Program ours = read_program(text, kProgram.string(), haas_options());
  const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, as_linuxcnc_reads_it(text),
                                                       "T1 P1 D0.5\nT2 P2 D0.375\nT5 P5 D0.25\nT7 P7 D0.25\nT8 P8 D0.3125\n");
  ASSERT_EQ(run.exit_code, 0) << run.messages;
  std::vector<std::size_t> our_feeds;
  for (std::size_t i = 0; i < ours.path.moves.size(); ++i) {
    if (ours.path.moves[i].kind != MoveKind::kRapid) our_feeds.push_back(i);
  }
  std::vector<const oracle::OracleMove*> their_feeds;
  for (const oracle::OracleMove& m : run.moves) {
    if (m.kind != MoveKind::kRapid) their_feeds.push_back(&m);
  }
  ASSERT_EQ(our_feeds.size(), their_feeds.size());
  ASSERT_GT(our_feeds.size(), 60U);
  for (std::size_t k = 0; k < our_feeds.size(); ++k) {
    const geometry::Move& m = ours.path.moves[our_feeds[k]];
    const oracle::OracleMove& o = *their_feeds[k];
    SCOPED_TRACE("feed move " + std::to_string(k) + " (line " + std::to_string(ours.blocks[our_feeds[k]].source_line) + ")");
    EXPECT_EQ(m.kind, o.kind);
    EXPECT_LE(std::hypot(std::hypot(m.end.x_mm - o.end.x_mm, m.end.y_mm - o.end.y_mm), m.end.z_mm - o.end.z_mm), kToleranceMm);
    if (m.kind == MoveKind::kArc && o.kind == MoveKind::kArc) {
      EXPECT_LE(std::hypot(m.center.x_mm - o.center.x_mm, m.center.y_mm - o.center.y_mm), kToleranceMm);
      EXPECT_EQ(m.ccw, o.rotation > 0);
    }
    EXPECT_NEAR(ours.blocks[our_feeds[k]].feed_mm_per_min, o.feed_mm_per_min, 0.01);
  }
}

// The end points of rs274's moves (the path), rapids and feeds alike.
std::vector<geometry::Point3> ends_of(const oracle::OracleRun& run) {
  std::vector<geometry::Point3> ends;
  for (const oracle::OracleMove& m : run.moves) ends.push_back(m.end);
  return ends;
}

TEST_F(HaasProgram, RefedWithSeveralMovesPerLineItRunsTheSamePathAtItsLinesLowestFeeds) {
  const std::string text = text_of(kProgram);
  std::vector<WrittenMove> written;
  const geometry::Program program = read_program(text, kProgram.string(), haas_options(), written);
  // Made-up feeds: 1 to 3 pieces per free feed move; none for rapids and the drilling cycles' fixed feeds.
  std::vector<FeedPiece> pieces;
  std::map<int, double> lowest_by_line;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    const geometry::Move& m = program.path.moves[i];
    if (m.kind == MoveKind::kRapid || written[i].fixed_feed) continue;
    const int count = m.kind == MoveKind::kArc ? 1 : 1 + static_cast<int>(i % 3);
    for (int k = 0; k < count; ++k) {
      geometry::Move piece = m;
      const double f0 = static_cast<double>(k) / count, f1 = static_cast<double>(k + 1) / count;
      piece.start = geometry::point_at(m, f0);
      piece.end = k + 1 == count ? m.end : geometry::point_at(m, f1);
      const double feed = 500.0 + 37.0 * static_cast<double>(i % 11) + 13.0 * k;
      pieces.push_back({static_cast<int>(i), piece, feed});
      auto [it, fresh] = lowest_by_line.emplace(written[i].line, feed);
      if (!fresh) it->second = std::min(it->second, feed);
    }
  }
  const RefeedResult r = refeed_text(text, program, written, pieces);
  EXPECT_GT(r.moves_at_lowest_feed, 10) << "compensated lines carry corner arcs and their moves";
  // Every line of several moves keeps its words; only its F changes, to the lowest feed (in/min, rounded down).
  std::map<int, int> moves_per_line;
  for (const WrittenMove& w : written) ++moves_per_line[w.line];
  const std::string input = as_linuxcnc_reads_it(text), output = as_linuxcnc_reads_it(r.text);
  const oracle::OracleRun before = oracle::run_rs274_text(*rs274_, input, "T1 P1 D0.5\nT2 P2 D0.375\nT5 P5 D0.25\nT7 P7 D0.25\nT8 P8 D0.3125\n");
  const oracle::OracleRun after = oracle::run_rs274_text(*rs274_, output, "T1 P1 D0.5\nT2 P2 D0.375\nT5 P5 D0.25\nT7 P7 D0.25\nT8 P8 D0.3125\n");
  ASSERT_EQ(before.exit_code, 0) << before.messages;
  ASSERT_EQ(after.exit_code, 0) << after.messages << "\n" << r.text;
  // The same path: every point rs274 reaches before is reached after, in order (splits add points between).
  const std::vector<geometry::Point3> a = ends_of(before), b = ends_of(after);
  std::size_t k = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    while (k < b.size() && std::hypot(std::hypot(b[k].x_mm - a[i].x_mm, b[k].y_mm - a[i].y_mm), b[k].z_mm - a[i].z_mm) > kToleranceMm) ++k;
    ASSERT_LT(k, b.size()) << "point " << i << " of the input's path is not on the re-fed path";
    ++k;
  }
  // The compensated profile's corner arcs run at the lowest feed of their line.
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    if (moves_per_line[written[i].line] < 2 || written[i].fixed_feed) continue;
    const double lowest = lowest_by_line[written[i].line];
    bool found = false;
    for (const oracle::OracleMove& m : after.moves) {
      if (m.kind == MoveKind::kRapid) continue;
      if (std::hypot(m.end.x_mm - program.path.moves[i].end.x_mm, m.end.y_mm - program.path.moves[i].end.y_mm) <= kToleranceMm &&
          std::abs(m.end.z_mm - program.path.moves[i].end.z_mm) <= kToleranceMm) {
        EXPECT_LE(m.feed_mm_per_min, lowest + 1e-6) << "line " << written[i].line;
        EXPECT_GT(m.feed_mm_per_min, lowest - 0.001 * 25.4 - 1e-6) << "line " << written[i].line;
        found = true;
        break;
      }
    }
    EXPECT_TRUE(found) << "move " << i << " of line " << written[i].line;
  }
}

}  // namespace
}  // namespace feedplan::gcode
