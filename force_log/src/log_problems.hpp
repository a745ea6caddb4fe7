#pragma once
// The problems found in one force log, capped so that a log broken on every line still gives a
// readable message. Internal to the force_log module.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/core/problem_list.hpp"

namespace feedplan::force_log::detail {

inline constexpr std::size_t kMaxProblems = 20;

// Names each problem by its place in the log and collects it in core's ProblemList: up to kMaxProblems,
// then counted ("… and K more problems").
class Problems {
 public:
  explicit Problems(std::string source)
      : source_(std::move(source)), list_(ProblemList::capped(kMaxProblems, ProblemCap::kCountTheRest, source_)) {}

  // A problem at 1-based `line` (0: the whole file) and `where` in it ("column 3 (fx_n)", "(header)").
  void add(std::size_t line, const std::string& where, const std::string& message) {
    std::string field = source_;
    if (line > 0) field += " line " + std::to_string(line);
    if (!where.empty()) field += (line > 0 && where.front() != '(' ? ", " : " ") + where;
    list_.add(std::move(field), message);
  }
  bool empty() const { return list_.empty(); }
  // Throws every problem found as one InputError.
  [[noreturn]] void raise() { throw InputError(list_.take()); }
  void raise_if_any() { list_.throw_if_any(); }

 private:
  std::string source_;
  ProblemList list_;
};

}  // namespace feedplan::force_log::detail
