// Reading cycle specs from YAML: a good spec gives the values written in it; every bad spec throws
// one InputError whose message names the field path, the offending value and the allowed range.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <variant>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"

namespace feedplan::cycles {
namespace {

const std::string kTool = "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30, name: \"SC EM D10 Z4\"}\n";

// The example of docs/method.md §4, with the loop centres of seed 003 Table 2.
const std::string kDesignExample =
    "cycle: trochoid\n"
    "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30, name: \"SC EM D10 Z4\"}\n"
    "material: S50C\n"
    "spindle_rpm: 2800\n"
    "axial_depth_mm: 10\n"
    "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1, direction: ccw}\n"
    "target_force_n: 300\n"
    "machine: {max_feed_mm_per_min: 10000, max_accel_mm_per_s2: 6500, block_time_min_s: 0.002}\n";

TEST(SpecReader, ReadsTheDesignExample) {
  const CycleSpec spec = read_cycle_spec(kDesignExample, "design.yaml");
  EXPECT_EQ(spec.cycle, "trochoid");
  EXPECT_EQ(spec.tool.name, "SC EM D10 Z4");
  EXPECT_EQ(spec.tool.diameter_mm, 10.0);
  EXPECT_EQ(spec.tool.flutes, 4);
  EXPECT_EQ(spec.tool.helix_deg, 30.0);
  EXPECT_EQ(spec.material, "S50C");
  EXPECT_EQ(spec.spindle_rpm, 2800.0);
  EXPECT_EQ(spec.axial_depth_mm, 10.0);
  EXPECT_EQ(spec.target_force_n, 300.0);
  EXPECT_EQ(spec.machine.max_feed_mm_per_min, 10000.0);
  EXPECT_EQ(spec.machine.max_accel_mm_per_s2, 6500.0);
  EXPECT_EQ(spec.machine.block_time_min_s, 0.002);
  EXPECT_FALSE(spec.stock.has_value());
  ASSERT_TRUE(std::holds_alternative<TrochoidSpec>(spec.geometry));
  const auto& t = std::get<TrochoidSpec>(spec.geometry);
  EXPECT_EQ(t.start.x_mm, 0.0);
  EXPECT_EQ(t.end.x_mm, 9.0);
  EXPECT_EQ(t.end.y_mm, 0.0);
  EXPECT_EQ(t.loop_radius_mm, 5.0);
  EXPECT_EQ(t.pitch_mm, 1.0);
  EXPECT_EQ(t.direction, Direction::kCcw);
}

TEST(SpecReader, OptionalFieldsTakeTheirDocumentedDefaults) {
  const CycleSpec spec = read_cycle_spec("cycle: corner\n"
                                         "tool: {diameter_mm: 8, flutes: 3}\n"
                                         "axial_depth_mm: 5\n"
                                         "corner: {corner_radius_mm: 6, radial_depth_mm: 1}\n",
                                         "defaults");
  EXPECT_EQ(spec.material, "");
  EXPECT_EQ(spec.spindle_rpm, 0.0);
  EXPECT_EQ(spec.target_force_n, 0.0);
  EXPECT_EQ(spec.clearance_z_mm, 5.0);
  EXPECT_EQ(spec.tool.helix_deg, 30.0);
  EXPECT_EQ(spec.machine.rapid_feed_mm_per_min, 30000.0);
  EXPECT_EQ(spec.machine.min_feed_mm_per_min, 10.0);
  const auto& c = std::get<CornerSpec>(spec.geometry);
  EXPECT_EQ(c.corner_point.x_mm, 0.0);
  EXPECT_EQ(c.corner_point.y_mm, 0.0);
  EXPECT_EQ(c.entry_heading_deg, 0.0);
  EXPECT_EQ(c.corner_angle_deg, 90.0);
  EXPECT_EQ(c.wall_length_mm, 30.0);
  EXPECT_FALSE(c.lead_mm.has_value());
  EXPECT_EQ(c.direction, Direction::kCcw);
}

// The tool's plunge feed per tooth: absent, the default 0.0025 · D; given, the tool's own (geometry::Tool).
TEST(SpecReader, ReadsTheToolsOwnPlungeFeedPerTooth) {
  const std::string trochoid = "cycle: trochoid\naxial_depth_mm: 10\n"
                               "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n";
  const CycleSpec own = read_cycle_spec(
      "tool: {diameter_mm: 10, flutes: 4, max_plunge_feed_per_tooth_mm: 0.04}\n" + trochoid, "own.yaml");
  EXPECT_EQ(own.tool.max_plunge_feed_per_tooth_mm, 0.04);
  EXPECT_EQ(own.tool.plunge_feed_per_tooth_mm(), 0.04);
  const CycleSpec at_diameter = read_cycle_spec(
      "tool: {diameter_mm: 10, flutes: 4, max_plunge_feed_per_tooth_mm: 10}\n" + trochoid, "limit.yaml");
  EXPECT_EQ(at_diameter.tool.plunge_feed_per_tooth_mm(), 10.0);
  const CycleSpec absent = read_cycle_spec(kTool + trochoid, "absent.yaml");
  EXPECT_EQ(absent.tool.max_plunge_feed_per_tooth_mm, 0.0);
  EXPECT_DOUBLE_EQ(absent.tool.plunge_feed_per_tooth_mm(), 0.025);
}

// Every refused value, with the whole message: field and line, the value, what was expected and why.
TEST(SpecReader, RefusesAPlungeFeedPerToothOutsideZeroToTheDiameter) {
  const auto only_problem = [](const std::string& value) {
    const std::string yaml = "cycle: trochoid\n"
                             "tool: {diameter_mm: 10, flutes: 4, max_plunge_feed_per_tooth_mm: " + value + "}\n"
                             "axial_depth_mm: 10\n"
                             "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n";
    try {
      read_cycle_spec(yaml, "plunge.yaml");
    } catch (const InputError& e) {
      if (e.problems().size() == 1) return to_string(e.problems().front());
      return "more than one problem: " + std::string(e.what());
    }
    return std::string("no InputError");
  };
  const std::string why =
      " — the largest feed per tooth along −Z while the tool descends into material, mm, at most the tool diameter "
      "(leave it out for the default 0.0025 × diameter)";
  const std::string field = "tool.max_plunge_feed_per_tooth_mm (line 2) = ";
  EXPECT_EQ(only_problem("12"), field + "12: must be in (0, 10]" + why);
  EXPECT_EQ(only_problem("0"), field + "0: must be in (0, 10]" + why);
  EXPECT_EQ(only_problem("-0.01"), field + "-0.01: must be in (0, 10]" + why);
  EXPECT_EQ(only_problem(".nan"), field + "nan: must be a finite number in (0, 10]" + why);
  EXPECT_EQ(only_problem(".inf"), field + "inf: must be a finite number in (0, 10]" + why);
  EXPECT_EQ(only_problem("fast"), field + "fast: must be a number — " + why.substr(5));
}

// A spec built in code is checked by the same rule (0 is the default there).
TEST(SpecReader, ValidateToolChecksAPlungeFeedPerToothOfItsOwn) {
  geometry::Tool tool{"D10", 10.0, 4, 30.0};
  EXPECT_TRUE(validate_tool(tool).empty());
  tool.max_plunge_feed_per_tooth_mm = 11.0;
  const std::vector<InputProblem> problems = validate_tool(tool);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems.front().field, "tool.max_plunge_feed_per_tooth_mm");
  EXPECT_EQ(problems.front().message.rfind("= 11: must be in (0, 10] — ", 0), 0u) << problems.front().message;
}

TEST(SpecReader, ReadsEveryCycleSection) {
  const CycleSpec spiral = read_cycle_spec(kTool + "cycle: spiral\naxial_depth_mm: 10\n"
                                                   "spiral: {center: [1, 2], initial_radius_mm: 8, final_radius_mm: 16, "
                                                   "pitch_mm: 1, direction: cw}\n",
                                           "s");
  const auto& s = std::get<SpiralSpec>(spiral.geometry);
  EXPECT_EQ(s.center.x_mm, 1.0);
  EXPECT_EQ(s.center.y_mm, 2.0);
  EXPECT_EQ(s.final_radius_mm, 16.0);
  EXPECT_EQ(s.direction, Direction::kCw);

  const CycleSpec boring = read_cycle_spec(
      kTool + "cycle: helical_boring\nhelical_boring: {hole_diameter_mm: 16, pitch_mm: 0.5, depth_mm: 12}\n", "h");
  const auto& h = std::get<HelicalBoringSpec>(boring.geometry);
  EXPECT_EQ(h.hole_diameter_mm, 16.0);
  EXPECT_EQ(h.pitch_mm, 0.5);
  EXPECT_EQ(h.depth_mm, 12.0);
  EXPECT_EQ(boring.axial_depth_mm, 0.0);

  const CycleSpec pocket = read_cycle_spec(kTool + "cycle: pocket\n"
                                                   "pocket: {width_mm: 60, height_mm: 40, depth_mm: 10, "
                                                   "corner_radius_mm: 8, finish_allowance_mm: 1, spiral_pitch_mm: 2}\n",
                                           "p");
  const auto& p = std::get<PocketSpec>(pocket.geometry);
  EXPECT_EQ(p.width_mm, 60.0);
  ASSERT_TRUE(p.finish_allowance_mm.has_value());
  EXPECT_EQ(*p.finish_allowance_mm, 1.0);
  ASSERT_TRUE(p.spiral_pitch_mm.has_value());
  EXPECT_EQ(*p.spiral_pitch_mm, 2.0);
  EXPECT_FALSE(p.helix_pitch_mm.has_value());
  EXPECT_FALSE(p.trochoid_pitch_mm.has_value());
}

TEST(SpecReader, ReadsAUserStockAndTheCycleUsesIt) {
  const CycleSpec spec = read_cycle_spec(kDesignExample +
                                             "stock:\n"
                                             "  z_bottom_mm: -30\n"
                                             "  z_top_mm: 2\n"
                                             "  regions:\n"
                                             "    - outer: {polygon: [[-50, -50], [50, -50], [50, 50], [-50, 50]]}\n"
                                             "      holes: [{circle: {center: [30, 30], radius_mm: 5}}]\n",
                                         "stock");
  ASSERT_TRUE(spec.stock.has_value());
  EXPECT_EQ(spec.stock->z_top_mm, 2.0);
  EXPECT_EQ(spec.stock->z_bottom_mm, -30.0);
  ASSERT_EQ(spec.stock->regions.size(), 1u);
  EXPECT_EQ(spec.stock->regions[0].outer.vertices.size(), 4u);
  ASSERT_EQ(spec.stock->regions[0].holes.size(), 1u);
  EXPECT_TRUE(spec.stock->regions[0].holes[0].is_circle());
  EXPECT_EQ(spec.stock->regions[0].holes[0].radius_mm, 5.0);

  const Cycle cycle = generate(spec);
  EXPECT_EQ(cycle.stock.z_top_mm, 2.0);
  EXPECT_EQ(cycle.stock.regions[0].outer.vertices[1].x_mm, 50.0);
  // Depths are measured from the given stock top: 2 − 10 = −8; the clearance is 2 + 5 = 7.
  for (const auto& move : cycle.path.moves) {
    if (move.cutting) {
      EXPECT_DOUBLE_EQ(move.start.z_mm, -8.0);
    }
  }
  EXPECT_DOUBLE_EQ(cycle.path.moves.front().start.z_mm, 7.0);
}

struct BadSpec {
  const char* name;
  std::string yaml;
  std::string field;  // field path (or source name) the message must name
  std::string value;  // the offending value as the message shows it
  std::string range;  // the allowed range or expectation
};

// Keeps ctest's listing readable: the case name instead of gtest's byte dump.
void PrintTo(const BadSpec& bad, std::ostream* os) { *os << bad.name; }

std::string trochoid_with(const std::string& section) { return "cycle: trochoid\n" + kTool + "axial_depth_mm: 10\n" + section; }

const BadSpec kBadSpecs[] = {
    {"PitchAtLeastDiameter", trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 12}\n"),
     "trochoid.pitch_mm (line 4)", "= 12", "must be in (0, 10)"},
    {"NegativeLoopRadius", trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: -5, pitch_mm: 1}\n"),
     "trochoid.loop_radius_mm", "= -5", "must be > 0"},
    {"LoopRadiusNotAbovePitch",
     trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 0.5, pitch_mm: 1}\n"),
     "trochoid.loop_radius_mm", "= 0.5", "must be > pitch_mm = 1"},
    {"ZeroInitialRadius",
     "cycle: spiral\n" + kTool + "axial_depth_mm: 10\nspiral: {initial_radius_mm: 0, final_radius_mm: 16, pitch_mm: 1}\n",
     "spiral.initial_radius_mm", "= 0", "must be > 5"},
    {"ToolDoesNotFitTheBore",
     "cycle: spiral\n" + kTool + "axial_depth_mm: 10\nspiral: {initial_radius_mm: 4, final_radius_mm: 16, pitch_mm: 1}\n",
     "spiral.initial_radius_mm", "= 4", "must be > 5 — the tool (radius 5) does not fit in the bore"},
    {"FinalNotAboveInitialRadius",
     "cycle: spiral\n" + kTool + "axial_depth_mm: 10\nspiral: {initial_radius_mm: 8, final_radius_mm: 8, pitch_mm: 1}\n",
     "spiral.final_radius_mm", "= 8", "must be > 8"},
    {"CornerRadiusBelowToolRadius",
     "cycle: corner\n" + kTool + "axial_depth_mm: 10\ncorner: {corner_radius_mm: 4, radial_depth_mm: 1.5}\n",
     "corner.corner_radius_mm", "= 4", "must be > 5"},
    {"RadialDepthAboveDiameter",
     "cycle: corner\n" + kTool + "axial_depth_mm: 10\ncorner: {corner_radius_mm: 10, radial_depth_mm: 11}\n",
     "corner.radial_depth_mm", "= 11", "must be in (0, 10]"},
    {"StraightCorner",
     "cycle: corner\n" + kTool + "axial_depth_mm: 10\ncorner: {corner_radius_mm: 10, radial_depth_mm: 1, corner_angle_deg: 180}\n",
     "corner.corner_angle_deg", "= 180", "must be in (0, 180)"},
    {"PocketNarrowerThanTool",
     "cycle: pocket\n" + kTool + "pocket: {width_mm: 12, height_mm: 40, depth_mm: 10, corner_radius_mm: 6}\n",
     "pocket.width_mm", "= 12", "must be ≥ 14"},
    {"PocketTooWideForOneSlot",
     "cycle: pocket\n" + kTool + "pocket: {width_mm: 100, height_mm: 80, depth_mm: 10, corner_radius_mm: 8}\n",
     "pocket.height_mm", "= 80", "must be ≤ 61.04"},
    {"PocketCornerRadiusAboveHalfWidth",
     "cycle: pocket\n" + kTool + "pocket: {width_mm: 60, height_mm: 40, depth_mm: 10, corner_radius_mm: 25}\n",
     "pocket.corner_radius_mm", "= 25", "must be in (5, 20]"},
    {"HoleLargerThanTwoDiameters",
     "cycle: helical_boring\n" + kTool + "helical_boring: {hole_diameter_mm: 25, pitch_mm: 1, depth_mm: 10}\n",
     "helical_boring.hole_diameter_mm", "= 25", "must be in (10, 20] — a hole larger than twice the tool diameter leaves an uncut core"},
    {"NaN", "cycle: trochoid\n" + kTool + "axial_depth_mm: .nan\n"
                                         "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n",
     "axial_depth_mm (line 3)", "= nan", "must be a finite number > 0"},
    {"Infinity", trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: .inf, pitch_mm: 1}\n"),
     "trochoid.loop_radius_mm", "= inf", "must be a finite number > 0"},
    {"MissingField", trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5}\n"),
     "trochoid.pitch_mm", "is missing from the trochoid section (line 4)", "required"},
    {"MissingSection", trochoid_with(""), "trochoid", "is missing", "required"},
    {"UnknownField", trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pich_mm: 1}\n"),
     "trochoid.pich_mm (line 4)", "is not a known field",
     "expected one of start, end, loop_radius_mm, pitch_mm, direction (did you mean pitch_mm?)"},
    {"WrongType",
     "cycle: trochoid\ntool: {diameter_mm: 10, flutes: \"four\"}\naxial_depth_mm: 10\n"
     "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n",
     "tool.flutes (line 2)", "= \"four\"", "must be an integer"},
    {"FlutesOutOfRange",
     "cycle: trochoid\ntool: {diameter_mm: 10, flutes: 0}\naxial_depth_mm: 10\n"
     "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n",
     "tool.flutes", "= 0", "must be in [1, 32]"},
    {"PointOfOneNumber", trochoid_with("trochoid: {start: [0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n"),
     "trochoid.start", "= [0]", "must be [x, y], two numbers in mm"},
    {"UnknownDirection",
     trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1, direction: clockwise}\n"),
     "trochoid.direction", "= clockwise", "must be ccw or cw"},
    {"UnknownCycle", "cycle: slotting\n" + kTool, "cycle (line 1)", "= slotting",
     "expected one of corner, trochoid, spiral, helical_boring, pocket"},
    {"SectionOfAnotherCycle",
     trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n"
                   "spiral: {initial_radius_mm: 8, final_radius_mm: 16, pitch_mm: 1}\n"),
     "spiral (line 5)", "is a section for cycle spiral", "but cycle is trochoid"},
    {"MalformedYaml", "cycle: trochoid\ntool: {diameter_mm: 10\n  flutes: 4\n", "bad.yaml", "is not valid YAML",
     "at line 3"},
    {"EmptyFile", "# only a comment\n", "bad.yaml", "is empty", "expected a cycle spec"},
    {"NotAMapping", "- cycle\n- trochoid\n", "bad.yaml", "is not a YAML mapping", "(it is a list)"},
    {"MinFeedAboveMaxFeed",
     trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n"
                   "machine: {max_feed_mm_per_min: 100, min_feed_mm_per_min: 200}\n"),
     "machine.min_feed_mm_per_min", "= 200", "must be < max_feed_mm_per_min = 100"},
    {"SelfIntersectingStock",
     trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n"
                   "stock: {z_bottom_mm: -20, z_top_mm: 0, regions: [{outer: {polygon: [[0, 0], [10, 10], [10, 0], [0, 10]]}}]}\n"),
     "stock.regions[0].outer.polygon (line 5)", "is not simple", "edges cross"},
    {"NegativeStockCircle",
     trochoid_with("trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n"
                   "stock: {z_bottom_mm: -20, z_top_mm: 0, regions: [{outer: {circle: {center: [0, 0], radius_mm: -1}}}]}\n"),
     "stock.regions[0].outer.circle.radius_mm", "= -1", "must be > 0"},
    {"AxialDepthOnAPocket",
     "cycle: pocket\n" + kTool + "axial_depth_mm: 5\n"
                                 "pocket: {width_mm: 60, height_mm: 40, depth_mm: 10, corner_radius_mm: 8}\n",
     "axial_depth_mm (line 3)", "= 5", "not used by a pocket cycle"},
};

