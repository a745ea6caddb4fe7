// A real hand-written Haas program (/work/shared/cam/handwritten_nims_mill_hp_4.ngc: a profile and a slot
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
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "rs274_runner.hpp"

namespace feedplan::gcode {
namespace {

namespace fs = std::filesystem;
using geometry::MoveKind;

constexpr double kToleranceMm = 1e-3 + 0.5 * 0.0001 * 25.4 * 1.7320508;  // 1 µm and half an inch digit

const fs::path kProgram = "/work/shared/cam/handwritten_nims_mill_hp_4.ngc";

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
    if (!fs::exists(kProgram)) GTEST_SKIP() << kProgram << " is absent (/work/shared/cam): the Haas program test is not run";
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

}  // namespace
}  // namespace feedplan::gcode
