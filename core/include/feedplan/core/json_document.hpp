#pragma once
// The one way feedplan parses a JSON document a user hands it (a plan report, a model database
// export): text that is not JSON, and JSON nested deeper than any feedplan document, are InputErrors
// naming the source. The depth bound matters beyond the message: nlohmann's dump() recurses once per
// level, and a problem shows the value it found, so 100 000 nested arrays would overflow the stack
// while the message is written.
//
// Templates over the document type (nlohmann::json or nlohmann::ordered_json), like json_fields.hpp.

#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "feedplan/core/input_error.hpp"

namespace feedplan {

//! The deepest nesting of arrays and objects accepted. feedplan's own documents nest at most 4 levels
//! (a plan report's path_learning.measurements rows); the bound leaves room and keeps dump() and every
//! recursive walk well inside the stack.
inline constexpr int kMaxJsonNestingDepth = 64;

//! Where a JSON text first nests arrays and objects deeper than `max_depth`: its 1-based line, or 0
//! when it never does. Brackets inside strings do not count; the text need not be valid JSON.
inline std::size_t json_line_nested_deeper_than(std::string_view text, int max_depth) {
  int depth = 0;
  std::size_t line = 1;
  bool in_string = false;
  bool escaped = false;
  for (const char c : text) {
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return line;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return 0;
}

//! Parses `text` (named `source_name` in problems) as a JSON document. Throws InputError when it
//! nests deeper than kMaxJsonNestingDepth ("… line 3: nests arrays and objects deeper than 64 levels
//! …") or is not valid JSON ("… is not valid JSON: <nlohmann's reason, with the byte position>", also
//! for a number beyond a double's range and for text that is not UTF-8).
template <typename Json>
Json parse_json_document(std::string_view text, const std::string& source_name) {
  if (const std::size_t line = json_line_nested_deeper_than(text, kMaxJsonNestingDepth); line != 0) {
    throw InputError(source_name, "line " + std::to_string(line) + ": nests arrays and objects deeper than " +
                                      std::to_string(kMaxJsonNestingDepth) +
                                      " levels: not a feedplan document (they nest a few levels)");
  }
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::exception& error) {  // parse_error, and out_of_range for 1e400
    throw InputError(source_name, std::string("is not valid JSON: ") + error.what());
  }
}

}  // namespace feedplan
