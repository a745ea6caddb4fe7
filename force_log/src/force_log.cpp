#include "feedplan/force_log/force_log.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/did_you_mean.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::force_log {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kMaxProblems = 20;

// The columns of our format, in the order the writer puts them.
enum Column { kT, kX, kY, kZ, kFx, kFy, kFz, kFeed, kRpm, kIx, kIy, kIz, kColumnCount };
const std::array<const char*, kColumnCount> kColumnNames = {
    "t_s", "x_mm", "y_mm", "z_mm", "fx_n", "fy_n", "fz_n", "feed_mm_per_min", "spindle_rpm", "ix_a", "iy_a", "iz_a"};
const std::array<int, kColumnCount> kDecimals = {6, 4, 4, 4, 3, 3, 3, 2, 1, 5, 5, 5};

// The field of `row` that holds `column` (const or not, as `row` is).
template <typename Row>
auto& cell_of(Row& row, int column) {
  switch (column) {
    case kT: return row.t_s;
    case kX: return row.x_mm;
    case kY: return row.y_mm;
    case kZ: return row.z_mm;
    case kFx: return row.fx_n;
    case kFy: return row.fy_n;
    case kFz: return row.fz_n;
    case kFeed: return row.feed_mm_per_min;
    case kRpm: return row.spindle_rpm;
    case kIx: return row.ix_a;
    case kIy: return row.iy_a;
    default: return row.iz_a;
  }
}

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

// Lines without their terminators ("\n" or "\r\n"); a UTF-8 byte-order mark is dropped.
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

// A cell as a number: nullopt when it is not one (the whole cell must be the number).
std::optional<double> parse_number(std::string_view cell) {
  if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
  double value = 0;
  const auto result = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (result.ec != std::errc() || result.ptr != cell.data() + cell.size()) return std::nullopt;
  return value;
}

// Fixed-point text with `decimals` digits after '.', locale-independent; "-0.000" becomes "0.000".
void append_fixed(std::string& out, double value, int decimals) {
  std::array<char, 64> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, decimals);
  std::string_view text(buffer.data(), static_cast<std::size_t>(result.ptr - buffer.data()));
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string_view::npos) text.remove_prefix(1);
  out += text;
}

// Metadata text on one line: line breaks become spaces.
std::string one_line(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

// Collects problems up to kMaxProblems and counts the rest.
class Problems {
 public:
  explicit Problems(std::string source) : source_(std::move(source)) {}

  void add(std::size_t line, const std::string& where, const std::string& message) {
    if (list_.size() >= kMaxProblems) {
      ++dropped_;
      return;
    }
    std::string field = source_;
    if (line > 0) field += " line " + std::to_string(line);
    if (!where.empty()) field += (line > 0 && where.front() != '(' ? ", " : " ") + where;
    list_.push_back({field, message});
  }

  bool empty() const { return list_.empty(); }

  [[noreturn]] void raise() {
    if (dropped_ > 0) list_.push_back({source_, "… and " + std::to_string(dropped_) + " more problems"});
    throw InputError(std::move(list_));
  }

  void raise_if_any() {
    if (!list_.empty()) raise();
  }

 private:
  std::string source_;
  std::vector<InputProblem> list_;
  std::size_t dropped_ = 0;
};

std::string column_label(std::size_t index, const std::string& name) {
  return "column " + std::to_string(index + 1) + " (" + name + ")";
}

// Parses one data cell into `value`; reports what is wrong with it. Returns false on a problem.
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

// Reports rows whose time does not increase.
void check_time_order(Problems& problems, const std::vector<ForceLogRow>& rows, const std::vector<std::size_t>& lines) {
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (std::isnan(rows[i].t_s) || std::isnan(rows[i - 1].t_s) || rows[i].t_s > rows[i - 1].t_s) continue;
    problems.add(lines[i], "t_s",
                 "= " + shortest_number_text(rows[i].t_s) + ": must be after " + shortest_number_text(rows[i - 1].t_s) +
                     " on line " + std::to_string(lines[i - 1]) + " — time must increase from row to row");
  }
}

