#pragma once
// The problems found while reading one program, each located by its line: collected up to a cap,
// then thrown together as one InputError (STYLE.md, "Errors"). Internal to the gcode module.

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/core/problem_list.hpp"

namespace feedplan::gcode::detail {

//! Problems of one program, field "<source> line N:" so that what() reads `part.ngc line 7: word Q5: …`;
//! collected by core's ProblemList, capped at `max_problems` (then "more problems follow …").
class ProblemLog {
 public:
  ProblemLog(std::string source_name, int max_problems)
      : source_name_(std::move(source_name)),
        problems_(ProblemList::capped(max_problems < 1 ? 1 : static_cast<std::size_t>(max_problems),
                                      ProblemCap::kStopAfter)) {}

  //! Records `message` for 1-based `line`. Past the cap, records one closing problem and then nothing.
  void add(int line, std::string message) { problems_.add(field(line), std::move(message)); }
  //! True once the cap is reached: the reader may stop reading.
  bool full() const { return problems_.full(); }
  bool empty() const { return problems_.empty(); }
  //! Throws the collected problems as one InputError (only when there are any).
  void throw_if_any() { problems_.throw_if_any(); }

 private:
  std::string field(int line) const {
    std::string text = source_name_.empty() ? std::string() : source_name_ + " ";
    return text + "line " + std::to_string(line) + ":";
  }

  std::string source_name_;
  ProblemList problems_;
};

}  // namespace feedplan::gcode::detail
