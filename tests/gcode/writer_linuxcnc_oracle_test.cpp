// Oracle test (docs/method.md §7): what the writer emits, run through LinuxCNC's interpreter (rs274) and
// read back with our reader, against the program it was written from.
//
// Programs: a hand-built one (lines, arcs both ways, a helix of 2.5 turns, a full circle, short moves,
// a feed change on nearly every move, rapids, dwells, spindle changes, coordinates that need
// rounding), the trochoid and spiral samples (samples/*.yaml through feedplan::cycles, each move with
// its own F = 800 + 37·i mod 2000), and a seeded random one; each in all three dialects, with default
// options and with busy ones (line numbers, coolant, retract, arcs split at 90°).
//
// Asserted for every move, after the approach rapids the writer puts first: rs274 accepts the program;
// its canonical end points and arc centres are within 1 µm of the program (arcs split into equal
// sub-arcs where the program's sweep exceeds max_arc_sweep_deg, computed here), arc direction and
// turn count are right, the sweep matches within 4 µm of arc length (rounding turns the end angles),
// every SET_FEED_RATE is a planned F and there is one per F change, spindle and dwells are the planned
// ones. Our reader reads the same moves: end points within 1 µm, same kind, direction and sweep,
// points inside each arc within 1.5 µm (the reader moves an arc's centre onto the bisector of its
// rounded ends, so its centre may differ more on short arcs while the path does not), the same F (to
// the 0.1 mm/min written), spindle and dwells.
//
// Fanuc writes a dwell as `G04 X<s>`, which LinuxCNC does not have; for Fanuc the test runs the text
// with that one form replaced by `G4 P<s>` (what Fanuc's X means). Nothing else is changed.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "program_builder.hpp"
#include "rs274_runner.hpp"

namespace feedplan::gcode {
namespace {

using geometry::Move;
using geometry::MoveKind;
using geometry::Point2;
using geometry::Point3;
using geometry::Program;
using geometry::SpindleDirection;
using oracle::OracleMove;
using oracle::OracleRun;
using testing_support::ExpectedMove;
using testing_support::kPi;
using testing_support::ProgramBuilder;

constexpr double kPositionToleranceMm = 1e-3;  // block ends and arc centres: 3 decimals round by ≤ 0.71 µm
// Points inside an arc: the circle through the rounded ends about the rounded (rs274) or re-centred
// (reader) centre; radial and tangential rounding add up to ~1.3 µm.
constexpr double kArcInteriorToleranceMm = 1.5e-3;
// Swept angle × radius: both ends move tangentially by up to 0.71 µm and the centre by up to 0.9 µm,
// which turns the angles at both ends — the writer accepts 4 last digits; a wrong turn count or
// direction is off by millimetres.
constexpr double kSweepToleranceMm = 4e-3;
constexpr double kFeedToleranceMmPerMin = 1e-4;  // rs274 prints 4 decimals; planned feeds have 1
constexpr unsigned kRandomSeed = 20240611;
constexpr int kRandomMoves = 400;

double distance_mm(const Point3& a, const Point3& b) {
  return std::hypot(std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm), b.z_mm - a.z_mm);
}

// --- The programs ---------------------------------------------------------------------------------

Program hand_built_program() {
  ProgramBuilder b({3.1234567, -7.7654321, 25});
  b.spindle(2800, SpindleDirection::kClockwise);
  b.rapid({3.1234567, -7.7654321, 2.0004});
  b.line({3.1234567, -7.7654321, -4.25}, 250.5);
  b.line({20.0005, -7.7654321, -4.25}, 1200);                           // rounds half away
  b.arc({20.0005, 2.2345679}, kPi / 2, true, 0, 950.3);                  // quarter, counter-clockwise
  b.arc({37.1, 2.2345679}, 1.5 * kPi, false, 0, 700);                    // three quarters, clockwise
  b.line({b.position().x_mm + 0.002, b.position().y_mm, -4.25}, 701);    // short moves
  b.line({b.position().x_mm + 0.002, b.position().y_mm + 0.001, -4.25}, 702);
  b.arc({b.position().x_mm, b.position().y_mm + 5.0}, 0.002, true, 0, 703);  // 0.01 mm of a 5 mm circle
  b.arc({b.position().x_mm - 0.5, b.position().y_mm}, 0.3, false, 0, 704);  // 0.15 mm of a 0.5 mm circle
  b.dwell(0.35).line({b.position().x_mm, b.position().y_mm, -6}, 120);
  b.arc({b.position().x_mm - 6.5, b.position().y_mm + 0.25}, 5 * kPi, true, -2.5, 333.3);  // helix, 2.5 turns
  b.arc({b.position().x_mm - 6.5, b.position().y_mm + 0.25}, 2 * kPi, false, 0, 444.4);    // full circle
  b.arc({b.position().x_mm + 3, b.position().y_mm - 4}, kPi * 190.0 / 180.0, true, 0, 555);  // > 180°: split
  b.arc({b.position().x_mm - 30, b.position().y_mm}, 0.25, false, 0.75, 1555);            // large radius
  b.spindle(3100, SpindleDirection::kClockwise).line({0, 0, -8.5}, 1999.9);
  b.spindle(3100, SpindleDirection::kCounterClockwise).arc({0, -1}, kPi / 3, true, 0, 10);
  for (int i = 0; i < 12; ++i) {  // a feed change on every move
    b.line({b.position().x_mm + 0.7, b.position().y_mm + (i % 2 == 0 ? 0.3 : -0.3), -8.5}, 400 + 50.1 * i);
  }
  b.spindle(0, SpindleDirection::kOff).rapid({b.position().x_mm, b.position().y_mm, 10});
  b.spindle(2800, SpindleDirection::kClockwise).rapid({-5, -5, 10}).line({-5, -5, 0}, 600);
  b.dwell_at_end(0.125);
  return b.build();
}

// A sample's path, each feed move with its own F = 800 + 37·i mod 2000, the spindle from the spec.
Program sample_program(const std::string& spec_file) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + spec_file);
  Program program;
  program.path = cycles::generate(spec).path;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    geometry::BlockCommand b;
    b.feed_mm_per_min = program.path.moves[i].kind == MoveKind::kRapid ? 0.0 : 800.0 + (37 * i) % 2000;
    b.spindle_rpm = spec.spindle_rpm;
    b.spindle = SpindleDirection::kClockwise;
    program.blocks.push_back(b);
  }
  return program;
}

