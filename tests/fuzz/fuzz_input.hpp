#pragma once
// What every harness does with one input: hand it to a reader as text and accept one outcome besides
// success, the reader's InputError (with a UTF-8 message). Anything else escaping (std::bad_alloc, std::out_of_range,
// nlohmann's or yaml-cpp's own exceptions) reaches std::terminate, which libFuzzer records as a crash —
// as are the sanitizers' findings and inputs that run past -timeout or -rss_limit_mb.

#include <cstddef>
#include <cstdint>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/utf8_text.hpp"

namespace feedplan::fuzz {

//! `data` as the text a reader gets from a file.
inline std::string input_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

//! Runs `read` on the text; an InputError is a correct answer to bad input. A message must name
//! something (an InputError without problems would print nothing to the user) and be UTF-8 whatever
//! the input's bytes: messages reach JSON (`--json` output), which holds nothing else.
template <typename Read>
void read_or_refuse(const std::uint8_t* data, std::size_t size, Read read) {
  try {
    read(input_text(data, size));
  } catch (const InputError& error) {
    if (error.problems().empty()) __builtin_trap();
    if (first_non_utf8_byte(error.what())) __builtin_trap();
  }
}

}  // namespace feedplan::fuzz
