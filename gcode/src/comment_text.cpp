#include "comment_text.hpp"

#include <cassert>
#include <cctype>
#include <cstdint>

namespace feedplan::gcode::detail {

namespace {

// Length of the UTF-8 sequence that starts with `lead`, or 0 when `lead` cannot start one.
std::size_t sequence_length(unsigned char lead) {
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF) return 2;
  if (lead >= 0xE0 && lead <= 0xEF) return 3;
  if (lead >= 0xF0 && lead <= 0xF4) return 4;
  return 0;
}

// The code point of a well-formed sequence at `text[i]` of `length` bytes, or 0 when the
// continuation bytes are not 10xxxxxx.
std::uint32_t code_point(std::string_view text, std::size_t i, std::size_t length) {
  static constexpr unsigned char kLeadMask[] = {0, 0x7F, 0x1F, 0x0F, 0x07};
  std::uint32_t value = static_cast<unsigned char>(text[i]) & kLeadMask[length];
  for (std::size_t k = 1; k < length; ++k) {
    const auto byte = static_cast<unsigned char>(text[i + k]);
    if ((byte & 0xC0) != 0x80) return 0;
    value = (value << 6) | (byte & 0x3F);
  }
  return value;
}

// Text for one non-ASCII character: a transliteration where one is obvious in a tool or program
// name, '?' otherwise.
const char* transliterated(std::uint32_t code) {
  switch (code) {
    case 0x00D8: case 0x00F8: case 0x2300: return "D";  // Ø ø ⌀ (diameter)
    case 0x00B0: return "deg";                          // °
    case 0x00B5: case 0x03BC: return "u";               // µ (micro sign), μ (Greek mu)
    default: return "?";
  }
}

std::string ascii_replacement(char c) {
  switch (c) {
    case '(': return "[";
    case ')': return "]";
    case '\t': return " ";
    case '%': case ';': return "?";
    default: break;
  }
  const auto byte = static_cast<unsigned char>(c);
  if (byte < 0x20 || byte == 0x7F) return "?";
  return std::string(1, c);
}

}  // namespace

std::string safe_comment_text(std::string_view text, bool upper_case, std::size_t max_length) {
  assert(max_length >= 4);
  std::string result;
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    std::size_t length = sequence_length(lead);
    if (length == 1) {
      result += ascii_replacement(text[i]);
      ++i;
      continue;
    }
    std::uint32_t code = 0;
    if (length != 0 && i + length <= text.size()) code = code_point(text, i, length);
    if (code == 0) {
      result += '?';  // an invalid byte: one '?' for it, then go on with the next byte
      ++i;
      continue;
    }
    result += transliterated(code);
    i += length;
  }
  const std::size_t first = result.find_first_not_of(' ');
  if (first == std::string::npos) return "";
  result = result.substr(first, result.find_last_not_of(' ') - first + 1);
  if (upper_case) {
    for (char& c : result) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  if (result.size() > max_length) {
    result.resize(max_length - 3);
    while (!result.empty() && result.back() == ' ') result.pop_back();
    result += "...";
  }
  return result;
}

}  // namespace feedplan::gcode::detail
