#pragma once
// Whether text is UTF-8. Every text a user hands feedplan may end up in JSON (plan reports, `db list
// --json`, exports), and JSON is UTF-8: nlohmann's dump() throws on anything else, so a name in
// Latin-1 stored today would break every later export. The readers and the store check text where
// it enters, and name where it is not UTF-8.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace feedplan {

//! The 0-based byte offset of the first byte of `text` that does not begin a well-formed UTF-8
//! sequence (RFC 3629: no overlong forms, no surrogates, nothing above U+10FFFF), or nothing when
//! the whole text is UTF-8.
inline std::optional<std::size_t> first_non_utf8_byte(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    std::size_t length = 0;
    unsigned char low = 0x80;   // the allowed range of the second byte
    unsigned char high = 0xBF;
    if (lead < 0x80) {
      length = 1;
    } else if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      if (lead == 0xE0) low = 0xA0;   // overlong
      if (lead == 0xED) high = 0x9F;  // surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      if (lead == 0xF0) low = 0x90;   // overlong
      if (lead == 0xF4) high = 0x8F;  // above U+10FFFF
    } else {
      return i;
    }
    if (i + length > text.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const unsigned char c = byte(i + k);
      const unsigned char min = k == 1 ? low : 0x80;
      const unsigned char max = k == 1 ? high : 0xBF;
      if (c < min || c > max) return i;
    }
    i += length;
  }
  return std::nullopt;
}

//! `text` with every byte that does not begin a well-formed UTF-8 sequence replaced by '?', so that
//! a message can show the rest of a value that is not UTF-8 (and stay UTF-8 itself).
inline std::string utf8_shown(std::string_view text) {
  std::string shown;
  while (true) {
    const std::optional<std::size_t> at = first_non_utf8_byte(text);
    if (!at) break;
    shown.append(text.substr(0, *at)).push_back('?');
    text.remove_prefix(*at + 1);
  }
  return shown.append(text);
}

//! Empty when `text` is UTF-8; otherwise "is not UTF-8 text (byte N is 0xHH)", N 1-based, for a
//! problem's message (the caller adds what to do: the advice differs for a file and a flag).
inline std::string utf8_problem(std::string_view text) {
  const std::optional<std::size_t> at = first_non_utf8_byte(text);
  if (!at) return {};
  static constexpr char kHex[] = "0123456789ABCDEF";
  const auto value = static_cast<unsigned char>(text[*at]);
  return "is not UTF-8 text (byte " + std::to_string(*at + 1) + " is 0x" + kHex[value >> 4] + kHex[value & 0xF] + ")";
}

}  // namespace feedplan
