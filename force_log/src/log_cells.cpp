#include "log_cells.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

namespace feedplan::force_log::detail {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::string lower(std::string_view text) {
  std::string result(text);
  std::transform(result.begin(), result.end(), result.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return result;
}

std::vector<std::string_view> split(std::string_view line, char separator) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    cells.push_back(trim(line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start)));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return cells;
}

std::vector<std::string_view> lines_of(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::vector<std::string_view> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    start = end + 1;
  }
  return lines;
}

std::optional<double> parse_number(std::string_view cell) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  double value = 0;
  const auto result = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (result.ec != std::errc() || result.ptr != cell.data() + cell.size()) return std::nullopt;
  return value;
}

std::string column_label(std::size_t index, const std::string& name) {
  return "column " + std::to_string(index + 1) + " (" + name + ")";
}

bool read_cell(Problems& problems, std::size_t line, std::size_t index, const std::string& name,
               std::string_view cell, double& value) {
  if (cell.empty()) {
    value = kNaN;
    return true;
  }
  const std::optional<double> number = parse_number(cell);
  if (!number) {
    problems.add(line, column_label(index, name), "= \"" + std::string(cell) + "\": not a number");
    return false;
  }
  if (!std::isfinite(*number)) {
    problems.add(line, column_label(index, name),
                 "= \"" + std::string(cell) + "\": must be a finite number (leave the cell empty when the value was "
                 "not recorded)");
    return false;
  }
  value = *number;
  return true;
}

}  // namespace feedplan::force_log::detail
