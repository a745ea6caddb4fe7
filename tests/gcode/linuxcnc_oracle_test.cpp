// Oracle test (docs/method.md §7): the reader against LinuxCNC's own interpreter. `rs274 -g in.ngc out.txt`
// (Debian package linuxcnc-uspace) writes the canonical machining calls it would make —
// STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED, SET_FEED_RATE, DWELL, spindle calls — and exits 1 on a
// program it rejects. Every program in tests/data/gcode/ is read by both: the moves must agree (end
// points and arc centres within 1 µm, arc direction and turn count equal, swept angle within 1 µm
// of arc length, feed within 0.01 mm/min, spindle and dwells equal), and every program in
// tests/data/gcode/bad/ must be rejected by the reader — and by LinuxCNC, except where the table
// below records that feedplan refuses something LinuxCNC accepts.
//
// rs274 prints 4 decimals in the program's unit, so the test programs keep inch values exact to
// 4 decimals (0.0001 in = 2.54 µm would otherwise exceed the 1 µm budget by rounding alone).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
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
using geometry::Point3;
using oracle::OracleMove;
using oracle::OracleRun;
using oracle::oracle_sweep_rad;
using oracle::run_rs274;

constexpr double kTwoPi = oracle::kTwoPi;
constexpr double kPositionToleranceMm = 1e-3;
constexpr double kFeedToleranceMmPerMin = 0.01;

fs::path data_dir() { return fs::path(FEEDPLAN_TEST_DATA_DIR) / "gcode"; }

double distance_mm(const Point3& a, const Point3& b) {
  return std::hypot(std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm), b.z_mm - a.z_mm);
}

const char* kind_name(MoveKind kind) {
  switch (kind) {
    case MoveKind::kRapid: return "rapid";
    case MoveKind::kLine: return "line";
    case MoveKind::kArc: return "arc";
  }
  return "?";
}

using LinuxCncOracle = oracle::Rs274Test;

// --- Programs both must accept, move by move ---------------------------------------------------

class OracleAgreement : public LinuxCncOracle, public ::testing::WithParamInterface<const char*> {};

TEST_P(OracleAgreement, MovesFeedsAndSpindleMatchLinuxCnc) {
  const fs::path path = data_dir() / (std::string(GetParam()) + ".ngc");
  geometry::Program ours;
  try {
    ours = load_program(path);
  } catch (const InputError& error) {
    FAIL() << "the reader rejects " << path << ":\n" << error.what();
  }
  EXPECT_TRUE(geometry::consistency_defects(ours.path).empty());
  ASSERT_EQ(ours.blocks.size(), ours.path.moves.size());

  const OracleRun oracle = run_rs274(*rs274_, path);
  ASSERT_EQ(oracle.exit_code, 0) << "rs274 rejects " << path << ":\n" << oracle.messages;
  EXPECT_TRUE(oracle.oddities.empty()) << "canonical calls the comparison cannot follow:\n" << oracle.oddities.front();
  ASSERT_EQ(ours.path.moves.size(), oracle.moves.size()) << "moves read by feedplan vs by LinuxCNC";

  double worst_end_mm = 0.0;
  double worst_center_mm = 0.0;
  double worst_sweep_mm = 0.0;
  double worst_feed = 0.0;
  int arcs = 0;
  for (std::size_t i = 0; i < oracle.moves.size(); ++i) {
    const geometry::Move& m = ours.path.moves[i];
    const geometry::BlockCommand& b = ours.blocks[i];
    const OracleMove& o = oracle.moves[i];
    SCOPED_TRACE("move " + std::to_string(i) + " (" + kind_name(o.kind) + ", line " + std::to_string(b.source_line) +
                 " of " + path.filename().string() + ")");
    ASSERT_EQ(m.kind, o.kind);
    const double end_mm = distance_mm(m.end, o.end);
    worst_end_mm = std::max(worst_end_mm, end_mm);
    EXPECT_LE(end_mm, kPositionToleranceMm);
    EXPECT_EQ(m.cutting, o.kind != MoveKind::kRapid);
    if (o.kind == MoveKind::kArc) {
      ++arcs;
      const double center_mm = std::hypot(m.center.x_mm - o.center.x_mm, m.center.y_mm - o.center.y_mm);
      worst_center_mm = std::max(worst_center_mm, center_mm);
      EXPECT_LE(center_mm, kPositionToleranceMm);
      EXPECT_EQ(m.ccw, o.rotation > 0) << "ARC_FEED rotation " << o.rotation;
      const int our_turns = static_cast<int>(std::ceil(m.sweep_rad / kTwoPi - 1e-9));
      EXPECT_EQ(our_turns, std::abs(o.rotation)) << "sweep " << m.sweep_rad << " rad, ARC_FEED rotation " << o.rotation;
      const double sweep_mm = std::abs(m.sweep_rad - oracle_sweep_rad(o)) * geometry::arc_radius_mm(m);
      worst_sweep_mm = std::max(worst_sweep_mm, sweep_mm);
      EXPECT_LE(sweep_mm, kPositionToleranceMm) << "sweep " << m.sweep_rad << " vs " << oracle_sweep_rad(o);
    }
    const double feed = std::abs(b.feed_mm_per_min - o.feed_mm_per_min);
    worst_feed = std::max(worst_feed, feed);
    EXPECT_LE(feed, kFeedToleranceMmPerMin) << b.feed_mm_per_min << " vs " << o.feed_mm_per_min;
    EXPECT_NEAR(b.spindle_rpm, o.spindle_rpm, 1e-3);
    EXPECT_EQ(b.spindle, o.spindle);
    EXPECT_NEAR(b.dwell_before_s, o.dwell_before_s, 1e-4);
  }
  EXPECT_NEAR(ours.dwell_at_end_s, oracle.dwell_at_end_s, 1e-4);
  std::printf("[ oracle   ] %s: %zu moves (%d arcs) agree with rs274; largest deviations: end %.3g µm, centre "
              "%.3g µm, sweep %.3g µm of arc, feed %.3g mm/min\n",
              path.filename().c_str(), oracle.moves.size(), arcs, worst_end_mm * 1e3, worst_center_mm * 1e3,
              worst_sweep_mm * 1e3, worst_feed);
}

