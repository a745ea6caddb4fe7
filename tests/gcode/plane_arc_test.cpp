// Arcs in the XZ (G18) and YZ (G19) planes — CAM lead-ins and ramps — against LinuxCNC's interpreter:
// rs274 writes each as one ARC_FEED in the plane (first axis, second axis: Z X for G18, Y Z for G19);
// the reader writes straight pieces along it. Every piece end must lie on rs274's arc (to 1 µm, plus
// half a printed digit in inches), the pieces must turn its way and sweep its angle, each at most 5°
// with a chord within 1 µm of the arc, and end on its end; the moves around the arcs match move by move.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/gcode/refeed.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "rs274_runner.hpp"
#include "text_lines.hpp"

namespace feedplan::gcode {
namespace {

using geometry::MoveKind;
using geometry::Point2;
using geometry::Point3;
using ::testing::HasSubstr;

constexpr double kToleranceMm = 1e-3;
constexpr double kInchPrintMm = 0.5 * 0.0001 * 25.4 * 1.7320508;
constexpr double kPi = 3.14159265358979323846;

double distance_mm(const Point3& a, const Point3& b) { return std::hypot(std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm), b.z_mm - a.z_mm); }

// A point in the plane of an arc: 'y' XZ (G18: Z first, X second), 'x' YZ (G19: Y first, Z second); 'z'
// names an XY arc.
Point2 in_plane(char plane, const Point3& p) { return plane == 'y' ? Point2{p.z_mm, p.x_mm} : Point2{p.y_mm, p.z_mm}; }

// rs274's ARC_FEED(first_end, second_end, first_centre, second_centre, rotation, axis_end) as XYZ.
Point3 arc_end_xyz(char plane, const oracle::OracleMove& o) {
  return plane == 'y' ? Point3{o.end.y_mm, o.end.z_mm, o.end.x_mm} : Point3{o.end.z_mm, o.end.x_mm, o.end.y_mm};
}

class PlaneArcOracle : public oracle::Rs274Test {
 protected:
  // Reads `text` and follows rs274's run of it; `planes` names the plane of each of its arcs in order.
  geometry::Program expect_as_linuxcnc(const std::string& text, const std::string& planes) {
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
    std::size_t k = 0;  // our next move
    std::size_t arc_index = 0;
    Point3 position{0.0, 0.0, 0.0};
    for (std::size_t i = 0; i < run.moves.size(); ++i) {
      const oracle::OracleMove& o = run.moves[i];
      SCOPED_TRACE("rs274 move " + std::to_string(i));
      if (o.kind != MoveKind::kArc) {
        EXPECT_LT(k, ours.path.moves.size());
        if (k >= ours.path.moves.size()) return ours;
        EXPECT_EQ(ours.path.moves[k].kind, o.kind);
        EXPECT_LE(distance_mm(ours.path.moves[k].end, o.end), tol);
        position = o.end;
        ++k;
        continue;
      }
      EXPECT_LT(arc_index, planes.size()) << "more arcs than the test names planes for";
      if (arc_index >= planes.size()) return ours;
      const char plane = planes[arc_index++];
      if (plane == 'z') {  // an XY arc: one arc move
        EXPECT_LT(k, ours.path.moves.size());
        if (k >= ours.path.moves.size()) return ours;
        const geometry::Move& m = ours.path.moves[k++];
        EXPECT_EQ(m.kind, MoveKind::kArc);
        EXPECT_LE(distance_mm(m.end, o.end), tol);
        EXPECT_LE(std::hypot(m.center.x_mm - o.center.x_mm, m.center.y_mm - o.center.y_mm), tol);
        position = o.end;
        continue;
      }
      const Point3 end = arc_end_xyz(plane, o);
      const Point2 center{o.center.x_mm, o.center.y_mm};
      const Point2 s = in_plane(plane, position);
      const double radius = std::hypot(s.x_mm - center.x_mm, s.y_mm - center.y_mm);
      const double ccw = o.rotation > 0 ? 1.0 : -1.0;
      // rs274's sweep: from start to end in the rotation's direction, (0, 2π], plus extra turns.
      const Point2 e = in_plane(plane, end);
      double sweep = std::fmod(ccw * (std::atan2(e.y_mm - center.y_mm, e.x_mm - center.x_mm) -
                                      std::atan2(s.y_mm - center.y_mm, s.x_mm - center.x_mm)), 2.0 * kPi);
      if (sweep <= 1e-12) sweep += 2.0 * kPi;
      sweep += (std::abs(o.rotation) - 1) * 2.0 * kPi;
      double swept = 0.0;
      int pieces = 0;
      const int line = k < ours.blocks.size() ? ours.blocks[k].source_line : 0;
      while (k < ours.path.moves.size()) {
        const geometry::Move& m = ours.path.moves[k++];
        ++pieces;
        EXPECT_EQ(m.kind, MoveKind::kLine);
        EXPECT_EQ(ours.blocks[k - 1].source_line, line) << "every piece is on the arc's line";
        EXPECT_TRUE(written[k - 1].keep_whole);
        const Point2 a = in_plane(plane, m.start), b = in_plane(plane, m.end);
        EXPECT_NEAR(std::hypot(b.x_mm - center.x_mm, b.y_mm - center.y_mm), radius, tol) << "a piece end off the arc";
        double turn = ccw * (std::atan2(b.y_mm - center.y_mm, b.x_mm - center.x_mm) -
                             std::atan2(a.y_mm - center.y_mm, a.x_mm - center.x_mm));
        turn = std::remainder(turn, 2.0 * kPi);
        EXPECT_GT(turn, 0.0) << "pieces turn the arc's way";
        EXPECT_LE(turn, 5.0 * kPi / 180.0 + 1e-9) << "at most 5° a piece";
        EXPECT_LE(radius * (1.0 - std::cos(turn / 2.0)), 1e-3 + 1e-9) << "chord within 1 µm of the arc";
        swept += turn;
        if (distance_mm(m.end, end) <= tol && std::abs(swept - sweep) * radius < 0.5) break;
      }
      EXPECT_LE(std::abs(swept - sweep) * radius, tol) << pieces << " pieces";
      EXPECT_LE(distance_mm(ours.path.moves[k - 1].end, end), tol);
      position = end;
    }
    EXPECT_EQ(k, ours.path.moves.size()) << "moves the reader made that rs274 did not";
    EXPECT_EQ(arc_index, planes.size());
    return ours;
  }
};

TEST_F(PlaneArcOracle, XzLeadInsByCentreAndRadiusBothWaysWithHelixInMillimetres) {
  const geometry::Program program = expect_as_linuxcnc(
      "G21 G17 G90\n"
      "S5000 M3\n"
      "G0 X0 Y0 Z10\n"
      "G1 Z5 F300\n"
      "G18 G2 X5 Z0 I5 K0 F200 (quarter lead-in, centre by I K)\n"
      "G1 X30\n"
      "G3 X35 Z5 R5 (arc out by R)\n"
      "G2 X25 Y8 Z5 I-5 K0 (helix: Y moves along)\n"
      "G3 X33 Z1 R-5 (the long way)\n"
      "G17 G1 X50 Y0\n"
      "G2 X60 Y10 I10 J0 (an XY arc after G17)\n"
      "G0 Z20\n"
      "M2\n",
      "yyyyz");
  ASSERT_FALSE(program.notes.empty());
  bool noted = false;
  for (const std::string& n : program.notes) noted = noted || n.find("4 arcs in the XZ or YZ plane") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST_F(PlaneArcOracle, YzRampsAndAFullCircleInInches) {
  expect_as_linuxcnc(
      "G20 G17 G90\n"
      "S5000 M3\n"
      "G0 X0 Y0 Z0.5\n"
      "G19 G1 Z0.25 F20\n"
      "G3 Y0.5 Z-0.25 J0.5 K0 (ramp down in YZ)\n"
      "G2 Y1.5 Z-0.25 R0.5\n"
      "G3 Y1.5 Z-0.25 J0 K0.25 (full circle)\n"
      "G91.1 G2 X1 Y2.5 Z0.75 J0.5 K0.5 (helix with X)\n"
      "G90 G17 G0 Z1\n"
      "M2\n",
      "xxxx");
}

TEST(PlaneArcProblems, WordsOfAnotherPlaneAndCompensationAreRefused) {
  auto problems_of = [](const std::string& text) {
    try {
      read_program(text, "test");
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string();
  };
  EXPECT_THAT(problems_of("G21 F100\nG19 G2 Y10 Z0 I5 K0\nM2\n"),
              HasSubstr("test line 2: word I5: I is not read in the YZ plane (G19)"));
  EXPECT_THAT(problems_of("G21 F100\nG18 G2 X10 Z0\nM2\n"), HasSubstr("test line 2: G2 without I, K or R"));
  EXPECT_THAT(problems_of("G21 F100\nG18 G2 X10 Z0 R3\nM2\n"), HasSubstr("test line 2: G2 R3: radius 3 mm is shorter"));
}

TEST_F(PlaneArcOracle, ARefedPlaneArcKeepsItsLineAndRunsAtItsLowestFeed) {
  const std::string text =
      "G21 G17 G90\n"
      "S5000 M3\n"
      "G0 X0 Y0 Z10\n"
      "G1 Z5 F300\n"
      "G18 G2 X5 Z0 I5 K0 F200\n"
      "G17 G1 X30\n"
      "M2\n";
  std::vector<WrittenMove> written;
  const geometry::Program program = read_program(text, "test", {}, written);
  std::vector<FeedPiece> pieces;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    if (program.path.moves[i].kind == MoveKind::kRapid) continue;
    pieces.push_back({static_cast<int>(i), program.path.moves[i], 150.0 + 10.0 * static_cast<double>(i % 7)});
  }
  const RefeedResult r = refeed_text(text, program, written, pieces);
  const std::vector<std::string> out = test_support::lines_of(r.text);
  ASSERT_EQ(out.size(), 7U) << r.text;
  EXPECT_EQ(out[4], "G18 G2 X5 Z0 I5 K0 F150.");
  EXPECT_EQ(r.lines_added, 0);
  const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, r.text);
  ASSERT_EQ(run.exit_code, 0) << run.messages;
  ASSERT_EQ(run.moves.size(), 4U);
  EXPECT_EQ(run.moves[2].kind, MoveKind::kArc);
  EXPECT_NEAR(run.moves[2].feed_mm_per_min, 150.0, 1e-6);
}

}  // namespace
}  // namespace feedplan::gcode
