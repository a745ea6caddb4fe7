// Cycle specs no user would write but a file can hold: what fuzzing the reader (tests/fuzz/cycle_spec)
// and a probe found. Each is refused with an InputError naming the field or the file, where the
// reader used to run out of memory or keep the first of two values silently.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/spec_reader.hpp"

namespace feedplan::cycles {
namespace {

using ::testing::HasSubstr;

// The message of reading `yaml`, or a failure when the reader accepts it.
std::string error_of(const std::string& yaml) {
  try {
    read_cycle_spec(yaml, "spec.yaml");
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError for " << yaml.substr(0, 80);
  return {};
}

const std::string kTrochoid =
    "cycle: trochoid\n"
    "axial_depth_mm: 3\n"
    "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n";

// Billion laughs in 800 bytes: nine levels of ten aliases each. Showing `tool`'s value expanded 10⁹
// nodes (24 s, 2.1 GB, then std::bad_alloc).
TEST(SpecReaderHostileInput, AliasBombIsRefusedBeforeItIsExpanded) {
  std::string yaml = kTrochoid + "l0: &l0 [lol, lol, lol, lol, lol, lol, lol, lol, lol, lol]\n";
  for (int level = 1; level <= 8; ++level) {
    std::string name = "l";
    name.append(std::to_string(level));
    yaml.append(name).append(": &").append(name).append(" [");
    for (int i = 0; i < 10; ++i) yaml.append(i == 0 ? "" : ", ").append("*l").append(std::to_string(level - 1));
    yaml.append("]\n");
  }
  yaml += "tool: *l8\n";
  EXPECT_THAT(error_of(yaml), HasSubstr("spec.yaml expands to more than 100000 YAML nodes through its aliases (*name)"));
}

// Anchors and aliases as a spec uses them stay allowed.
TEST(SpecReaderHostileInput, AModestAliasIsRead) {
  const CycleSpec spec = read_cycle_spec(
      "cycle: trochoid\n"
      "tool: {diameter_mm: 10, flutes: 4}\n"
      "axial_depth_mm: &depth 3\n"
      "clearance_z_mm: *depth\n"
      "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n",
      "spec.yaml");
  EXPECT_EQ(spec.clearance_z_mm, 3.0);
}

// A value shown in a problem is cut short: a 5000-element list in the wrong place is not echoed whole.
TEST(SpecReaderHostileInput, ALongValueIsShortenedInTheMessage) {
  std::string list = "[";
  for (int i = 0; i < 5000; ++i) list += (i == 0 ? "" : ", ") + std::to_string(i);
  list += "]";
  const std::string message = error_of(kTrochoid + "tool: " + list + "\n");
  EXPECT_THAT(message, HasSubstr("tool (line 4) = [0, 1, 2, 3"));
  EXPECT_THAT(message, HasSubstr("…: must be a mapping"));
  EXPECT_LT(message.size(), 1000u);
}

// YAML keeps the first of two equal keys; the second value was ignored without a word.
TEST(SpecReaderHostileInput, DuplicateKeysAreAnErrorNamingBothLines) {
  const std::string message = error_of(
      "cycle: trochoid\n"
      "tool: {diameter_mm: 10, flutes: 4}\n"
      "axial_depth_mm: 3\n"
      "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1}\n"
      "axial_depth_mm: 30\n");
  EXPECT_THAT(message, HasSubstr("axial_depth_mm (line 5) is given twice (also on line 3): give it once"));
  EXPECT_THAT(error_of(kTrochoid + "tool: {diameter_mm: 10, flutes: 4, diameter_mm: 12}\n"),
              HasSubstr("tool.diameter_mm (line 4) is given twice (also on line 4): give it once"));
}

// A tool name in Latin-1 went into plan reports, whose JSON writer then threw (nlohmann: invalid UTF-8).
TEST(SpecReaderHostileInput, TextThatIsNotUtf8IsRefused) {
  EXPECT_THAT(error_of(kTrochoid + "tool: {diameter_mm: 10, flutes: 4, name: Fr\xe4ser}\n"),
              HasSubstr("tool.name (line 4) = \"Fr?ser\": is not UTF-8 text (byte 3 is 0xE4); save the file as UTF-8"));
  EXPECT_THAT(error_of(kTrochoid + "tool: {diameter_mm: 10, flutes: 4}\nmaterial: S50C \xff\n"),
              HasSubstr("material (line 5) = \"S50C ?\": is not UTF-8 text (byte 6 is 0xFF)"));
}

// Found by libFuzzer: a key with a byte that is not UTF-8 was quoted into the message as it stood.
TEST(SpecReaderHostileInput, ProblemsShowBytesThatAreNotUtf8AsQuestionMarks) {
  EXPECT_THAT(error_of(kTrochoid + "tool: {diameter_mm: 10, flutes: 4}\nsolid\xc4 S51C: 1\n"),
              HasSubstr("solid? S51C (line 5) is not a known field"));
}

// /dev/zero as the spec: read until memory ran out.
TEST(SpecReaderHostileInput, FilesAreReadUpToTheSizeLimit) {
  try {
    load_cycle_spec("/dev/zero");
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("/dev/zero is larger than 4 MiB: not a cycle spec"));
  }
}

}  // namespace
}  // namespace feedplan::cycles