// Seeded random lines, arcs and helices with coordinates that need rounding (seed printed).
Program random_program() {
  std::mt19937 random(kRandomSeed);
  auto uniform = [&random](double low, double high) { return std::uniform_real_distribution<double>(low, high)(random); };
  ProgramBuilder b({uniform(-50, 50), uniform(-50, 50), 10});
  b.spindle(4000, SpindleDirection::kClockwise);
  b.rapid({b.position().x_mm, b.position().y_mm, 1});
  for (int i = 0; i < kRandomMoves; ++i) {
    const double feed = std::round(uniform(10, 20000) * 10) / 10;
    if (i % 37 == 5) b.dwell(std::round(uniform(0.001, 2) * 1000) / 1000);
    const double kind = uniform(0, 1);
    const Point3 p = b.position();
    if (kind < 0.3) {
      const double length = std::exp(uniform(std::log(0.01), std::log(30)));
      const double direction = uniform(0, 2 * kPi);
      b.line({p.x_mm + length * std::cos(direction), p.y_mm + length * std::sin(direction),
              p.z_mm + (uniform(0, 1) < 0.3 ? uniform(-2, 2) : 0.0)},
             feed);
    } else if (kind < 0.35) {
      b.rapid({p.x_mm + uniform(-20, 20), p.y_mm + uniform(-20, 20), p.z_mm + uniform(-1, 1)});
    } else {
      const double radius = std::exp(uniform(std::log(0.05), std::log(40)));
      const double direction = uniform(0, 2 * kPi);
      const double min_sweep = 0.01 / radius;
      const double sweep = uniform(0, 1) < 0.15 ? uniform(2 * kPi, 6 * kPi) : uniform(std::min(min_sweep, 1.0), 2 * kPi);
      const double dz = uniform(0, 1) < 0.3 ? uniform(-3, 3) : 0.0;
      b.arc({p.x_mm + radius * std::cos(direction), p.y_mm + radius * std::sin(direction)}, sweep, uniform(0, 1) < 0.5,
            dz, feed);
    }
    const Point3 q = b.position();
    if (std::abs(q.x_mm) > 400 || std::abs(q.y_mm) > 400 || std::abs(q.z_mm) > 100) {
      b.rapid({0, 0, q.z_mm});
    }
  }
  return b.build();
}

struct Case {
  const char* name;
  std::function<Program()> program;
  Dialect dialect;
  bool busy = false;  // line numbers, coolant, retract, tool 3, arcs split at 90°
};

