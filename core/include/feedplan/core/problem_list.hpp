#pragma once
// The one collector of input problems (STYLE.md, "Errors"): readers and validators add every problem they
// find, each naming its field, and throw them together as one InputError.
//
// A reader of a file that may be broken on every line caps the list, so that the message stays readable:
//   - ProblemCap::kStopAfter: the first problem past the cap is replaced by "more problems follow; stopped
//     after N" and full() tells the reader it may stop reading;
//   - ProblemCap::kCountTheRest: problems past the cap are counted, and "… and K more problems" closes the
//     list when it is thrown.
// Validators of values add "<prefix><field> = <value>: <rule>" through add_value() and the checks below.

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan {

//! How a capped list ends.
enum class ProblemCap {
  kNone,          //!< no cap
  kStopAfter,     //!< "more problems follow; stopped after N", then nothing more
  kCountTheRest,  //!< keep counting; "… and K more problems" when thrown
};

class ProblemList {
 public:
  //! An uncapped list; add_value() names fields "<field_prefix><field>" (e.g. prefix "model.").
  explicit ProblemList(std::string field_prefix = "") : field_prefix_(std::move(field_prefix)) {}

  //! A list capped at `max_problems` (≥ 1) by `cap`. The closing problem is filed under `closing_field`,
  //! or, when that is empty, under the field of the problem that overflowed.
  static ProblemList capped(std::size_t max_problems, ProblemCap cap, std::string closing_field = "") {
    ProblemList list;
    list.max_problems_ = max_problems < 1 ? 1 : max_problems;
    list.cap_ = cap;
    list.closing_field_ = std::move(closing_field);
    return list;
  }

  //! Records one problem (or, past the cap, what the cap says).
  void add(std::string field, std::string message) {
    if (cap_ == ProblemCap::kNone || problems_.size() < max_problems_) {
      problems_.push_back({std::move(field), std::move(message)});
    } else if (cap_ == ProblemCap::kCountTheRest) {
      ++dropped_;
    } else if (!full()) {
      problems_.push_back({closing_field_.empty() ? std::move(field) : closing_field_,
                           "more problems follow; stopped after " + std::to_string(max_problems_)});
    }
  }

  //! Records every problem of `problems`, in order.
  void add_all(const std::vector<InputProblem>& problems) {
    for (const InputProblem& p : problems) add(p.field, p.message);
  }

  //! Records "<prefix><field>" with "= <value_text>: <rule>".
  void add_value(const std::string& field, const std::string& value_text, const std::string& rule) {
    add(field_prefix_ + field, "= " + value_text + ": " + rule);
  }

  //! A problem unless `value` is finite.
  void finite(const std::string& field, double value) {
    if (!std::isfinite(value)) add_value(field, shortest_number_text(value), "must be finite");
  }
  //! A problem unless `value` is finite and > 0.
  void positive(const std::string& field, double value) {
    if (!std::isfinite(value) || value <= 0.0) add_value(field, shortest_number_text(value), "must be finite and > 0");
  }
  //! A problem unless `value` is finite and ≥ 0.
  void non_negative(const std::string& field, double value) {
    if (!std::isfinite(value) || value < 0.0) add_value(field, shortest_number_text(value), "must be finite and ≥ 0");
  }

  bool empty() const { return problems_.empty() && dropped_ == 0; }
  //! True once a kStopAfter list has closed: the reader may stop reading.
  bool full() const { return cap_ == ProblemCap::kStopAfter && problems_.size() > max_problems_; }

  //! Every problem recorded, closed as the cap says; the list is left empty.
  std::vector<InputProblem> take() {
    if (dropped_ > 0) {
      problems_.push_back({closing_field_, "… and " + std::to_string(dropped_) + " more problems"});
      dropped_ = 0;
    }
    return std::move(problems_);
  }

  //! Throws every problem as one InputError when there is any.
  void throw_if_any() {
    if (!empty()) throw InputError(take());
  }

 private:
  std::string field_prefix_;
  std::size_t max_problems_ = std::numeric_limits<std::size_t>::max();
  ProblemCap cap_ = ProblemCap::kNone;
  std::string closing_field_;
  std::vector<InputProblem> problems_;
  std::size_t dropped_ = 0;
};

}  // namespace feedplan
