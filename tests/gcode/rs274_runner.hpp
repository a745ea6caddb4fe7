#pragma once
// LinuxCNC's G-code interpreter as a test oracle (docs/method.md §7), shared by the reader's and the
// writer's oracle tests. `rs274 -g in.ngc out.txt` (Debian package linuxcnc-uspace) writes the
// canonical machining calls it would make — STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED,
// SET_FEED_RATE, DWELL, spindle calls, COMMENT, MESSAGE — and exits 1 on a program it rejects.
// rs274 prints 4 decimals in the program's unit. Test-only code.

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/geometry/move.hpp"
#include "feedplan/geometry/program.hpp"

namespace feedplan::gcode::oracle {

namespace fs = std::filesystem;

inline constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
inline constexpr double kMmPerInch = 25.4;

//! rs274 on PATH, or nullopt.
inline std::optional<fs::path> find_rs274() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const fs::path candidate = fs::path(dir) / "rs274";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return std::nullopt;
}

inline std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

//! One move as LinuxCNC's canonical calls describe it, converted to mm.
struct OracleMove {
  geometry::MoveKind kind = geometry::MoveKind::kLine;
  geometry::Point3 start;
  geometry::Point3 end;
  geometry::Point2 center;
  int rotation = 0;  //!< ARC_FEED's rotation: +n counter-clockwise, −n clockwise, n turns
  double feed_mm_per_min = 0.0;
  double spindle_rpm = 0.0;
  geometry::SpindleDirection spindle = geometry::SpindleDirection::kOff;
  double dwell_before_s = 0.0;
  //! Z offsets in effect for the move, mm (canonical coordinates are the program's: machine Z = program Z
  //! + origin_z_mm + tool_length_z_mm): work offset plus G92 (SET_G5X_OFFSET, SET_G92_OFFSET) ...
  double origin_z_mm = 0.0;
  double tool_length_z_mm = 0.0;  //!< ... and the tool length offset (USE_TOOL_LENGTH_OFFSET)
};

//! What one run of rs274 produced.
struct OracleRun {
  int exit_code = -1;
  std::string messages;  //!< what rs274 printed (its error text on rejection)
  std::vector<OracleMove> moves;
  double dwell_at_end_s = 0.0;
  std::vector<std::string> oddities;   //!< canonical calls the comparison cannot follow
  std::vector<std::string> calls;      //!< every canonical call's name, in order
  std::vector<std::string> comments;   //!< COMMENT arguments without the quotes (interpreter's own too)
  std::vector<double> feed_rates_mm_per_min;  //!< every SET_FEED_RATE, in order
};

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<double> numbers_in(const std::string& arguments) {
  std::vector<double> numbers;
  std::stringstream items(arguments);
  std::string item;
  while (std::getline(items, item, ',')) numbers.push_back(std::strtod(item.c_str(), nullptr));
  return numbers;
}