std::ostream& operator<<(std::ostream& out, const Case& c) { return out << c.name; }

std::vector<Case> cases() {
  std::vector<Case> all;
  const std::vector<std::pair<const char*, std::function<Program()>>> programs = {
      {"hand_built", hand_built_program},
      {"trochoid", [] { return sample_program("trochoid.yaml"); }},
      {"spiral", [] { return sample_program("spiral.yaml"); }},
      {"random", random_program},
  };
  for (const auto& [name, make] : programs) {
    for (Dialect dialect : {Dialect::kLinuxCnc, Dialect::kFanuc, Dialect::kHaas}) {
      all.push_back({name, make, dialect, false});
      if (std::string(name) == "hand_built" || std::string(name) == "random") all.push_back({name, make, dialect, true});
    }
  }
  return all;
}

std::string case_name(const Case& c) {
  return std::string(c.name) + "_" + to_string(c.dialect) + (c.busy ? "_busy" : "");
}

WriterOptions options_for(const Case& c) {
  WriterOptions options;
  options.dialect = c.dialect;
  options.program_name = c.name;
  options.header_comments = {{"case", case_name(c)}};
  if (c.busy) {
    options.line_numbers = true;
    options.line_number_step = 7;
    options.coolant = true;
    options.retract_z_mm = 30.0;
    options.tool_number = 3;  // rs274's own tool table has tools 1 to 3
    options.max_arc_sweep_deg = 90.0;
  }
  return options;
}

// The text as LinuxCNC can run it: Fanuc's dwell form `G04 X<s>` becomes `G4 P<s>`.
std::string runnable_on_linuxcnc(const std::string& text, Dialect dialect) {
  return dialect == Dialect::kFanuc ? oracle::fanuc_dwell_as_linuxcnc(text) : text;
}

// The retract rapid the writer adds at the end, if any: to retract_z_mm when the program ends below.
std::optional<Point3> retract_of(const Program& program, const WriterOptions& options) {
  const Point3 end = program.path.moves.back().end;
  if (!options.retract_z_mm || std::round(end.z_mm * 1000) >= std::round(*options.retract_z_mm * 1000)) return std::nullopt;
  return Point3{end.x_mm, end.y_mm, *options.retract_z_mm};
}

// Where the tool is when the safe return starts: after the retract, else at the program's end.
Point3 before_safe_return(const Program& program, const std::optional<Point3>& retract) {
  return retract ? *retract : program.path.moves.back().end;
}

// The safe return as rs274 runs it: `G53 G0 Z0.` (LinuxCNC) goes to machine Z 0, `G91 G28 Z0.` (Fanuc,
// Haas) through the point it is at to the G28 position, parameters 5161–5163, machine zero in rs274.
// Machine Z 0 in the program's coordinates is minus the Z offsets rs274 reports in effect (`last`, its
// last move's): the work offset and G92 (0 in rs274) and the tool length (G43 H: its built-in tool table
// gives tool 1 12.9794 mm, tool 3 32.3342 mm), so the tool tip ends below work Z 0. X and Y stay.
// Nothing when the tool is there already (rs274 reports no move of no length).
std::optional<Point3> oracle_safe_return(const Point3& from, const OracleMove& last) {
  const double machine_zero_z_mm = -(last.origin_z_mm + last.tool_length_z_mm);
  if (std::abs(from.z_mm - machine_zero_z_mm) < 1e-7) return std::nullopt;
  return Point3{from.x_mm, from.y_mm, machine_zero_z_mm};
}

// The safe return as our reader reads it (reader.hpp, G28/G30/G53): a park, a rapid straight up to the
// highest Z the tool reached before it plus 25 mm — of the reader's initial position (Z 0), the approach
// (which ends at the program's start), the program's moves and the retract. Never nothing: the tool is
// always below that.
Point3 reader_park(const std::vector<ExpectedMove>& expected, const Point3& from) {
  double highest_z_mm = std::max(0.0, expected.front().move.start.z_mm);
  for (const ExpectedMove& e : expected) highest_z_mm = std::max(highest_z_mm, e.move.end.z_mm);
  highest_z_mm = std::max(highest_z_mm, from.z_mm);
  return {from.x_mm, from.y_mm, highest_z_mm + 25.0};
}

