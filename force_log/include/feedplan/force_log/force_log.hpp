#pragma once
// Force logs (docs/method.md §4): what a machine's data acquisition writes, and what the virtual machine
// writes in the same format. A CSV text:
//
//   # source: feedplan simulate          ← metadata, "# key: value", anywhere before or among the rows
//   # spindle_rpm: 2800
//   # sample_rate_hz: 10000
//   t_s,x_mm,y_mm,z_mm,fx_n,fy_n,fz_n,feed_mm_per_min,spindle_rpm[,ix_a,iy_a,iz_a]
//   0.000000,0.0000,0.0000,-10.0000,0.000,0.000,0.000,1000.00,2800.0
//
// Required columns: t_s, x_mm, y_mm and either fx_n, fy_n (dynamometer or spindle sensor) or ix_a,
// iy_a (servo currents, to be turned into forces with a calibration, docs/method.md §6.4). Optional: z_mm,
// fz_n, feed_mm_per_min, spindle_rpm, iz_a. A cell may be empty when the value was not recorded
// (read as NaN); t_s and the required force (or current) cells may not.
//
// Also read as they are: Kistler DynoWare CSV exports — a header block starting `DynoWare,Version …`
// with `Key:,value` lines (among them `Sampling rate [Hz]:,10000`), then the channel row
// `Time,Fx,Fy,Fz` (Fz optional, other channels ignored) and a units row (`s,N,N,N`; kN is scaled).
// Such logs have no positions: has_positions is false and x_mm, y_mm, z_mm are NaN, as are
// feed_mm_per_min and spindle_rpm. Time keeps the export's clock (it need not start at 0).

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace feedplan::force_log {

//! One sample of a force log. A value that was not recorded is NaN.
struct ForceLogRow {
  double t_s = 0.0;              //!< time since the log's clock started, s
  double x_mm = 0.0;             //!< tool-centre position x, program coordinates, mm
  double y_mm = 0.0;             //!< tool-centre position y, mm
  double z_mm = 0.0;             //!< tool-centre position z (tool tip), mm
  double fx_n = 0.0;             //!< cutting force x, N
  double fy_n = 0.0;             //!< cutting force y, N
  double fz_n = 0.0;             //!< cutting force z, N
  double feed_mm_per_min = 0.0;  //!< path feed at this instant, mm/min
  double spindle_rpm = 0.0;      //!< spindle speed, rev/min
  double ix_a = 0.0;             //!< x feed-drive servo current, A (only when has_currents)
  double iy_a = 0.0;             //!< y feed-drive servo current, A (only when has_currents)
  double iz_a = 0.0;             //!< z feed-drive servo current, A (only when has_currents)
};

//! A whole force log: metadata and rows in time order.
struct ForceLog {
  //! "# key: value" lines in file order, e.g. {"spindle_rpm", "2800"}, {"source", "feedplan simulate"}.
  std::vector<std::pair<std::string, std::string>> metadata;
  bool has_positions = true;   //!< x_mm, y_mm (and z_mm) hold positions; false for Kistler exports
  bool has_forces = true;      //!< fx_n, fy_n hold forces; false for current-only logs
  bool has_currents = false;   //!< ix_a, iy_a, iz_a hold servo currents (and are written as columns)
  std::vector<ForceLogRow> rows;  //!< samples, strictly increasing t_s

  //! The value of the first metadata entry named `key`, or "" when there is none.
  std::string metadata_value(const std::string& key) const;
};

//! The log as CSV text in the format above: each metadata pair as "# key: value" (line breaks in keys
//! or values become spaces, a ':' in a key becomes '_'), the header row, then one line per row. Time
//! has 6 decimals (1 µs), positions 4 (0.1 µm), forces 3 (1 mN), feed 2, spindle speed 1 and currents 5
//! decimals; the decimal point is '.' whatever the locale. NaN values (a value not recorded) are
//! written as empty cells, as are positions when !has_positions and forces when !has_forces; the current
//! columns appear only when has_currents.
std::string format_force_log(const ForceLog& log);

//! Writes format_force_log(log) to `path` atomically (temporary file + rename). Returns "" on success,
//! otherwise a message naming the path and the reason; the target is then left as it was.
std::string write_force_log(const std::string& path, const ForceLog& log);

//! Parses a force log: our format or a Kistler DynoWare export (recognised by its first line starting
//! with "DynoWare"). `source_name` names the text in messages (a path, or "test").
//!
//! Metadata is free text except that the writer's numeric keys (sample_rate_hz, tool_diameter_mm,
//! flutes, helix_deg, spindle_rpm, radial_depth_mm, axial_depth_mm, feed_per_tooth_mm) must hold
//! numbers in range (flutes a whole number in [1, 100], helix_deg in [0, 90), spindle_rpm and
//! feed_per_tooth_mm finite and ≥ 0, the others finite and > 0), and every key and value must be UTF-8.
//!
//! Our format: a header row is required (the first line that is neither blank nor '#'); every column
//! name must be known (an unknown one is reported with the closest known name) and appear once;
//! t_s, x_mm, y_mm and fx_n, fy_n (or ix_a, iy_a) must be there. Every row must have as many cells as
//! the header; every cell must be empty or a finite number; t_s, the force (or current) cells and, unless
//! both columns are empty throughout, x_mm and y_mm may not be empty; t_s must increase strictly. There
//! must be at least one row. Kistler exports: the `Time`, `Fx` and `Fy` channels must be there, the units
//! row must follow with s and N (or kN); rows as above.
//!
//! Every problem found (up to 20, then a count of the rest) is collected and one feedplan::InputError
//! carries them all, each naming the line (and the column by number and name), the value and what was
//! expected, e.g. `log.csv line 12, column 5 (fx_n) = "1.2.3": not a number`.
ForceLog read_force_log(const std::string& text, const std::string& source_name);

//! The largest force log load_force_log reads by default, bytes: 512 MiB is about 15 minutes of
//! feedplan CSV at 10 kHz, and takes some 2 GB once read; /dev/zero or an endless pipe would otherwise
//! be read until memory runs out.
inline constexpr std::size_t kMaxForceLogFileBytes = std::size_t{512} << 20;

//! Reads the file at `path` and parses it with read_force_log (the path is the source name). A file
//! that does not exist, cannot be read or holds more than `max_file_bytes` is an InputError naming the
//! path ("… is larger than 512 MiB: split the recording …").
ForceLog load_force_log(const std::string& path, std::size_t max_file_bytes = kMaxForceLogFileBytes);

}  // namespace feedplan::force_log