INSTANTIATE_TEST_SUITE_P(Programs, OracleAgreement,
                         ::testing::Values("lines", "arcs_ij", "arcs_r", "helix", "incremental", "inch", "trochoid",
                                           "format", "rounded_arcs"),
                         [](const ::testing::TestParamInfo<const char*>& info) { return std::string(info.param); });

// --- Programs the reader must reject -----------------------------------------------------------

struct BadProgram {
  const char* file;               // in tests/data/gcode/bad/
  const char* problem;            // a fragment of the reader's problem text
  bool linuxcnc_rejects = true;   // false: LinuxCNC accepts it, feedplan refuses it by choice
};

std::ostream& operator<<(std::ostream& out, const BadProgram& bad) { return out << bad.file; }

const std::vector<BadProgram>& bad_programs() {
  static const std::vector<BadProgram> programs = {
      {"unknown_word.ngc", "line 2: word Q5: not supported"},
      {"unknown_g_code.ngc", "line 2: word G12: not supported"},
      {"unknown_m_code.ngc", "line 2: word M100: not supported"},
      {"unknown_letter.ngc", "line 2: word L2: L is read only with drilling cycles"},
      {"feed_before_f.ngc", "line 3: G1 before any F word"},
      {"feed_zero.ngc", "line 2: G2 with F0 in effect"},
      {"feed_reset_by_g94.ngc", "line 4: G1 with no F since G94 on line 3"},
      {"feed_negative.ngc", "line 2: word F-5: a feed must be ≥ 0"},
      {"arc_radius_mismatch.ngc", "line 2: G3 I5.1: end point is 0.2 mm off the circle"},
      {"arc_r_too_short.ngc", "line 2: G2 R4: radius 4 mm is shorter than half the chord"},
      {"arc_r_full_circle.ngc", "line 2: G2 R5: start and end are the same point"},
      {"arc_zero_radius.ngc", "line 2: G2 I0 J0: zero radius"},
      {"arc_without_ijr.ngc", "line 2: G2 without I, J or R"},
      {"arc_r_and_ij.ngc", "line 2: word R5: R and I/J in one arc"},
      {"arc_k_word.ngc", "line 2: word K1: K is read only with G2 or G3"},
      {"arc_turns_zero.ngc", "line 2: word P0: the number of turns"},
      {"arc_turns_fraction.ngc", "line 2: word P1.5: the number of turns"},
      {"ij_without_arc.ngc", "line 2: word I5: I is read only with G2 or G3"},
      {"number_two_points.ngc", "line 2: word X1..2: \"1..2\" is not a number"},
      {"number_letters.ngc", "line 2: word X: needs a number after the letter, found \"ABC\""},
      {"number_missing.ngc", "line 2: word X: needs a number after the letter"},
      {"number_exponent.ngc", "line 2: word E3: not supported"},
      {"same_group_motion.ngc", "line 2: word G1: same modal group (motion) as G0"},
      {"same_group_distance.ngc", "line 2: word G91: same modal group (distance mode) as G90"},
      {"same_group_spindle.ngc", "line 2: word M5: same modal group (spindle) as M3"},
      {"repeated_letter.ngc", "line 2: word X2: a second X word"},
      {"repeated_feed.ngc", "line 1: word F200: a second F word"},
      {"comment_unclosed.ngc", "line 2: comment: '(' at column 7 is not closed"},
      {"comment_unopened.ngc", "line 2: comment: ')' at column 14 has no matching '('"},
      {"comment_nested.ngc", "line 2: comment: '(' at column 4 inside a comment"},
      {"missing_end.ngc", "line 2: end of text: the program ends without M2, M30 or a closing %"},
      {"axis_without_motion.ngc", "line 2: word X5: axis words need a motion mode"},
      {"axis_with_g80.ngc", "line 3: word X3: axis words cannot be used with G80"},
      {"dwell_negative.ngc", "line 2: word P-1: a G4 dwell must be ≥ 0 s"},
      {"dwell_without_p.ngc", "line 2: G4 without P"},
      {"dwell_with_arc.ngc", "line 2: word G4: not allowed with G2, G3 or G64"},
      {"line_number_not_first.ngc", "line 2: word N10: a line number must be the first word"},
      {"percent_not_opened.ngc", "line 3: '%': a closing % needs an opening %"},
      {"many_problems.ngc", "line 8: comment: '(' at column 7 is not closed"},
      {"plane_g18_j_word.ngc", "line 2: word J0: J is not read in the XZ plane (G18)"},
      // LinuxCNC accepts these; feedplan refuses them (reader.hpp says why).
      {"lathe_g7.ngc", "line 2: word G7: not supported (lathe diameter mode)", false},
      {"arc_radius_mismatch_small.ngc", "line 2: G3 I5.01: end point is 0.02 mm off the circle", false},
      {"tool_change.ngc", "line 3: word M6: not supported after the first move (tool change: the path is planned "
                          "for one tool", false},
      {"tool_change_second.ngc", "line 3: word M6: a second tool change (T1 M6 on line 2) is not supported", false},
      {"cutter_compensation.ngc", "line 2: word G41: no D word and no tool in the spindle", false},
      {"tool_length_offset.ngc", "line 3: word H2: G43 H2 is the length offset of tool 2, but tool 1 is in the "
                                 "spindle", false},
      {"inverse_time.ngc", "line 2: word G93: not supported (inverse-time feed", false},
      {"feed_per_revolution.ngc", "line 2: word G95: not supported (feed per revolution", false},
      {"units_change_with_f.ngc", "line 2: word F10: F in a block whose G20 changes the units", false},
      {"work_offset_after_move.ngc", "line 3: word G55: not supported after the first move", false},
      {"block_delete.ngc", "line 2: character '/': not supported (block delete", false},
      {"parameter.ngc", "line 2: character '#': not supported", false},
      {"rotary_axis.ngc", "line 2: word A3: not supported (rotary axes", false},
  };
  return programs;
}