// How many of `moves` come before the program's own: the approach rapids (at most two, the last
// ending at the program's start). Checks the rapids the writer adds after them — `trailing`: the retract
// when there is one, then the safe return where it takes the tool (none: no safe return, or one of no
// length) — against the ends given.
template <typename ReadMove>
std::size_t approach_count(const std::vector<ReadMove>& moves, std::size_t expected, const Point3& start,
                           const std::vector<Point3>& trailing) {
  const std::size_t own = expected + trailing.size();
  EXPECT_GE(moves.size(), own);
  EXPECT_LE(moves.size(), own + 2) << "more moves than the program, its approach, retract and safe return";
  if (moves.size() < own || moves.size() > own + 2) return 0;
  const std::size_t k = moves.size() - own;
  for (std::size_t i = 0; i < k; ++i) EXPECT_EQ(moves[i].kind, MoveKind::kRapid) << "approach move " << i;
  if (k > 0) {
    EXPECT_LE(distance_mm(moves[k - 1].end, start), kPositionToleranceMm);
  }
  for (std::size_t t = 0; t < trailing.size(); ++t) {
    const ReadMove& m = moves[k + expected + t];
    EXPECT_EQ(m.kind, MoveKind::kRapid) << "trailing move " << t << " (retract or safe return)";
    EXPECT_LE(distance_mm(m.start, t == 0 ? moves[k + expected - 1].end : trailing[t - 1]), kPositionToleranceMm)
        << "trailing move " << t << " starts where the tool is";
    EXPECT_LE(distance_mm(m.end, trailing[t]), kPositionToleranceMm) << "trailing move " << t << " (retract or safe return)";
  }
  return k;
}

// `trailing` with `last` appended when there is one.
std::vector<Point3> with(std::vector<Point3> trailing, const std::optional<Point3>& last) {
  if (last) trailing.push_back(*last);
  return trailing;
}

// Turn count ARC_FEED reports for a sweep: ⌈sweep / 2π⌉.
int turns_of(double sweep_rad) { return static_cast<int>(std::ceil(sweep_rad / (2 * kPi) - 1e-9)); }

class WriterOracle : public oracle::Rs274Test, public ::testing::WithParamInterface<Case> {};

