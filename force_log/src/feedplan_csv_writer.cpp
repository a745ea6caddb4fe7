// The feedplan force-log CSV writer: "# key: value" metadata lines, the header row, one row per
// sample with fixed decimals per column and empty cells for values not recorded.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string_view>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "log_columns.hpp"
#include "log_text.hpp"

namespace feedplan::force_log {

using namespace detail;

namespace {

// Fixed-point text with `decimals` digits after '.', locale-independent; "-0.000" becomes "0.000".
void append_fixed(std::string& out, double value, int decimals) {
  std::string text = fixed_number_text(value, decimals);
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  out += text;
}

// Metadata text on one line: line breaks become spaces.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

}  // namespace

void detail::append_force_log_header(std::string& out, const ForceLog& log) {
  for (const auto& [key, value] : log.metadata) {
    std::string clean_key = one_line(key);
    std::replace(clean_key.begin(), clean_key.end(), ':', '_');
    out += "# " + clean_key + ": " + one_line(value) + "\n";
  }
  const int column_count = log.has_currents ? kColumnCount : kIx;
  for (int c = 0; c < column_count; ++c) {
    if (c > 0) out += ',';
    out += kColumnNames[c];
  }
  out += '\n';
}

void detail::append_force_log_row(std::string& out, const ForceLog& log, const ForceLogRow& row) {
  const int column_count = log.has_currents ? kColumnCount : kIx;
  for (int c = 0; c < column_count; ++c) {
    if (c > 0) out += ',';
    const bool omitted = (!log.has_positions && (c == kX || c == kY || c == kZ)) ||
                         (!log.has_forces && (c == kFx || c == kFy || c == kFz));
    const double value = cell_of(row, c);
    if (omitted || std::isnan(value)) continue;  // empty cell: not recorded
    append_fixed(out, value, kDecimals[c]);
  }
  out += '\n';
}

std::string format_force_log(const ForceLog& log) {
  std::string out;
  out.reserve(128 + log.rows.size() * (log.has_currents ? 110 : 80));
  append_force_log_header(out, log);
  for (const ForceLogRow& row : log.rows) append_force_log_row(out, log, row);
  return out;
}

std::string write_force_log(const std::string& path, const ForceLog& log) {
  return write_file_atomically(path, format_force_log(log));
}

}  // namespace feedplan::force_log