// `lines[start]` is the "DynoWare,Version ..." line.
ForceLog read_kistler(const std::vector<std::string_view>& lines, std::size_t start, const std::string& source_name) {
  Problems problems(source_name);
  ForceLog log;
  log.has_positions = false;
  const std::vector<std::string_view> first = split(lines[start], ',');
  log.metadata.emplace_back("source", "Kistler DynoWare export" +
                                          (first.size() > 1 && !first[1].empty() ? " (" + std::string(first[1]) + ")"
                                                                                 : std::string()));
  std::size_t channel_line = 0;  // index into lines
  for (std::size_t i = start + 1; i < lines.size(); ++i) {
    const std::vector<std::string_view> cells = split(lines[i], ',');
    if (lower(cells[0]) == "time") {
      channel_line = i;
      break;
    }
    if (cells[0].empty()) continue;
    std::string key(cells[0]);
    if (key.back() == ':') key.pop_back();
    const std::string value = cells.size() > 1 ? std::string(cells[1]) : std::string();
    if (key == "Sampling rate [Hz]") {
      const std::optional<double> rate = parse_number(value);
      if (!rate || !std::isfinite(*rate) || *rate <= 0) {
        problems.add(i + 1, "Sampling rate [Hz]", "= \"" + value + "\": must be a number > 0 Hz");
      } else {
        log.metadata.emplace_back("sample_rate_hz", value);
      }
      continue;
    }
    if (!trim(value).empty()) log.metadata.emplace_back("dynoware." + key, value);
  }
  if (channel_line == 0) {
    problems.add(0, "", "is a Kistler DynoWare export without a channel row: expected a line Time,Fx,Fy,Fz after the "
                        "header block");
    problems.raise();
  }

  // Channels: Time, Fx, Fy required, Fz optional; other channels (Mz, ...) are ignored.
  const std::vector<std::string_view> channels = split(lines[channel_line], ',');
  const std::array<std::string, 4> wanted = {"time", "fx", "fy", "fz"};
  const std::array<int, 4> target = {kT, kFx, kFy, kFz};
  std::array<std::optional<std::size_t>, 4> index;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    for (std::size_t w = 0; w < wanted.size(); ++w) {
      if (lower(channels[c]) == wanted[w] && !index[w]) index[w] = c;
    }
  }
  for (std::size_t w = 1; w < 3; ++w) {
    if (!index[w]) {
      problems.add(channel_line + 1, "", "has no channel " + std::string(w == 1 ? "Fx" : "Fy") +
                                             ": a force log needs Time, Fx and Fy (found " +
                                             std::string(lines[channel_line]) + ")");
    }
  }
  problems.raise_if_any();

  // Units row: s for time, N or kN for forces.
  std::array<double, 4> scale = {1.0, 1.0, 1.0, 1.0};
  const std::size_t units_line = channel_line + 1;
  if (units_line >= lines.size()) {
    problems.add(units_line, "", "is missing: expected the units row (s,N,N,N) after the channel row");
    problems.raise();
  }
  const std::vector<std::string_view> units = split(lines[units_line], ',');
  for (std::size_t w = 0; w < wanted.size(); ++w) {
    if (!index[w]) continue;
    const std::string unit = *index[w] < units.size() ? std::string(units[*index[w]]) : std::string();
    const std::string label = column_label(*index[w], std::string(channels[*index[w]]));
    if (w == 0) {
      if (unit != "s") problems.add(units_line + 1, label, "= \"" + unit + "\": the time unit must be s");
    } else if (unit == "kN") {
      scale[w] = 1000.0;
    } else if (unit != "N") {
      problems.add(units_line + 1, label, "= \"" + unit + "\": the force unit must be N or kN");
    }
  }
  problems.raise_if_any();

  std::vector<std::size_t> row_lines;
  for (std::size_t i = units_line + 1; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    const std::vector<std::string_view> cells = split(lines[i], ',');
    if (cells.size() != channels.size()) {
      problems.add(i + 1, "", "has " + std::to_string(cells.size()) + " cells, the channel row (line " +
                                  std::to_string(channel_line + 1) + ") has " + std::to_string(channels.size()));
      continue;
    }
    ForceLogRow row{0, kNaN, kNaN, kNaN, 0, 0, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
    bool ok = true;
    for (std::size_t w = 0; w < wanted.size(); ++w) {
      if (!index[w]) continue;
      const std::string name(channels[*index[w]]);
      double value = kNaN;
      if (!read_cell(problems, i + 1, *index[w], name, cells[*index[w]], value)) {
        ok = false;
        continue;
      }
      if (std::isnan(value)) {
        problems.add(i + 1, column_label(*index[w], name), "is empty: every sample needs " + name);
        ok = false;
        continue;
      }
      cell_of(row, target[w]) = value * scale[w];
    }
    if (!ok) continue;
    log.rows.push_back(row);
    row_lines.push_back(i + 1);
  }
  if (log.rows.empty() && problems.empty()) {
    problems.add(units_line + 1, "", "is the last line: the export has no samples");
  }
  check_time_order(problems, log.rows, row_lines);
  problems.raise_if_any();
  return log;
}

