// Golden files (STYLE.md, tests kind 3): the writer's exact text for three small fixed programs in
// every dialect, tests/data/gcode/golden/<case>_<dialect>.nc, compared byte for byte. A change in the
// output shows up as a diff of these files in review.
//
// They are regenerated only on purpose: scripts/regenerate-golden-gcode.sh runs this test with
// FEEDPLAN_REGENERATE_GOLDEN=1, which makes it write the files instead of comparing them.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/gcode/writer.hpp"
#include "program_builder.hpp"
#include "rs274_runner.hpp"

namespace feedplan::gcode {
namespace {

namespace fs = std::filesystem;
using geometry::Program;
using geometry::SpindleDirection;
using testing_support::kPi;
using testing_support::ProgramBuilder;

fs::path golden_dir() { return fs::path(FEEDPLAN_TEST_DATA_DIR) / "gcode" / "golden"; }

bool regenerating() {
  const char* flag = std::getenv("FEEDPLAN_REGENERATE_GOLDEN");
  return flag != nullptr && std::string(flag) == "1";
}

// Corner rounding: along a wall, round a convex corner of radius 7.5 mm, along the next wall; the
// feed drops before the corner and rises after it, as a plan would have it.
Program corner_program() {
  ProgramBuilder b({-20, -5.5, 5});
  b.spindle(2800, SpindleDirection::kClockwise);
  b.rapid({-20, -5.5, 1}).line({-20, -5.5, -10}, 300).line({-5, -5.5, -10}, 1200).line({0, -5.5, -10}, 900);
  b.arc({0, 2}, kPi / 2, true, 0, 650).arc({0, 2}, kPi / 4, true, 0, 720.5);
  b.line({b.position().x_mm - 4, b.position().y_mm + 4, -10}, 900).line({-12, 20, -10}, 1200);
  b.rapid({-12, 20, 5});
  return b.build();
}

// Helical bore: helix of 2.5 turns down 5 mm, a dwell, a finishing full circle, a spindle change.
Program helix_program() {
  ProgramBuilder b({44, 30, 2});
  b.spindle(4000, SpindleDirection::kClockwise);
  b.line({44, 30, 0}, 500).arc({40, 30}, 5 * kPi, false, -5, 800);
  b.dwell(0.25).arc({40, 30}, 2 * kPi, false, 0, 1100.2);
  b.line({40, 30, -5}, 1100.2);
  b.spindle(3000, SpindleDirection::kCounterClockwise).line({40, 30, -4}, 200);
  b.dwell_at_end(0.5);
  return b.build();
}

// Short moves and rounding: a move and an arc below the resolution (left out), a sliver arc, a full
// circle as one block (max sweep 360°), numbers that need rounding.
Program short_moves_program() {
  ProgramBuilder b({1.23456789, -0.00004, 3});
  b.spindle(12000.4, SpindleDirection::kClockwise);
  b.line({1.23456789, -0.00004, -0.5}, 100.04);
  b.line({1.23459, -0.00004, -0.5}, 150);                          // 0.02 µm: rounds to no motion
  b.line({1.2351, 0.0003, -0.5}, 150);
  b.arc({1.2351, 2.0003}, 0.00001, true, 0, 160);                  // 0.02 µm of arc: no motion
  b.arc({1.2351, 2.0003}, 0.001, true, 0, 170);                    // 2 µm of arc
  b.arc({1.2351, 1.0003}, 2 * kPi, true, 0, 180);                  // full circle
  b.arc({b.position().x_mm + 0.75, b.position().y_mm}, kPi, false, -0.25, 190.55);
  return b.build();
}

struct GoldenCase {
  const char* name;
  Program (*program)();
  WriterOptions options;
};

std::vector<GoldenCase> golden_cases() {
  WriterOptions corner;
  corner.program_name = "corner rounding";
  corner.program_number = 1001;
  corner.header_comments = {{"cycle", "corner"},
                            {"tool", "SC EM \xC3\x98" "10 Z4 (carbide)"},
                            {"material", "S50C"},
                            {"target force N", "300"}};
  WriterOptions helix;
  helix.program_name = "helical bore";
  helix.program_number = 2002;
  helix.line_numbers = true;
  helix.coolant = true;
  helix.retract_z_mm = 25.0;
  helix.tool_number = 2;
  helix.header_comments = {{"cycle", "helical_boring"}};
  WriterOptions short_moves;
  short_moves.program_name = "short, moves";
  short_moves.decimals = 4;
  short_moves.max_arc_sweep_deg = 360.0;
  short_moves.tool_change = false;
  return {{"corner", corner_program, corner}, {"helix", helix_program, helix}, {"short_moves", short_moves_program, short_moves}};
}

struct GoldenFile {
  std::string name;  // <case>_<dialect>
  std::string text;  // what the writer writes
  Dialect dialect = Dialect::kLinuxCnc;
};

std::vector<GoldenFile> golden_files() {
  std::vector<GoldenFile> files;
  for (const GoldenCase& c : golden_cases()) {
    for (Dialect dialect : {Dialect::kLinuxCnc, Dialect::kFanuc, Dialect::kHaas}) {
      WriterOptions options = c.options;
      options.dialect = dialect;
      files.push_back({std::string(c.name) + "_" + to_string(dialect), write_gcode(c.program(), options), dialect});
    }
  }
  return files;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(WriterGolden, OutputMatchesTheGoldenFilesByteForByte) {
  for (const GoldenFile& file : golden_files()) {
    const fs::path path = golden_dir() / (file.name + ".nc");
    if (regenerating()) {
      fs::create_directories(golden_dir());
      const std::string problem = write_file_atomically(path, file.text);
      ASSERT_EQ(problem, "");
      std::printf("[ golden   ] wrote %s\n", path.c_str());
      continue;
    }
    ASSERT_TRUE(fs::exists(path)) << path << " is missing: run scripts/regenerate-golden-gcode.sh and review the diff";
    EXPECT_EQ(read_file(path), file.text)
        << path << " differs from the writer's output. If the change is intended, run "
        << "scripts/regenerate-golden-gcode.sh and review the diff of tests/data/gcode/golden/.";
  }
}

TEST(WriterGolden, EveryGoldenFileBelongsToACase) {
  if (regenerating()) GTEST_SKIP() << "regenerating";
  std::set<std::string> names;
  for (const GoldenFile& file : golden_files()) names.insert(file.name + ".nc");
  for (const auto& entry : fs::directory_iterator(golden_dir())) {
    EXPECT_EQ(names.count(entry.path().filename().string()), 1u) << entry.path() << " is not written by any case";
  }
}

using WriterGoldenOracle = oracle::Rs274Test;

TEST_F(WriterGoldenOracle, LinuxCncRunsEveryGoldenFile) {
  for (const GoldenFile& file : golden_files()) {
    const std::string text = file.dialect == Dialect::kFanuc ? oracle::fanuc_dwell_as_linuxcnc(file.text) : file.text;
    const oracle::OracleRun run = oracle::run_rs274_text(*rs274_, text);
    EXPECT_EQ(run.exit_code, 0) << file.name << ":\n" << run.messages;
  }
}

}  // namespace
}  // namespace feedplan::gcode
