#pragma once
// Splitting one line of RS274/NGC text into words: comments, spaces and case removed, numbers
// checked. Internal to the gcode module.

#include <string>
#include <string_view>
#include <vector>

#include "problem_log.hpp"

namespace feedplan::gcode::detail {

//! One word of a block: a letter and its number.
struct Word {
  char letter = 'G';   //!< upper-case letter
  double value = 0.0;  //!< the number as written, in the program's units (finite)
  std::string text;    //!< the word as written, upper case without spaces ("X-1.5"), for messages
};

//! The words of one line.
struct LexedLine {
  std::vector<Word> words;  //!< in the order written; empty for blank and comment-only lines
  bool percent = false;     //!< the line is a lone `%`
  bool ok = true;           //!< false when a problem was logged; the line must not be executed
};

//! Splits `text` (one line, without its newline; a trailing '\r' is ignored) into words. Handles
//! `( )` comments (not nested, closed on the same line), `;` comments to the end of the line, spaces
//! and tabs anywhere outside comments (LinuxCNC ignores them), lower-case letters. A number is a
//! plain decimal: optional sign, digits with at most one decimal point, at least one digit — no
//! exponents, no `#` parameters or `[ ]` expressions, and at most ±1 000 000 (N and O words excepted).
//! An `O` word must be alone on its line (a
//! program number). The first problem in a line is logged for 1-based `line` and ends the line.
LexedLine lex_line(std::string_view text, int line, ProblemLog& problems);

}  // namespace feedplan::gcode::detail
