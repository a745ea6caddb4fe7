#pragma once
// Output paths a command will write: checked with the other flags, before anything is written.

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::cli {

//! Adds a problem for `flag` unless `path` is empty or names a file (new or existing) in an existing
//! directory.
inline void check_output_path(const std::string& flag, const std::string& path, std::vector<InputProblem>& problems) {
  namespace fs = std::filesystem;
  if (path.empty()) return;
  const fs::path p(path);
  const fs::path directory = p.has_parent_path() ? p.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    problems.push_back({flag, "= '" + path + "': directory '" + directory.string() + "' does not exist"});
  } else if (fs::is_directory(p, ec)) {
    problems.push_back({flag, "= '" + path + "': is a directory, expected a file name"});
  }
}

}  // namespace feedplan::cli
