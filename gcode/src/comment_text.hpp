#pragma once
// User text (tool names, program names, header values) made safe to stand inside a G-code comment
// on every dialect the writer speaks. Internal to the gcode module; writer.hpp states the rules.

#include <cstddef>
#include <string>
#include <string_view>

namespace feedplan::gcode::detail {

//! `text` (UTF-8; invalid bytes are tolerated) as comment text: '(' ')' → '[' ']'; '%', ';',
//! control characters, DEL and other non-printables → '?', tab → ' '; 'Ø' 'ø' '⌀' → "D", '°' →
//! "deg", 'µ' 'μ' → "u", any other non-ASCII character (or invalid byte) → '?'; leading and trailing
//! spaces removed; upper-cased when `upper_case`; cut to `max_length` characters (≥ 4), a cut text
//! ending in "...". The result contains printable ASCII only and no '(' ')' ';' '%'.
std::string safe_comment_text(std::string_view text, bool upper_case, std::size_t max_length);

}  // namespace feedplan::gcode::detail
