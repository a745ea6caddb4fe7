#pragma once
// Reading an input file with a ceiling on its size. A path may name /dev/zero, a pipe that never ends
// or a log of the wrong machine: read whole, it takes memory without bound before any check can run.
// Each reader sets the ceiling of its format and says in its message what the format is for.

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <istream>
#include <string>

#include "feedplan/core/input_error.hpp"

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

//! What a reader says about the file it reads whole (read_input_file).
struct InputFileKind {
  std::string what;       //!< what the file should be, e.g. "a plan report, JSON"
  std::size_t max_bytes;  //!< the ceiling
  std::string too_large;  //!< why a larger file is not one, e.g. "a plan of 100 000 blocks writes about 20 MiB"
};

//! The whole file at `path`, at most kind.max_bytes. InputError naming the path when it does not exist
//! ("no such file (expected …)"), is a directory, cannot be opened or read, or holds more than the
//! ceiling — a device or a pipe (/dev/zero) is read up to the ceiling like a file, never taken for a
//! missing one.
inline std::string read_input_file(const std::filesystem::path& path, const InputFileKind& kind) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(path.string(), "cannot be read: no such file (expected " + kind.what + ")");
  if (fs::is_directory(status)) throw InputError(path.string(), "cannot be read: it is a directory, not " + kind.what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot be read: permission denied or I/O error");
  std::string text;
  if (!read_at_most(in, kind.max_bytes, text)) {
    throw InputError(path.string(), "is larger than " + byte_size_text(kind.max_bytes) + ": not " + kind.what + " (" +
                                        kind.too_large + ")");
  }
  if (in.bad()) throw InputError(path.string(), "cannot be read: I/O error");
  return text;
}

}  // namespace feedplan
