#pragma once
// The problems found in one force log, capped so that a log broken on every line still gives a
// readable message. Internal to the force_log module.

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::force_log::detail {

inline constexpr std::size_t kMaxProblems = 20;

// Collects problems up to kMaxProblems and counts the rest.
class Problems {
 public:
  explicit Problems(std::string source) : source_(std::move(source)) {}

  // A problem at 1-based `line` (0: the whole file) and `where` in it ("column 3 (fx_n)", "(header)").
  void add(std::size_t line, const std::string& where, const std::string& message) {
    if (list_.size() >= kMaxProblems) {
      ++dropped_;
      return;
    }
    std::string field = source_;
    if (line > 0) field += " line " + std::to_string(line);
    if (!where.empty()) field += (line > 0 && where.front() != '(' ? ", " : " ") + where;
    list_.push_back({field, message});
  }

  bool empty() const { return list_.empty(); }

  // Throws every problem found as one InputError.
  [[noreturn]] void raise() {
    if (dropped_ > 0) list_.push_back({source_, "… and " + std::to_string(dropped_) + " more problems"});
    throw InputError(std::move(list_));
  }

  void raise_if_any() {
    if (!list_.empty()) raise();
  }

 private:
  std::string source_;
  std::vector<InputProblem> list_;
  std::size_t dropped_ = 0;
};

}  // namespace feedplan::force_log::detail