class BadSpecTest : public ::testing::TestWithParam<BadSpec> {};

TEST_P(BadSpecTest, ThrowsInputErrorNamingFieldValueAndRange) {
  const BadSpec& bad = GetParam();
  try {
    read_cycle_spec(bad.yaml, "bad.yaml");
    FAIL() << "no InputError for " << bad.name;
  } catch (const InputError& e) {
    bool found = false;
    for (const auto& problem : e.problems()) {
      const std::string text = to_string(problem);
      if (text.rfind(bad.field, 0) == 0 && text.find(bad.value) != std::string::npos &&
          text.find(bad.range) != std::string::npos) {
        found = true;
      }
    }
    EXPECT_TRUE(found) << bad.name << ": no problem starts with '" << bad.field << "' and contains '" << bad.value
                       << "' and '" << bad.range << "'; got:\n"
                       << e.what();
    // what() carries the same text as the problems.
    EXPECT_NE(std::string(e.what()).find(bad.value), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(SpecReader, BadSpecTest, ::testing::ValuesIn(kBadSpecs),
                         [](const ::testing::TestParamInfo<BadSpec>& info) { return std::string(info.param.name); });

// A pocket narrower than the tool is reported once, on its short side, and the corner radius is
// not given an empty allowed range (5, 4] as a consequence.
TEST(SpecReader, NarrowPocketIsReportedOnItsWidthOnly) {
  try {
    read_cycle_spec("cycle: pocket\n" + kTool +
                        "pocket: {width_mm: 8, height_mm: 40, depth_mm: 10, corner_radius_mm: 8}\n",
                    "narrow.yaml");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems().front().field.rfind("pocket.width_mm", 0), 0u) << e.what();
  }
}

TEST(SpecReader, CollectsEveryProblemOnceInOneError) {
  const std::string yaml =
      "cycle: spiral\n"
      "tool: {diameter_mm: 10, flutes: 4, colour: red}\n"
      "axial_depth_mm: -1\n"
      "spiral: {initial_radius_mm: 4, pitch_mm: 12}\n"
      "clearance_z_mm: 0.5\n";
  try {
    read_cycle_spec(yaml, "many.yaml");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const auto& problems = e.problems();
    const std::vector<std::string> expected = {"tool.colour (line 2)", "spiral.final_radius_mm", "axial_depth_mm (line 3)",
                                               "spiral.initial_radius_mm (line 4)", "spiral.pitch_mm (line 4)",
                                               "clearance_z_mm (line 5)"};
    ASSERT_EQ(problems.size(), expected.size()) << e.what();
    for (const auto& field : expected) {
      int count = 0;
      for (const auto& p : problems) count += p.field == field;
      EXPECT_EQ(count, 1) << field << " in\n" << e.what();
    }
  }
}

TEST(SpecReader, AMissingValueIsReportedOnceNotAgainAsOutOfRange) {
  try {
    read_cycle_spec("cycle: trochoid\ntool: {flutes: 4}\naxial_depth_mm: 10\n"
                    "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n",
                    "once.yaml");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0].field, "tool.diameter_mm");
    EXPECT_NE(e.problems()[0].message.find("is missing from the tool section (line 2)"), std::string::npos);
  }
}

