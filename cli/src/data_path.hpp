#pragma once
// Where the bundled data (materials.yaml) is: $FEEDPLAN_DATA_DIR, else the installed copy, else the
// source tree (running from a build directory).

#include <cstdlib>
#include <filesystem>
#include <string>

namespace feedplan::cli {

//! Path of the bundled materials file.
inline std::string bundled_materials_path() {
  if (const char* dir = std::getenv("FEEDPLAN_DATA_DIR")) return std::string(dir) + "/materials.yaml";
  std::error_code ec;
  const std::filesystem::path installed = std::filesystem::path(FEEDPLAN_INSTALLED_DATA_DIR) / "materials.yaml";
  if (std::filesystem::exists(installed, ec)) return installed.string();
  return (std::filesystem::path(FEEDPLAN_SOURCE_DATA_DIR) / "materials.yaml").string();
}

}  // namespace feedplan::cli
