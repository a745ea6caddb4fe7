#pragma once
// Force-log text as lines and comma-separated cells, and one cell as a number. Shared by the
// feedplan CSV and the Kistler DynoWare readers. Internal to the force_log module.

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "log_problems.hpp"

namespace feedplan::force_log::detail {

// An empty cell: the value was not recorded.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// `text` without leading and trailing spaces, tabs and carriage returns.
std::string_view trim(std::string_view text);

// `text` with ASCII letters lower-cased.
std::string lower(std::string_view text);

// The cells of `line` between `separator`s, each trimmed.
std::vector<std::string_view> split(std::string_view line, char separator);

// Lines without their terminators ("\n" or "\r\n"); a UTF-8 byte-order mark is dropped.
std::vector<std::string_view> lines_of(std::string_view text);

// A cell as a number: nullopt when it is not one (the whole cell must be the number).
std::optional<double> parse_number(std::string_view cell);

// "column <index + 1> (<name>)", where problems with a cell point.
std::string column_label(std::size_t index, const std::string& name);

// Parses one data cell into `value` (NaN for an empty cell); reports what is wrong with it.
// Returns false on a problem.
bool read_cell(Problems& problems, std::size_t line, std::size_t index, const std::string& name,
               std::string_view cell, double& value);

}  // namespace feedplan::force_log::detail
