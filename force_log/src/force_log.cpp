// Reading and loading force logs: the format is recognised from the first line that is not blank
// (a Kistler DynoWare export starts with "DynoWare"; anything else is read as feedplan CSV).

#include "feedplan/force_log/force_log.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <system_error>

#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan_csv_reader.hpp"
#include "kistler_dynoware_reader.hpp"
#include "log_cells.hpp"

namespace feedplan::force_log {

std::string ForceLog::metadata_value(const std::string& key) const {
  for (const auto& [k, v] : metadata) {
    if (k == key) return v;
  }
  return {};
}

ForceLog read_force_log(const std::string& text, const std::string& source_name) {
  using detail::trim;
  const std::vector<std::string_view> lines = detail::lines_of(text);
  const auto first = std::find_if(lines.begin(), lines.end(), [](std::string_view l) { return !trim(l).empty(); });
  if (first != lines.end() && trim(*first).rfind("DynoWare", 0) == 0) {
    return detail::read_kistler_dynoware(lines, static_cast<std::size_t>(first - lines.begin()), source_name);
  }
  return detail::read_feedplan_csv(lines, source_name);
}

ForceLog load_force_log(const std::string& path, std::size_t max_file_bytes) {
  const std::string text =
      read_input_file(path, {"a force log", max_file_bytes, "split the recording into parts of at most that size"});
  return read_force_log(text, path);
}

}  // namespace feedplan::force_log
