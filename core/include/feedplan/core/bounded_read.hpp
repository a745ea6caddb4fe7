#pragma once
// Reading an input file with a ceiling on its size. A path may name /dev/zero, a pipe that never ends
// or a log of the wrong machine: read whole, it takes memory without bound before any check can run.
// Each reader sets the ceiling of its format and says in its message what the format is for.

#include <cstddef>
#include <istream>
#include <string>

namespace feedplan {

//! Reads the rest of `in` into `text`. Returns false, leaving `text` at `max_bytes` bytes, when `in`
//! holds more than `max_bytes`; true otherwise (`in.bad()` then tells whether a read failed).
inline bool read_at_most(std::istream& in, std::size_t max_bytes, std::string& text) {
  text.clear();
  constexpr std::size_t kChunk = 1 << 16;
  std::string chunk(kChunk, '\0');
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(kChunk));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (text.size() + got > max_bytes) {
      text.append(chunk, 0, max_bytes - text.size());
      return false;
    }
    text.append(chunk, 0, got);
  }
  return true;
}

//! `bytes` for a message: "64 MiB", "512 KiB", "700 bytes" (whole units only when exact).
inline std::string byte_size_text(std::size_t bytes) {
  if (bytes >= (1u << 20) && bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  if (bytes >= (1u << 10) && bytes % (1u << 10) == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}

}  // namespace feedplan