TEST_P(WriterOracle, LinuxCncAndOurReaderRunTheProgramAsPlanned) {
  const Case& c = GetParam();
  const Program program = c.program();
  if (std::string(c.name) == "random") {
    std::printf("[ random   ] %d moves, seed %u (kRandomSeed in %s)\n", kRandomMoves, kRandomSeed, __FILE__);
  }
  const WriterOptions options = options_for(c);
  const std::string text = write_gcode(program, options);
  const std::string runnable = runnable_on_linuxcnc(text, c.dialect);
  const std::vector<ExpectedMove> expected = testing_support::expected_moves(program, options.max_arc_sweep_deg);
  const Point3 start = program.path.moves.front().start;
  const std::optional<Point3> retract = retract_of(program, options);
  const std::vector<Point3> retracts = with({}, retract);
  const Point3 returning_from = before_safe_return(program, retract);

  // --- LinuxCNC --------------------------------------------------------------------------------
  const OracleRun run = oracle::run_rs274_text(*rs274_, runnable);
  ASSERT_EQ(run.exit_code, 0) << "rs274 rejects the " << case_name(c) << " program:\n" << run.messages;
  EXPECT_TRUE(run.oddities.empty()) << run.oddities.front();
  ASSERT_FALSE(run.moves.empty());
  const std::vector<Point3> oracle_trailing = with(retracts, oracle_safe_return(returning_from, run.moves.back()));
  ASSERT_EQ(oracle_trailing.size(), retracts.size() + 1) << "rs274 runs the safe return";
  const std::size_t k = approach_count(run.moves, expected.size(), start, oracle_trailing);
  ASSERT_EQ(run.moves.size(), expected.size() + k + oracle_trailing.size());
  double worst_end = 0.0;
  double worst_center = 0.0;
  double worst_sweep = 0.0;
  int feed_changes = 0;
  std::optional<double> last_feed;
  for (std::size_t j = 0; j < expected.size(); ++j) {
    const Move& m = expected[j].move;
    const geometry::BlockCommand& b = program.blocks[expected[j].program_move];
    const OracleMove& o = run.moves[k + j];
    SCOPED_TRACE("rs274, program move " + std::to_string(expected[j].program_move) + ", written move " +
                 std::to_string(j));
    ASSERT_EQ(o.kind, m.kind);
    worst_end = std::max(worst_end, distance_mm(o.end, m.end));
    EXPECT_LE(distance_mm(o.end, m.end), kPositionToleranceMm);
    if (m.kind == MoveKind::kArc) {
      const double center = std::hypot(o.center.x_mm - m.center.x_mm, o.center.y_mm - m.center.y_mm);
      worst_center = std::max(worst_center, center);
      EXPECT_LE(center, kPositionToleranceMm);
      EXPECT_EQ(o.rotation > 0, m.ccw) << "ARC_FEED rotation " << o.rotation;
      EXPECT_EQ(std::abs(o.rotation), turns_of(m.sweep_rad));
      const double sweep_mm = std::abs(oracle::oracle_sweep_rad(o) - m.sweep_rad) * geometry::arc_radius_mm(m);
      worst_sweep = std::max(worst_sweep, sweep_mm);
      EXPECT_LE(sweep_mm, kSweepToleranceMm);
    }
    if (m.kind != MoveKind::kRapid) {
      EXPECT_NEAR(o.feed_mm_per_min, b.feed_mm_per_min, kFeedToleranceMmPerMin);
      if (!last_feed || *last_feed != b.feed_mm_per_min) ++feed_changes;
      last_feed = b.feed_mm_per_min;
    }
    if (b.spindle != SpindleDirection::kOff) {
      EXPECT_EQ(o.spindle_rpm, std::round(b.spindle_rpm));
    }
    EXPECT_EQ(o.spindle, b.spindle);
    const bool first_piece = j == 0 || expected[j - 1].program_move != expected[j].program_move;
    EXPECT_NEAR(o.dwell_before_s, first_piece ? b.dwell_before_s : 0.0, 1e-4);
  }
  // The end dwell comes before the retract and the safe return.
  EXPECT_NEAR(run.moves[k + expected.size()].dwell_before_s, program.dwell_at_end_s, 1e-4);
  EXPECT_NEAR(run.dwell_at_end_s, 0.0, 1e-9);
  std::vector<double> set_feeds;
  for (double f : run.feed_rates_mm_per_min) {
    if (f != 0.0) set_feeds.push_back(f);  // G94 and the program end set F0
  }
  EXPECT_EQ(static_cast<int>(set_feeds.size()), feed_changes) << "one SET_FEED_RATE per F change";
  std::set<double> planned;
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    if (program.path.moves[i].kind != MoveKind::kRapid) planned.insert(program.blocks[i].feed_mm_per_min);
  }
  for (double f : set_feeds) {
    const auto it = planned.lower_bound(f - kFeedToleranceMmPerMin);
    EXPECT_TRUE(it != planned.end() && std::abs(*it - f) <= kFeedToleranceMmPerMin) << "SET_FEED_RATE(" << f << ")";
  }

  // --- Our reader -------------------------------------------------------------------------------
  Program back;
  try {
    back = read_program(runnable, case_name(c));
  } catch (const InputError& error) {
    FAIL() << "our reader rejects the " << case_name(c) << " program:\n" << error.what();
  }
  const std::vector<Point3> read_trailing = with(retracts, reader_park(expected, returning_from));
  const std::size_t kr = approach_count(back.path.moves, expected.size(), start, read_trailing);
  ASSERT_EQ(back.path.moves.size(), expected.size() + kr + read_trailing.size());
  EXPECT_FALSE(back.path.moves.back().cutting) << "the park cuts nothing";
  for (const std::string& note : back.notes) EXPECT_EQ(note.find("machine position"), std::string::npos) << note;
  double worst_read = 0.0;
  for (std::size_t j = 0; j < expected.size(); ++j) {
    const Move& m = expected[j].move;
    const geometry::BlockCommand& b = program.blocks[expected[j].program_move];
    const Move& r = back.path.moves[kr + j];
    const geometry::BlockCommand& rb = back.blocks[kr + j];
    SCOPED_TRACE("reader, program move " + std::to_string(expected[j].program_move) + ", written move " +
                 std::to_string(j));
    ASSERT_EQ(r.kind, m.kind);
    for (double fraction : {0.25, 0.5, 0.75, 1.0}) {
      if (m.kind != MoveKind::kArc && fraction < 1.0) continue;
      const double d = distance_mm(geometry::point_at(r, fraction), geometry::point_at(m, fraction));
      worst_read = std::max(worst_read, d);
      EXPECT_LE(d, fraction < 1.0 ? kArcInteriorToleranceMm : kPositionToleranceMm) << "at " << fraction << " of the move";
    }
    if (m.kind == MoveKind::kArc) {
      EXPECT_EQ(r.ccw, m.ccw);
      EXPECT_LE(std::abs(r.sweep_rad - m.sweep_rad) * geometry::arc_radius_mm(m), kSweepToleranceMm);
    }
    // F is written with 1 decimal
    EXPECT_NEAR(rb.feed_mm_per_min, m.kind == MoveKind::kRapid ? 0.0 : std::round(b.feed_mm_per_min * 10) / 10, 1e-9);
    EXPECT_EQ(rb.spindle, b.spindle);
    if (b.spindle != SpindleDirection::kOff) {
      EXPECT_EQ(rb.spindle_rpm, std::round(b.spindle_rpm));
    }
    const bool first_piece = j == 0 || expected[j - 1].program_move != expected[j].program_move;
    EXPECT_NEAR(rb.dwell_before_s, first_piece ? b.dwell_before_s : 0.0, 1e-9);
  }
  EXPECT_NEAR(back.blocks[kr + expected.size()].dwell_before_s, program.dwell_at_end_s, 1e-9);
  EXPECT_NEAR(back.dwell_at_end_s, 0.0, 1e-12);
  std::printf("[ oracle   ] %s: %zu moves written as %zu; rs274 worst end %.3g µm, centre %.3g µm, sweep %.3g µm; "
              "reader worst %.3g µm\n",
              case_name(c).c_str(), program.path.moves.size(), expected.size(), worst_end * 1e3, worst_center * 1e3,
              worst_sweep * 1e3, worst_read * 1e3);
}

