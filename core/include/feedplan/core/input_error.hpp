#pragma once
// The one exception type for bad user input (specs, logs, files, CLI flags). It carries every
// problem found, each naming the field path, the value and what was expected; the CLI prints
// them and exits 2.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/core/utf8_text.hpp"

namespace feedplan {

//! One problem with user input.
struct InputProblem {
  std::string field;    //!< field path or location, e.g. "trochoid.pitch_mm" or "line 12"
  std::string message;  //!< the value and what was expected, e.g. "= 12: must be in (0, 10)"
};

//! Formats a problem as one line: "<field> <message>".
inline std::string to_string(const InputProblem& problem) {
  if (problem.field.empty()) return problem.message;
  return problem.field + " " + problem.message;
}

//! Thrown when user input is invalid; what() lists every problem, one per line. Problems quote the
//! input, which may hold any bytes: a byte that does not belong to UTF-8 text is shown as '?', so
//! that every message is UTF-8 (it may go into JSON, which holds nothing else).
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<InputProblem> problems)
      : std::runtime_error(join(as_utf8(problems))), problems_(std::move(problems)) {}
  InputError(std::string field, std::string message)
      : InputError(std::vector<InputProblem>{{std::move(field), std::move(message)}}) {}

  //! Every problem found, in the order they were found.
  const std::vector<InputProblem>& problems() const { return problems_; }

 private:
  static std::vector<InputProblem>& as_utf8(std::vector<InputProblem>& problems) {
    for (auto& p : problems) {
      if (first_non_utf8_byte(p.field)) p.field = utf8_shown(p.field);
      if (first_non_utf8_byte(p.message)) p.message = utf8_shown(p.message);
    }
    return problems;
  }
  static std::string join(const std::vector<InputProblem>& problems) {
    std::string text;
    for (const auto& p : problems) {
      if (!text.empty()) text += '\n';
      text += to_string(p);
    }
    return text;
  }
  std::vector<InputProblem> problems_;
};

}  // namespace feedplan
