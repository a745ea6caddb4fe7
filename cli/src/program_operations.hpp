#pragma once
// The operations of a program another system wrote: stretches of its moves between tool changes or comment
// lines, as CAM posts mark them ("(begin operation: Pocket)", "(PROFILE)"), each named by its comment —
// what `feedplan optimize` reports time and predicted peak force for, before and after.

#include <cstddef>
#include <string>
#include <vector>

#include "feedplan/gcode/reader.hpp"

namespace feedplan::cli {

//! Moves [first_move, end_move) of the program.
struct ProgramOperation {
  std::string name;            //!< the comment that opens it (a FreeCAD "begin operation: " prefix dropped), else "T<n>"
  std::size_t first_move = 0;
  std::size_t end_move = 0;
  int first_line = 0;          //!< text lines of its first and last move
  int last_line = 0;
};

//! The operations of the program `text` whose moves were read as `written`: a new one starts at a move
//! with another tool than the move before it, or with a line holding only comments between the two when
//! the operation so far has a feed move (its name: the last "begin operation" comment among them, else the
//! first that does not start with "finish" or "end"; none such: no new operation); an operation still named after its tool takes such a
//! comment before its first feed move. Every move belongs to exactly one operation, in program order.
std::vector<ProgramOperation> program_operations(const std::string& text, const std::vector<gcode::WrittenMove>& written);

}  // namespace feedplan::cli
