#pragma once
// Building InputProblems that name the value, the allowed range and the reason
// (STYLE.md, "Errors"). Internal to the cycles module.

#include <limits>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/point.hpp"

namespace feedplan::cycles::detail {

//! "[x, y]".
std::string format_point(const geometry::Point2& point);

//! An interval of allowed values; an infinite bound is no bound.
struct Range {
  double low = -std::numeric_limits<double>::infinity();  //!< lower bound
  bool low_closed = false;                                //!< the lower bound itself is allowed
  double high = std::numeric_limits<double>::infinity();  //!< upper bound
  bool high_closed = false;                               //!< the upper bound itself is allowed

  bool contains(double value) const;
  std::string text() const;  //!< "(0, 10)", "> 5", "≥ 1", "≤ 20"
};

inline Range above(double low) { return {low, false}; }
inline Range at_least(double low) { return {low, true}; }
inline Range open_range(double low, double high) { return {low, false, high, false}; }

//! Appends `<field> = <value>: must be in <range> — <why>` (or "must be a finite number in ..." for
//! NaN and infinities) unless the value is finite and in range. Returns true when it was fine.
bool check(std::vector<InputProblem>& problems, const std::string& field, double value, const Range& range,
           const std::string& why = "");

//! Appends `<field> = <value>: must be a finite number` unless it is one. Returns true when fine.
bool check_finite(std::vector<InputProblem>& problems, const std::string& field, double value);

//! Same for both coordinates of a point.
bool check_finite(std::vector<InputProblem>& problems, const std::string& field, const geometry::Point2& point);

}  // namespace feedplan::cycles::detail
