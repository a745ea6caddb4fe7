// Reading a tool library (feedplan optimize --tools): the end mill of each T number, each written as a
// cycle spec's tool section and checked the same way; every problem named by field and line.

#include <gtest/gtest.h>

#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/spec_reader.hpp"

namespace feedplan::cycles {
namespace {

TEST(ToolLibrary, EveryTNumberWithItsEndMill) {
  const auto tools = read_tool_library(
      "# the front panel's end mills\n"
      "tools:\n"
      "  2: {diameter_mm: 6.35, flutes: 2, helix_deg: 30, name: \"1/4 in 2-flute\"}\n"
      "  3: {diameter_mm: 4.7625, flutes: 2}\n",
      "tools.yaml");
  ASSERT_EQ(tools.size(), 2u);
  EXPECT_EQ(tools.at(2).diameter_mm, 6.35);
  EXPECT_EQ(tools.at(2).flutes, 2);
  EXPECT_EQ(tools.at(2).name, "1/4 in 2-flute");
  EXPECT_EQ(tools.at(3).diameter_mm, 4.7625);
  EXPECT_EQ(tools.at(3).helix_deg, 30.0) << "the spec's default helix";
  EXPECT_EQ(tools.at(3).name, "T3");
}

std::string problems_of(const std::string& yaml) {
  try {
    read_tool_library(yaml, "tools.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ToolLibrary, EveryProblemByFieldAndLine) {
  const std::string text = problems_of(
      "tools:\n"
      "  2: {diameter_mm: -6, flutes: 2}\n"
      "  x: {diameter_mm: 6, flutes: 2}\n"
      "  4: {diameter_mm: 6, flutes: 2, colour: red}\n"
      "  5: {flutes: 3}\n");
  EXPECT_NE(text.find("tools.2.diameter_mm (line 2) = -6"), std::string::npos) << text;
  EXPECT_NE(text.find("tools.x (line 3) is not a T number"), std::string::npos) << text;
  EXPECT_NE(text.find("colour"), std::string::npos) << text;
  EXPECT_NE(text.find("tools.5"), std::string::npos) << text;
  EXPECT_NE(text.find("diameter_mm"), std::string::npos) << text;
  EXPECT_NE(problems_of("tool: {diameter_mm: 6}\n").find("tools"), std::string::npos);
  EXPECT_NE(problems_of("tools: []\n").find("must be a mapping of T numbers to tools"), std::string::npos);
  EXPECT_NE(problems_of("- 1\n").find("is not a YAML mapping"), std::string::npos);
  EXPECT_NE(problems_of("tools: {2: {diameter_mm: 6, flutes: 2}\n").find("tools.yaml"), std::string::npos)
      << "malformed YAML names the file";
}

}  // namespace
}  // namespace feedplan::cycles
