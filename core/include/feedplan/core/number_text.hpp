#pragma once
// Numbers as they appear in messages, metadata, logs and reports ("= 0.1: must be > 0", "12.50 mm").
// Three formats, kept apart on purpose because their texts differ and tests pin them: the shortest text
// that reads back as the same double, what `std::ostream << value` writes (6 significant digits), and a
// fixed count of decimals. All are locale-independent ('.' as the decimal point).

#include <array>
#include <charconv>
#include <cmath>
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

//! `value` with up to 6 significant digits, as printf's "%g" writes it in the C locale (and a default
//! `std::ostringstream << value`): "0.333333", "1e+06", "inf", "-inf"; every NaN is "nan" (whatever its
//! sign bit).
inline std::string six_digit_number_text(double value) {
  if (std::isnan(value)) return "nan";
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::general, 6);
  return std::string(buffer.data(), result.ptr);
}

//! `value` with exactly `decimals` (≥ 0) digits after the point, correctly rounded: "12.50", "-0.100",
//! "3" for 0 decimals. NaN is "nan", infinities "inf" and "-inf".
inline void append_fixed_number_text(std::string& out, double value, int decimals) {
  std::array<char, 400> buffer{};  // room for the largest double in full
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, decimals);
  out.append(buffer.data(), result.ptr);
}

//! The text append_fixed_number_text appends.
inline std::string fixed_number_text(double value, int decimals) {
  std::string text;
  append_fixed_number_text(text, value, decimals);
  return text;
}

}  // namespace feedplan
