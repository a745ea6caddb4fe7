#pragma once
// Numbers as they appear in messages and metadata ("= 0.1: must be > 0"). Two formats, kept apart
// on purpose because their texts differ and tests pin them: the shortest text that reads back as the
// same double, and what `std::ostream << value` writes (6 significant digits).

#include <array>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string>

namespace feedplan {

//! Shortest text that reads back as the same double, locale-independent: "796", "0.1",
//! "0.30000000000000004", "1e+20". NaN of either sign is "nan", infinities "inf" and "-inf".
inline std::string shortest_number_text(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::general);
  return std::string(buffer.data(), result.ptr);
}

//! `value` exactly as a default `std::ostringstream << value` writes it: up to 6 significant digits
//! ("0.333333", "1e+06"), infinities "inf" and "-inf", NaN "nan" or, with the sign bit set, "-nan".
inline std::string six_digit_number_text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace feedplan
