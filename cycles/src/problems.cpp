#include "problems.hpp"

#include <cmath>

#include "feedplan/core/number_text.hpp"

namespace feedplan::cycles::detail {

std::string format_point(const geometry::Point2& point) {
  // Appended piecewise: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
  std::string text = "[";
  text += six_digit_number_text(point.x_mm);
  text += ", ";
  text += six_digit_number_text(point.y_mm);
  text += "]";
  return text;
}

bool Range::contains(double value) const {
  if (!std::isfinite(value)) return false;
  const bool low_ok = std::isinf(low) || (low_closed ? value >= low : value > low);
  const bool high_ok = std::isinf(high) || (high_closed ? value <= high : value < high);
  return low_ok && high_ok;
}

std::string Range::text() const {
  const bool has_low = !std::isinf(low);
  const bool has_high = !std::isinf(high);
  if (has_low && has_high) {
    return std::string(low_closed ? "[" : "(") + six_digit_number_text(low) + ", " + six_digit_number_text(high) +
           (high_closed ? "]" : ")");
  }
  if (has_low) return std::string(low_closed ? "≥ " : "> ") + six_digit_number_text(low);
  if (has_high) return std::string(high_closed ? "≤ " : "< ") + six_digit_number_text(high);
  return "any finite number";
}

bool check(std::vector<InputProblem>& problems, const std::string& field, double value, const Range& range,
           const std::string& why) {
  if (range.contains(value)) return true;
  const bool bounded = !std::isinf(range.low) || !std::isinf(range.high);
  std::string message = "= " + six_digit_number_text(value) + ": must be ";
  if (!std::isfinite(value)) {
    message += "a finite number";
    if (bounded) message += (!std::isinf(range.low) && !std::isinf(range.high) ? " in " : " ") + range.text();
  } else {
    message += (!std::isinf(range.low) && !std::isinf(range.high) ? "in " : "") + range.text();
  }
  if (!why.empty()) message += " — " + why;
  problems.push_back({field, message});
  return false;
}

bool check_finite(std::vector<InputProblem>& problems, const std::string& field, double value) {
  if (std::isfinite(value)) return true;
  problems.push_back({field, "= " + six_digit_number_text(value) + ": must be a finite number"});
  return false;
}

bool check_finite(std::vector<InputProblem>& problems, const std::string& field, const geometry::Point2& point) {
  if (std::isfinite(point.x_mm) && std::isfinite(point.y_mm)) return true;
  problems.push_back({field, "= " + format_point(point) + ": coordinates must be finite numbers (mm)"});
  return false;
}

}  // namespace feedplan::cycles::detail