ForceLog read_ours(const std::vector<std::string_view>& lines, const std::string& source_name) {
  Problems problems(source_name);
  ForceLog log;
  std::optional<std::size_t> header_line;  // index into lines
  std::vector<int> columns;                // header position → Column
  std::array<std::optional<std::size_t>, kColumnCount> position;
  std::vector<ForceLogRow> rows;
  std::vector<std::size_t> row_lines;

  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string_view line = trim(lines[i]);
    if (line.empty()) continue;
    if (line.front() == '#') {
      const std::string_view body = trim(line.substr(1));
      const std::size_t colon = body.find(':');
      if (colon != std::string_view::npos && colon > 0) {
        log.metadata.emplace_back(std::string(trim(body.substr(0, colon))), std::string(trim(body.substr(colon + 1))));
      }
      continue;
    }
    if (!header_line) {
      header_line = i;
      const std::vector<std::string_view> names = split(line, ',');
      std::vector<std::string> known(kColumnNames.begin(), kColumnNames.end());
      for (std::size_t c = 0; c < names.size(); ++c) {
        const std::string name(names[c]);
        const auto it = std::find(known.begin(), known.end(), name);
        if (it == known.end()) {
          std::string message = "= \"" + name + "\": unknown column; expected " + std::string(kColumnNames[0]);
          for (int k = 1; k < kColumnCount; ++k) message += std::string(", ") + kColumnNames[k];
          const std::string best = closest_name(name, known, LetterCase::kIgnored);
          if (!best.empty()) message += " (did you mean " + best + "?)";
          problems.add(i + 1, "column " + std::to_string(c + 1), message);
          columns.push_back(-1);
          continue;
        }
        const int column = static_cast<int>(it - known.begin());
        if (position[column]) {
          problems.add(i + 1, "column " + std::to_string(c + 1),
                       "= \"" + name + "\": repeats column " + std::to_string(*position[column] + 1));
          columns.push_back(-1);
          continue;
        }
        position[column] = c;
        columns.push_back(column);
      }
      std::vector<std::string> missing;
      for (int required : {kT, kX, kY}) {
        if (!position[required]) missing.emplace_back(kColumnNames[required]);
      }
      const bool forces = position[kFx] || position[kFy];
      const bool currents = position[kIx] || position[kIy];
      if (forces || !currents) {
        for (int required : {kFx, kFy}) {
          if (!position[required]) missing.emplace_back(kColumnNames[required]);
        }
      } else {
        for (int required : {kIx, kIy}) {
          if (!position[required]) missing.emplace_back(kColumnNames[required]);
        }
      }
      if (!missing.empty()) {
        std::string list;
        for (const auto& name : missing) list += (list.empty() ? "" : ", ") + name;
        problems.add(i + 1, "(header)",
                     "lacks the column" + std::string(missing.size() > 1 ? "s " : " ") + list +
                         ": a force log needs t_s, x_mm, y_mm and fx_n, fy_n (or the currents ix_a, iy_a)");
      }
      problems.raise_if_any();  // rows cannot be read against a broken header
      continue;
    }

    const std::vector<std::string_view> cells = split(line, ',');
    if (cells.size() != columns.size()) {
      problems.add(i + 1, "", "has " + std::to_string(cells.size()) + " cells, the header (line " +
                                  std::to_string(*header_line + 1) + ") has " + std::to_string(columns.size()));
      continue;
    }
    ForceLogRow row{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
    bool ok = true;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const int column = columns[c];
      if (!read_cell(problems, i + 1, c, kColumnNames[column], cells[c], cell_of(row, column))) ok = false;
    }
    if (std::isnan(row.t_s) && ok) {
      problems.add(i + 1, column_label(*position[kT], "t_s"), "is empty: every row needs its time");
      ok = false;
    }
    if (!ok) continue;
    rows.push_back(row);
    row_lines.push_back(i + 1);
  }

  if (!header_line) {
    problems.add(0, "", lines.empty() || std::all_of(lines.begin(), lines.end(), [](auto l) { return trim(l).empty(); })
                            ? "is empty: expected a force log (header row t_s,x_mm,y_mm,...,fx_n,fy_n then samples)"
                            : "has no header row: expected t_s,x_mm,y_mm,...,fx_n,fy_n after the # metadata lines");
    problems.raise();
  }
  if (rows.empty() && problems.empty()) {
    problems.add(*header_line + 1, "", "is the header, and no samples follow it");
  }

  // Column pairs that are all-or-nothing: x/y positions, fx/fy forces, ix/iy currents. A pair is
  // "recorded" when any of its cells holds a value; then every row must hold both.
  auto recorded = [&](int a, int b) {
    if (!position[a] || !position[b]) return false;
    return std::any_of(rows.begin(), rows.end(), [&](const ForceLogRow& r) {
      return !std::isnan(cell_of(r, a)) || !std::isnan(cell_of(r, b));
    });
  };
  auto require_full = [&](int a, int b, const std::string& what) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      for (int column : {a, b}) {
        if (!std::isnan(cell_of(rows[r], column))) continue;
        problems.add(row_lines[r], column_label(*position[column], kColumnNames[column]),
                     "is empty, but other rows record " + what + ": give it in every row or in none");
      }
    }
  };
  log.has_positions = recorded(kX, kY);
  log.has_forces = recorded(kFx, kFy);
  log.has_currents = recorded(kIx, kIy);
  if (log.has_positions) require_full(kX, kY, "positions");
  if (log.has_forces) require_full(kFx, kFy, "forces");
  if (log.has_currents) require_full(kIx, kIy, "currents");
  if (!rows.empty() && !log.has_forces && !log.has_currents) {
    problems.add(*header_line + 1, "(header)",
                 "fx_n, fy_n are empty in every row and there are no currents ix_a, iy_a: the log holds no force");
  }
  check_time_order(problems, rows, row_lines);
  problems.raise_if_any();
  log.rows = std::move(rows);
  return log;
}

}  // namespace