class OracleRejection : public LinuxCncOracle, public ::testing::WithParamInterface<BadProgram> {};

TEST_P(OracleRejection, ReaderRejectsAndLinuxCncAgreesOrIsRecorded) {
  const BadProgram& bad = GetParam();
  const fs::path path = data_dir() / "bad" / bad.file;
  ASSERT_TRUE(fs::exists(path)) << path;
  try {
    load_program(path);
    ADD_FAILURE() << "the reader accepts " << path;
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(bad.problem), std::string::npos)
        << "expected \"" << bad.problem << "\" in:\n" << error.what();
  }
  const OracleRun oracle = run_rs274(*rs274_, path);
  if (bad.linuxcnc_rejects) {
    EXPECT_EQ(oracle.exit_code, 1) << "LinuxCNC accepts " << path << "; record it as a disagreement";
  } else {
    EXPECT_EQ(oracle.exit_code, 0) << "LinuxCNC now rejects " << path << " too:\n" << oracle.messages;
  }
}

INSTANTIATE_TEST_SUITE_P(Programs, OracleRejection, ::testing::ValuesIn(bad_programs()),
                         [](const ::testing::TestParamInfo<BadProgram>& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(OracleData, EveryBadProgramIsInTheTable) {
  std::set<std::string> listed;
  for (const BadProgram& bad : bad_programs()) listed.insert(bad.file);
  for (const auto& entry : fs::directory_iterator(data_dir() / "bad")) {
    EXPECT_EQ(listed.count(entry.path().filename().string()), 1u) << entry.path() << " is not in bad_programs()";
  }
}

}  // namespace
}  // namespace feedplan::gcode
