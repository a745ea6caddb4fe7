#pragma once
// The --tool flag of the commands that take a program instead of a cycle spec:
// "diameter_mm=10,flutes=4,helix_deg=30[,name=…]".

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cli {

//! The tool `text` describes; every problem is added to `problems`, named "--tool".
geometry::Tool parse_tool(const std::string& text, std::vector<InputProblem>& problems);

}  // namespace feedplan::cli
