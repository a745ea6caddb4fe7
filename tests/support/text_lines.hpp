#pragma once
// Test helper: a text's lines, without their line feeds (a CR before one stays).

#include <sstream>
#include <string>
#include <vector>

namespace feedplan::test_support {

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

}  // namespace feedplan::test_support