std::string ForceLog::metadata_value(const std::string& key) const {
  for (const auto& [k, v] : metadata) {
    if (k == key) return v;
  }
  return {};
}

std::string format_force_log(const ForceLog& log) {
  std::string out;
  out.reserve(128 + log.rows.size() * (log.has_currents ? 110 : 80));
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
  for (const ForceLogRow& row : log.rows) {
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
  return out;
}

std::string write_force_log(const std::string& path, const ForceLog& log) {
  return write_file_atomically(path, format_force_log(log));
}

ForceLog read_force_log(const std::string& text, const std::string& source_name) {
  const std::vector<std::string_view> lines = lines_of(text);
  const auto first = std::find_if(lines.begin(), lines.end(), [](std::string_view l) { return !trim(l).empty(); });
  if (first != lines.end() && trim(*first).rfind("DynoWare", 0) == 0) {
    return read_kistler(lines, static_cast<std::size_t>(first - lines.begin()), source_name);
  }
  return read_ours(lines, source_name);
}

ForceLog load_force_log(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path, "cannot be read: no such file (expected a force log)");
  if (fs::is_directory(path, ec)) throw InputError(path, "cannot be read: it is a directory, not a force log");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "cannot be read: permission denied or I/O error");
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw InputError(path, "cannot be read: I/O error");
  return read_force_log(text.str(), path);
}

}  // namespace feedplan::force_log