INSTANTIATE_TEST_SUITE_P(Programs, WriterOracle, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& info) { return case_name(info.param); });

// --- User text in comments --------------------------------------------------------------------------

class WriterCommentOracle : public oracle::Rs274Test, public ::testing::WithParamInterface<Dialect> {};

TEST_P(WriterCommentOracle, NastyNamesStayCommentsForLinuxCnc) {
  const std::vector<std::string> names = {"x) M30 (", "(MSG, boom", "%\nG0 X0", "msg,boom", "(DEBUG, #1",
                                          "LOGOPEN,/tmp/feedplan-injected", "abort, now", "py, import os"};
  ProgramBuilder builder({0, 0, 5});
  builder.spindle(1000, SpindleDirection::kClockwise).line({0, 0, -1}, 100).line({5, 0, -1}, 200).rapid({5, 0, 5});
  const Program program = builder.build();
  WriterOptions plain_options;
  plain_options.dialect = GetParam();
  const OracleRun plain = oracle::run_rs274_text(*rs274_, write_gcode(program, plain_options));
  ASSERT_EQ(plain.exit_code, 0) << plain.messages;
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    WriterOptions options = plain_options;
    options.program_name = name;
    options.header_comments = {{"tool", name}, {"material", name}};
    const std::string text = write_gcode(program, options);
    const OracleRun run = oracle::run_rs274_text(*rs274_, text);
    ASSERT_EQ(run.exit_code, 0) << run.messages;
    for (const std::string& call : run.calls) {
      EXPECT_TRUE(call != "MESSAGE" && call.rfind("LOG", 0) != 0) << call << " in\n" << text;
    }
    EXPECT_EQ(run.messages.find("boom"), std::string::npos) << run.messages;
    EXPECT_EQ(run.calls.size(), plain.calls.size() + (GetParam() == Dialect::kLinuxCnc ? 3 : 2))
        << "the same calls as without the names, plus their comments";
    ASSERT_EQ(run.moves.size(), plain.moves.size());
    for (std::size_t i = 0; i < run.moves.size(); ++i) EXPECT_EQ(distance_mm(run.moves[i].end, plain.moves[i].end), 0.0);
    const Program back = read_program(text, "named");
    EXPECT_EQ(back.path.moves.size(), run.moves.size());
  }
}

INSTANTIATE_TEST_SUITE_P(Dialects, WriterCommentOracle,
                         ::testing::Values(Dialect::kLinuxCnc, Dialect::kFanuc, Dialect::kHaas),
                         [](const ::testing::TestParamInfo<Dialect>& info) { return to_string(info.param); });

}  // namespace

// Names the dialect in test output (gtest finds it next to Dialect).
void PrintTo(Dialect dialect, std::ostream* out) { *out << to_string(dialect); }

}  // namespace feedplan::gcode