//! Follows the canonical calls in rs274's output file. Zero-length straight moves (LinuxCNC emits
//! one for a bare "G1") are dropped, as the reader drops them.
inline void parse_canonical(const std::string& text, OracleRun& run) {
  using geometry::MoveKind;
  using geometry::SpindleDirection;
  double unit_mm = 1.0;
  geometry::Point3 position;
  double feed = 0.0;
  double rpm = 0.0;
  SpindleDirection spindle = SpindleDirection::kOff;
  double dwell = 0.0;
  double g5x_z = 0.0;
  double g92_z = 0.0;
  double tool_z = 0.0;
  std::stringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const std::size_t open = line.find('(');
    const std::size_t close = line.rfind(')');
    if (open == std::string::npos || close == std::string::npos || close < open) continue;
    const std::size_t name_begin = line.rfind(' ', open) == std::string::npos ? 0 : line.rfind(' ', open) + 1;
    const std::string name = line.substr(name_begin, open - name_begin);
    const std::string arguments = line.substr(open + 1, close - open - 1);
    run.calls.push_back(name);
    if (name == "COMMENT") {
      run.comments.push_back(arguments.size() >= 2 ? arguments.substr(1, arguments.size() - 2) : arguments);
      continue;
    }
    if (name == "MESSAGE") continue;
    if (name == "USE_LENGTH_UNITS") {
      unit_mm = arguments == "CANON_UNITS_INCHES" ? kMmPerInch : 1.0;
      if (arguments != "CANON_UNITS_INCHES" && arguments != "CANON_UNITS_MM") run.oddities.push_back(line);
    } else if (name == "SELECT_PLANE") {
      if (arguments != "CANON_PLANE_XY") run.oddities.push_back(line);
    } else if (name == "SET_FEED_RATE") {
      feed = numbers_in(arguments).at(0) * unit_mm;  // LinuxCNC converts F when it is set
      run.feed_rates_mm_per_min.push_back(feed);
    } else if (name == "SET_SPINDLE_SPEED") {
      rpm = numbers_in(arguments).at(1);
    } else if (name == "START_SPINDLE_CLOCKWISE") {
      spindle = SpindleDirection::kClockwise;
    } else if (name == "START_SPINDLE_COUNTERCLOCKWISE") {
      spindle = SpindleDirection::kCounterClockwise;
    } else if (name == "STOP_SPINDLE_TURNING") {
      spindle = SpindleDirection::kOff;
    } else if (name == "DWELL") {
      dwell += numbers_in(arguments).at(0);
    } else if (name == "SET_G5X_OFFSET") {  // (origin index, x, y, z, a, b, c)
      g5x_z = numbers_in(arguments).at(3) * unit_mm;
    } else if (name == "SET_G92_OFFSET") {  // (x, y, z, a, b, c)
      g92_z = numbers_in(arguments).at(2) * unit_mm;
    } else if (name == "USE_TOOL_LENGTH_OFFSET") {  // (x y z, a b c, u v w): the offset's axes apart by spaces
      std::stringstream offset(arguments);
      double x = 0.0;
      double y = 0.0;
      offset >> x >> y >> tool_z;
      tool_z *= unit_mm;
    } else if (name == "STRAIGHT_TRAVERSE" || name == "STRAIGHT_FEED" || name == "ARC_FEED") {
      const std::vector<double> v = numbers_in(arguments);
      OracleMove move;
      move.start = position;
      if (name == "ARC_FEED") {
        // ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end_point, a, b, c)
        move.kind = MoveKind::kArc;
        move.end = {v.at(0) * unit_mm, v.at(1) * unit_mm, v.at(5) * unit_mm};
        move.center = {v.at(2) * unit_mm, v.at(3) * unit_mm};
        move.rotation = static_cast<int>(v.at(4));
      } else {
        move.kind = name == "STRAIGHT_TRAVERSE" ? MoveKind::kRapid : MoveKind::kLine;
        move.end = {v.at(0) * unit_mm, v.at(1) * unit_mm, v.at(2) * unit_mm};
        const double length = std::hypot(std::hypot(move.end.x_mm - position.x_mm, move.end.y_mm - position.y_mm),
                                          move.end.z_mm - position.z_mm);
        if (length < 1e-7) continue;
      }
      for (std::size_t i = name == "ARC_FEED" ? 6 : 3; i < v.size(); ++i) {
        if (v[i] != 0.0) run.oddities.push_back(line + "  (a rotary or extra axis moves)");
      }
      move.feed_mm_per_min = move.kind == MoveKind::kRapid ? 0.0 : feed;
      move.spindle_rpm = rpm;
      move.spindle = spindle;
      move.dwell_before_s = dwell;
      move.origin_z_mm = g5x_z + g92_z;
      move.tool_length_z_mm = tool_z;
      dwell = 0.0;
      position = move.end;
      run.moves.push_back(move);
    }
  }
  run.dwell_at_end_s = dwell;
}

//! Holds an exclusive lock on a machine-wide file while it lives: two rs274 processes running at the
//! same time (ctest -j) crash with a bus error, so every run of it is serialised.
class Rs274Lock {
 public:
  Rs274Lock() : fd_(::open((fs::temp_directory_path() / "feedplan-rs274.lock").c_str(), O_RDWR | O_CREAT, 0666)) {
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~Rs274Lock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
  }
  Rs274Lock(const Rs274Lock&) = delete;
  Rs274Lock& operator=(const Rs274Lock&) = delete;

 private:
  int fd_;
};

