#pragma once
// Writing an output file so that it is either complete or untouched: the text goes to a temporary
// file beside the target, which is then renamed over it (rename is atomic on POSIX file systems).

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include <unistd.h>

namespace feedplan {

//! Writes `content` to `path` atomically. Returns an empty string on success, otherwise a message
//! naming the path and the reason; on failure the target is left as it was.
inline std::string write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  namespace fs = std::filesystem;
  const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) return "cannot write " + path.string() + ": directory " + directory.string() + " does not exist";
  // Built with append: GCC 12 warns falsely (-Wrestrict) on "." + std::string when inlined.
  std::string temporary_name = ".";
  temporary_name.append(path.filename().string()).append(".tmp").append(std::to_string(::getpid()));
  const fs::path temporary = directory / temporary_name;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) return "cannot write " + path.string() + ": cannot create " + temporary.string();
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(temporary, ec);
      return "cannot write " + path.string() + ": write failed (disk full?)";
    }
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    return "cannot write " + path.string() + ": " + ec.message();
  }
  return {};
}

}  // namespace feedplan
