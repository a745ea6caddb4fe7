#include "kistler_dynoware_reader.hpp"

#include <array>
#include <cmath>
#include <optional>

#include "log_cells.hpp"
#include "log_columns.hpp"
#include "log_metadata.hpp"
#include "log_problems.hpp"
#include "time_order.hpp"

namespace feedplan::force_log::detail {

namespace {

// Channels: Time, Fx, Fy required, Fz optional; other channels (Mz, ...) are ignored.
const std::array<std::string, 4> kWanted = {"time", "fx", "fy", "fz"};
const std::array<int, 4> kTarget = {kT, kFx, kFy, kFz};

// The channel row as read.
struct Channels {
  std::size_t line = 0;                                   // index into lines
  std::vector<std::string_view> names;                    // every channel, as written
  std::array<std::optional<std::size_t>, 4> index;        // kWanted[w] → its position in names
};

// "Kistler DynoWare export (<version>)" from the first line's cells.
std::string source_description(const std::vector<std::string_view>& first) {
  return "Kistler DynoWare export" +
         (first.size() > 1 && !first[1].empty() ? " (" + std::string(first[1]) + ")" : std::string());
}

// The header block after `lines[start]` into `log`'s metadata. Returns the index of the channel
// row (the first line starting with Time), or 0 when there is none.
std::size_t read_header_block(Problems& problems, const std::vector<std::string_view>& lines, std::size_t start,
                              ForceLog& log) {
  for (std::size_t i = start + 1; i < lines.size(); ++i) {
    const std::vector<std::string_view> cells = split(lines[i], ',');
    if (lower(cells[0]) == "time") return i;
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
    if (!trim(value).empty() && check_metadata_entry(problems, i + 1, key, "dynoware." + key, value)) {
      log.metadata.emplace_back("dynoware." + key, value);
    }
  }
  return 0;
}

// The wanted channels of the channel row at `channel_line`; Fx or Fy missing is a problem.
Channels find_channels(Problems& problems, const std::vector<std::string_view>& lines, std::size_t channel_line) {
  Channels channels;
  channels.line = channel_line;
  channels.names = split(lines[channel_line], ',');
  for (std::size_t c = 0; c < channels.names.size(); ++c) {
    for (std::size_t w = 0; w < kWanted.size(); ++w) {
      if (lower(channels.names[c]) == kWanted[w] && !channels.index[w]) channels.index[w] = c;
    }
  }
  for (std::size_t w = 1; w < 3; ++w) {
    if (!channels.index[w]) {
      problems.add(channel_line + 1, "", "has no channel " + std::string(w == 1 ? "Fx" : "Fy") +
                                             ": a force log needs Time, Fx and Fy (found " +
                                             std::string(lines[channel_line]) + ")");
    }
  }
  return channels;
}

// The units row at `units_line`: s for time, N or kN for forces. Returns the factor to N (and s)
// of each wanted channel.
std::array<double, 4> read_units(Problems& problems, const std::vector<std::string_view>& lines,
                                 std::size_t units_line, const Channels& channels) {
  std::array<double, 4> scale = {1.0, 1.0, 1.0, 1.0};
  const std::vector<std::string_view> units = split(lines[units_line], ',');
  for (std::size_t w = 0; w < kWanted.size(); ++w) {
    if (!channels.index[w]) continue;
    const std::size_t index = *channels.index[w];
    const std::string unit = index < units.size() ? std::string(units[index]) : std::string();
    const std::string label = column_label(index, std::string(channels.names[index]));
    if (w == 0) {
      if (unit != "s") problems.add(units_line + 1, label, "= \"" + unit + "\": the time unit must be s");
    } else if (unit == "kN") {
      scale[w] = 1000.0;
    } else if (unit != "N") {
      problems.add(units_line + 1, label, "= \"" + unit + "\": the force unit must be N or kN");
    }
  }
  return scale;
}

// The sample on line index `i`, scaled to s and N; nullopt (and problems) when a wanted cell is bad
// or empty.
std::optional<ForceLogRow> read_sample(Problems& problems, std::string_view line, std::size_t i,
                                       const Channels& channels, const std::array<double, 4>& scale) {
  const std::vector<std::string_view> cells = split(line, ',');
  if (cells.size() != channels.names.size()) {
    problems.add(i + 1, "", "has " + std::to_string(cells.size()) + " cells, the channel row (line " +
                                std::to_string(channels.line + 1) + ") has " + std::to_string(channels.names.size()));
    return std::nullopt;
  }
  ForceLogRow row{0, kNaN, kNaN, kNaN, 0, 0, kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
  bool ok = true;
  for (std::size_t w = 0; w < kWanted.size(); ++w) {
    if (!channels.index[w]) continue;
    const std::size_t index = *channels.index[w];
    const std::string name(channels.names[index]);
    double value = kNaN;
    if (!read_cell(problems, i + 1, index, name, cells[index], value)) {
      ok = false;
      continue;
    }
    if (std::isnan(value)) {
      problems.add(i + 1, column_label(index, name), "is empty: every sample needs " + name);
      ok = false;
      continue;
    }
    cell_of(row, kTarget[w]) = value * scale[w];
  }
  if (!ok) return std::nullopt;
  return row;
}

}  // namespace

ForceLog read_kistler_dynoware(const std::vector<std::string_view>& lines, std::size_t start,
                               const std::string& source_name) {
  Problems problems(source_name);
  ForceLog log;
  log.has_positions = false;
  log.metadata.emplace_back("source", source_description(split(lines[start], ',')));
  const std::size_t channel_line = read_header_block(problems, lines, start, log);
  if (channel_line == 0) {
    problems.add(0, "", "is a Kistler DynoWare export without a channel row: expected a line Time,Fx,Fy,Fz after the "
                        "header block");
    problems.raise();
  }
  const Channels channels = find_channels(problems, lines, channel_line);
  problems.raise_if_any();

  const std::size_t units_line = channel_line + 1;
  if (units_line >= lines.size()) {
    problems.add(units_line, "", "is missing: expected the units row (s,N,N,N) after the channel row");
    problems.raise();
  }
  const std::array<double, 4> scale = read_units(problems, lines, units_line, channels);
  problems.raise_if_any();

  std::vector<std::size_t> row_lines;
  for (std::size_t i = units_line + 1; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    if (const std::optional<ForceLogRow> row = read_sample(problems, lines[i], i, channels, scale)) {
      log.rows.push_back(*row);
      row_lines.push_back(i + 1);
    }
  }
  if (log.rows.empty() && problems.empty()) {
    problems.add(units_line + 1, "", "is the last line: the export has no samples");
  }
  check_time_order(problems, log.rows, row_lines);
  problems.raise_if_any();
  return log;
}

}  // namespace feedplan::force_log::detail