//! Runs rs274 on the file `program` in a directory of this process's own; `tool_table`, when not empty,
//! is the text of a LinuxCNC tool table (`T1 P1 D0.5`, diameters in inches) given with -t.
inline OracleRun run_rs274(const fs::path& rs274, const fs::path& program, const std::string& tool_table = "") {
  const Rs274Lock lock;
  const fs::path dir = fs::temp_directory_path() / ("feedplan-rs274-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path output = dir / "canonical.txt";
  const fs::path messages = dir / "messages.txt";
  fs::remove(output);
  std::string table_option;
  if (!tool_table.empty()) {
    const fs::path table = dir / "tools.tbl";
    std::ofstream(table, std::ios::binary | std::ios::trunc) << tool_table;
    table_option = " -t " + shell_quoted(table.string());
  }
  const std::string command = "cd " + shell_quoted(dir.string()) + " && " + shell_quoted(rs274.string()) + table_option + " -g " +
                              shell_quoted(fs::absolute(program).string()) + " " + shell_quoted(output.string()) +
                              " < /dev/null > " + shell_quoted(messages.string()) + " 2>&1";
  OracleRun run;
  const int status = std::system(command.c_str());
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.messages = read_text(messages);
  if (fs::exists(output)) parse_canonical(read_text(output), run);
  fs::remove_all(dir);
  return run;
}

//! Runs rs274 on program text (written to a file of this process's own first), with run_rs274's tool table.
inline OracleRun run_rs274_text(const fs::path& rs274, const std::string& text, const std::string& tool_table = "") {
  const fs::path file = fs::temp_directory_path() / ("feedplan-rs274-input-" + std::to_string(::getpid()) + ".ngc");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
  }
  OracleRun run = run_rs274(rs274, file, tool_table);
  fs::remove(file);
  return run;
}

//! The swept angle LinuxCNC means by an ARC_FEED: from start to end in the rotation's direction,
//! in (0, 2π] (2π when start and end coincide), plus one full turn per extra count of rotation.
inline double oracle_sweep_rad(const OracleMove& m) {
  const bool ccw = m.rotation > 0;
  double base = kTwoPi;
  if (std::hypot(m.end.x_mm - m.start.x_mm, m.end.y_mm - m.start.y_mm) > 1e-9) {
    const double a0 = std::atan2(m.start.y_mm - m.center.y_mm, m.start.x_mm - m.center.x_mm);
    const double a1 = std::atan2(m.end.y_mm - m.center.y_mm, m.end.x_mm - m.center.x_mm);
    base = std::fmod(ccw ? a1 - a0 : a0 - a1, kTwoPi);
    if (base <= 0.0) base += kTwoPi;
  }
  return base + (std::abs(m.rotation) - 1) * kTwoPi;
}

//! Fanuc's dwell `G04 X<s>` (seconds) as LinuxCNC writes it, `G4 P<s>`: LinuxCNC has no X form.
//! The only change the writer's Fanuc programs need to run on rs274.
inline std::string fanuc_dwell_as_linuxcnc(const std::string& text) {
  std::string result;
  std::size_t begin = 0;
  for (std::size_t at = text.find("G04 X"); at != std::string::npos; at = text.find("G04 X", begin)) {
    result += text.substr(begin, at - begin) + "G4 P";
    begin = at + 5;
  }
  return result + text.substr(begin);
}

//! Fixture for tests that need rs274: it fails when rs274 is missing — the oracle is part of the
//! test suite (CI installs linuxcnc-uspace) — unless FEEDPLAN_SKIP_RS274=1 says to skip.
class Rs274Test : public ::testing::Test {
 protected:
  void SetUp() override {
    rs274_ = find_rs274();
    if (!rs274_) {
      const char* skip = std::getenv("FEEDPLAN_SKIP_RS274");
      if (skip != nullptr && std::string(skip) == "1") {
        GTEST_SKIP() << "rs274 is not on PATH and FEEDPLAN_SKIP_RS274=1: LinuxCNC oracle not run";
      }
      FAIL() << "rs274 (LinuxCNC's G-code interpreter, the oracle of this test) is not on PATH: install the "
                "Debian package linuxcnc-uspace (scripts/install-deps.sh; CI installs it), or set "
                "FEEDPLAN_SKIP_RS274=1 to skip the LinuxCNC oracle tests";
    }
  }
  std::optional<fs::path> rs274_;
};

}  // namespace feedplan::gcode::oracle