TEST(SpecReader, LoadReportsAMissingFileByItsPath) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "feedplan_no_such_spec.yaml";
  std::filesystem::remove(path);
  try {
    load_cycle_spec(path);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).field, path.string());
    EXPECT_NE(e.problems()[0].message.find("no such file"), std::string::npos);
  }
  EXPECT_THROW(load_cycle_spec(std::filesystem::temp_directory_path()), InputError);
}

TEST(SpecReader, LoadNamesTheFileInDocumentLevelProblems) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "feedplan_empty_spec.yaml";
  std::ofstream(path) << "\n";
  try {
    load_cycle_spec(path);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problems().at(0).field, path.string());
  }
  std::filesystem::remove(path);
}

TEST(Validate, ProgrammaticSpecsAreCheckedLikeYamlOnes) {
  CycleSpec spec;
  spec.cycle = "spiral";  // but holds a trochoid
  spec.axial_depth_mm = 10;
  spec.geometry = TrochoidSpec{{0, 0}, {9, 0}, 5, 1, Direction::kCcw};
  const auto problems = validate(spec);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "cycle");
  EXPECT_THROW(generate(spec), InputError);
  spec.cycle = "trochoid";
  EXPECT_TRUE(validate(spec).empty());
  EXPECT_NO_THROW(generate(spec));
}

}  // namespace
}  // namespace feedplan::cycles
