#include "feedplan_csv_reader.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "feedplan/core/did_you_mean.hpp"
#include "log_cells.hpp"
#include "log_columns.hpp"
#include "log_metadata.hpp"
#include "log_problems.hpp"
#include "time_order.hpp"

namespace feedplan::force_log::detail {

namespace {

// The header row as read.
struct Header {
  std::size_t line = 0;                                           // index into lines
  std::vector<int> columns;                                       // header position → Column
  std::array<std::optional<std::size_t>, kColumnCount> position;  // Column → header position
};

// A "# key: value" line (line index `i`) into `log`'s metadata, when log_metadata.hpp's checks pass;
// other comment lines are skipped.
void read_metadata_line(Problems& problems, std::string_view line, std::size_t i, ForceLog& log) {
  const std::string_view body = trim(line.substr(1));
  const std::size_t colon = body.find(':');
  if (colon != std::string_view::npos && colon > 0) {
    std::string key(trim(body.substr(0, colon)));
    std::string value(trim(body.substr(colon + 1)));
    if (check_metadata_entry(problems, i + 1, "# " + key, key, value)) {
      log.metadata.emplace_back(std::move(key), std::move(value));
    }
  }
}

// The column names of the header on line index `i`; unknown and repeated names are problems (and
// column -1).
void read_column_names(Problems& problems, std::string_view line, std::size_t i, Header& header) {
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
      header.columns.push_back(-1);
      continue;
    }
    const int column = static_cast<int>(it - known.begin());
    if (header.position[column]) {
      problems.add(i + 1, "column " + std::to_string(c + 1),
                   "= \"" + name + "\": repeats column " + std::to_string(*header.position[column] + 1));
      header.columns.push_back(-1);
      continue;
    }
    header.position[column] = c;
    header.columns.push_back(column);
  }
}

// t_s, x_mm, y_mm and either the forces fx_n, fy_n or the currents ix_a, iy_a must be columns.
void check_required_columns(Problems& problems, const Header& header) {
  const auto& position = header.position;
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
    problems.add(header.line + 1, "(header)",
                 "lacks the column" + std::string(missing.size() > 1 ? "s " : " ") + list +
                     ": a force log needs t_s, x_mm, y_mm and fx_n, fy_n (or the currents ix_a, iy_a)");
  }
}

// The header row on line index `i`.
Header read_header(Problems& problems, std::string_view line, std::size_t i) {
  Header header;
  header.line = i;
  read_column_names(problems, line, i, header);
  check_required_columns(problems, header);
  return header;
}

// The sample on line index `i`; nullopt (and problems) when a cell is bad or the time is empty.
std::optional<ForceLogRow> read_row(Problems& problems, const Header& header, std::string_view line, std::size_t i) {
  const std::vector<std::string_view> cells = split(line, ',');
  if (cells.size() != header.columns.size()) {
    problems.add(i + 1, "", "has " + std::to_string(cells.size()) + " cells, the header (line " +
                                std::to_string(header.line + 1) + ") has " + std::to_string(header.columns.size()));
    return std::nullopt;
  }
  ForceLogRow row{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  bool ok = true;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const int column = header.columns[c];
    if (!read_cell(problems, i + 1, c, kColumnNames[column], cells[c], cell_of(row, column))) ok = false;
  }
  if (std::isnan(row.t_s) && ok) {
    problems.add(i + 1, column_label(*header.position[kT], "t_s"), "is empty: every row needs its time");
    ok = false;
  }
  if (!ok) return std::nullopt;
  return row;
}

// No header row: the file is empty or holds metadata only.
[[noreturn]] void raise_no_header(Problems& problems, const std::vector<std::string_view>& lines) {
  problems.add(0, "", lines.empty() || std::all_of(lines.begin(), lines.end(), [](auto l) { return trim(l).empty(); })
                          ? "is empty: expected a force log (header row t_s,x_mm,y_mm,...,fx_n,fy_n then samples)"
                          : "has no header row: expected t_s,x_mm,y_mm,...,fx_n,fy_n after the # metadata lines");
  problems.raise();
}

// Whether the column pair a, b is "recorded": both are columns and some row holds a value in either.
bool recorded(const Header& header, const std::vector<ForceLogRow>& rows, int a, int b) {
  if (!header.position[a] || !header.position[b]) return false;
  return std::any_of(rows.begin(), rows.end(), [&](const ForceLogRow& r) {
    return !std::isnan(cell_of(r, a)) || !std::isnan(cell_of(r, b));
  });
}

// Every row must hold both columns a and b of a recorded pair.
void require_full(Problems& problems, const Header& header, const std::vector<ForceLogRow>& rows,
                  const std::vector<std::size_t>& row_lines, int a, int b, const std::string& what) {
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (int column : {a, b}) {
      if (!std::isnan(cell_of(rows[r], column))) continue;
      problems.add(row_lines[r], column_label(*header.position[column], kColumnNames[column]),
                   "is empty, but other rows record " + what + ": give it in every row or in none");
    }
  }
}

// Column pairs that are all-or-nothing: x/y positions, fx/fy forces, ix/iy currents. Sets which
// `log` records; a recorded pair must be full, and forces or currents must be recorded.
void check_column_pairs(Problems& problems, const Header& header, const std::vector<ForceLogRow>& rows,
                        const std::vector<std::size_t>& row_lines, ForceLog& log) {
  log.has_positions = recorded(header, rows, kX, kY);
  log.has_forces = recorded(header, rows, kFx, kFy);
  log.has_currents = recorded(header, rows, kIx, kIy);
  if (log.has_positions) require_full(problems, header, rows, row_lines, kX, kY, "positions");
  if (log.has_forces) require_full(problems, header, rows, row_lines, kFx, kFy, "forces");
  if (log.has_currents) require_full(problems, header, rows, row_lines, kIx, kIy, "currents");
  if (!rows.empty() && !log.has_forces && !log.has_currents) {
    problems.add(header.line + 1, "(header)",
                 "fx_n, fy_n are empty in every row and there are no currents ix_a, iy_a: the log holds no force");
  }
}

}  // namespace

ForceLog read_feedplan_csv(const std::vector<std::string_view>& lines, const std::string& source_name) {
  Problems problems(source_name);
  ForceLog log;
  std::optional<Header> header;
  std::vector<ForceLogRow> rows;
  std::vector<std::size_t> row_lines;

  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string_view line = trim(lines[i]);
    if (line.empty()) continue;
    if (line.front() == '#') {
      read_metadata_line(problems, line, i, log);
      continue;
    }
    if (!header) {
      header = read_header(problems, line, i);
      problems.raise_if_any();  // rows cannot be read against a broken header
      continue;
    }
    if (const std::optional<ForceLogRow> row = read_row(problems, *header, line, i)) {
      rows.push_back(*row);
      row_lines.push_back(i + 1);
    }
  }

  if (!header) raise_no_header(problems, lines);
  if (rows.empty() && problems.empty()) {
    problems.add(header->line + 1, "", "is the header, and no samples follow it");
  }
  check_column_pairs(problems, *header, rows, row_lines, log);
  check_time_order(problems, rows, row_lines);
  problems.raise_if_any();
  log.rows = std::move(rows);
  return log;
}

}  // namespace feedplan::force_log::detail
