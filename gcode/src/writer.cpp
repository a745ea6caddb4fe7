#include "feedplan/gcode/writer.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "arc_geometry.hpp"
#include "comment_text.hpp"
#include "decimal_text.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::gcode {

using geometry::BlockCommand;
using geometry::Move;
using geometry::MoveKind;
using geometry::Point2;
using geometry::Point3;
using geometry::SpindleDirection;

namespace {

constexpr double kCoordinateLimitMm = 99999.0;  // 8 digits at 3 decimals: the longest number Fanuc takes
constexpr double kContinuityMm = 1e-6;          // consistency_defects' tolerance
constexpr double kMinimumFeedMmPerMin = 0.05;   // smaller feeds print as F0.
constexpr int kMaxProblems = 50;
constexpr int kMaxLineNumber = 99999;          // Fanuc and LinuxCNC refuse larger N
constexpr std::size_t kLinuxCncCommentLength = 120;
constexpr std::size_t kIsoCommentLength = 58;  // Fanuc, Haas: "(" + 58 + ")" = 60 characters
constexpr int kFeedDecimals = 1;
constexpr int kDwellDecimals = 3;

// Radius agreement an I J arc must meet on every controller the writer speaks: LinuxCNC refuses
// radii that differ by more than 0.00005 in (1.27 µm) and by more than 0.1 % (interp_arc.cc), our
// reader by more than 2 µm (ReaderOptions::arc_radius_tolerance_mm). Kept a little inside both.
constexpr double kArcRadiusDifferenceMm = 0.0012;
constexpr double kArcRadiusDifferenceRelativeMm = 0.0019;
constexpr double kArcRadiusDifferenceRelative = 0.0009;
constexpr double kCentreCandidateSteps = 0.9;  // I J may move the centre by at most this many last digits
constexpr int kMaxArcHalvings = 10;

std::string number(double value) { return shortest_number_text(value); }

bool is_valid_key_character(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == ' ' || c == '_' || c == '.' || c == '/' || c == '-';
}

// Quoted for a message, with non-printables shown as \xNN so that the message itself stays one line.
std::string quoted(const std::string& text) {
  std::string result = "\"";
  for (char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7F) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02X", byte);
      result += escaped;
    } else {
      result += c;
    }
  }
  return result + "\"";
}

void check_point(const Point3& p, const std::string& field, ProblemList& problems) {
  const std::array<std::pair<const char*, double>, 3> axes = {{{"x_mm", p.x_mm}, {"y_mm", p.y_mm}, {"z_mm", p.z_mm}}};
  for (const auto& [name, value] : axes) {
    if (!std::isfinite(value)) {
      problems.add(field + "." + name, "= " + number(value) + ": must be finite");
    } else if (std::abs(value) > kCoordinateLimitMm) {
      problems.add(field + "." + name, "= " + number(value) + ": must be within ±99999 mm (8 digits at 3 decimals, "
                                       "the longest number Fanuc takes)");
    }
  }
}

bool finite_point(const Point3& p) { return std::isfinite(p.x_mm) && std::isfinite(p.y_mm) && std::isfinite(p.z_mm); }

const char* motion_name(MoveKind kind) {
  switch (kind) {
    case MoveKind::kRapid: return "G0";
    case MoveKind::kLine: return "G1";
    case MoveKind::kArc: return "G2/G3";
  }
  return "?";
}

// Move `i` must start where move i - 1 ends: G-code gives end points only.
void check_continuity(const std::vector<Move>& moves, std::size_t i, const std::string& field, ProblemList& problems) {
  const Move& m = moves[i];
  if (i == 0 || !finite_point(m.start) || !finite_point(moves[i - 1].end)) return;
  const Point3& previous = moves[i - 1].end;
  const double gap = std::hypot(std::hypot(m.start.x_mm - previous.x_mm, m.start.y_mm - previous.y_mm),
                                m.start.z_mm - previous.z_mm);
  if (gap > kContinuityMm) {
    problems.add(field + ".start", "is " + number(gap) + " mm from the end of move " + std::to_string(i - 1) +
                                       ": G-code gives end points only, so each move must start where the "
                                       "previous one ends (within 1 µm)");
  }
}

// An arc's centre and sweep must be finite, its end on its circle and where the sweep leads.
void check_arc(const Move& m, const std::string& field, ProblemList& problems) {
  const std::array<std::pair<const char*, double>, 2> centre = {{{"x_mm", m.center.x_mm}, {"y_mm", m.center.y_mm}}};
  bool centre_ok = true;
  for (const auto& [name, value] : centre) {
    if (!std::isfinite(value) || std::abs(value) > kCoordinateLimitMm) {
      problems.add(field + ".center." + name, "= " + number(value) + ": must be finite and within ±99999 mm");
      centre_ok = false;
    }
  }
  if (!(m.sweep_rad > 0.0) || !std::isfinite(m.sweep_rad)) {
    problems.add(field + ".sweep_rad", "= " + number(m.sweep_rad) + ": an arc's sweep must be finite and > 0");
    centre_ok = false;
  }
  if (!centre_ok || !finite_point(m.start) || !finite_point(m.end)) return;
  const double r0 = geometry::arc_radius_mm(m);
  const double r1 = std::hypot(m.end.x_mm - m.center.x_mm, m.end.y_mm - m.center.y_mm);
  if (!(r0 > kContinuityMm)) {
    problems.add(field + ".center", "is the start point: an arc needs a radius > 1 µm");
  } else if (std::abs(r0 - r1) > kContinuityMm) {
    problems.add(field + ".end", "is " + number(std::abs(r0 - r1)) + " mm off the arc's circle (radius " +
                                     number(r0) + " mm at the start, " + number(r1) + " mm at the end)");
  } else {
    const Point3 reached = geometry::point_at(m, 1.0);
    const double miss = std::hypot(reached.x_mm - m.end.x_mm, reached.y_mm - m.end.y_mm);
    if (miss > 10 * kContinuityMm) {
      problems.add(field + ".sweep_rad", "= " + number(m.sweep_rad) + ": the arc ends " + number(miss) +
                                             " mm from its end point");
    }
  }
}

// Block `i` (of a move of `kind`): feed, spindle speed and direction, dwell.
void check_block(const BlockCommand& b, MoveKind kind, std::size_t i, ProblemList& problems) {
  const std::string block_field = "program.blocks[" + std::to_string(i) + "]";
  if (kind != MoveKind::kRapid && (!std::isfinite(b.feed_mm_per_min) || !(b.feed_mm_per_min >= kMinimumFeedMmPerMin))) {
    problems.add(block_field + ".feed_mm_per_min",
                 "= " + number(b.feed_mm_per_min) + ": a feed move (" + motion_name(kind) +
                     ") needs a finite F ≥ 0.05 mm/min (F is written with 1 decimal)");
  }
  if (!std::isfinite(b.spindle_rpm) || b.spindle_rpm < 0.0 || b.spindle_rpm > 999999.0) {
    problems.add(block_field + ".spindle_rpm", "= " + number(b.spindle_rpm) + ": must be finite, in [0, 999999]");
  }
  if (b.spindle != SpindleDirection::kOff && b.spindle != SpindleDirection::kClockwise &&
      b.spindle != SpindleDirection::kCounterClockwise) {
    problems.add(block_field + ".spindle", "= " + std::to_string(static_cast<int>(b.spindle)) +
                                               ": not a SpindleDirection");
  }
  if (!std::isfinite(b.dwell_before_s) || b.dwell_before_s < 0.0) {
    problems.add(block_field + ".dwell_before_s", "= " + number(b.dwell_before_s) + ": must be finite and ≥ 0 s");
  }
}

// Everything write_gcode needs from the program (the header lists it).
void check_program(const geometry::Program& program, const WriterOptions& options, ProblemList& problems) {
  const auto& moves = program.path.moves;
  const auto& blocks = program.blocks;
  if (blocks.size() != moves.size()) {
    problems.add("program.blocks", "has " + std::to_string(blocks.size()) + " entries for " +
                                       std::to_string(moves.size()) + " moves: one BlockCommand per move");
  }
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const Move& m = moves[i];
    const std::string field = "program.path.moves[" + std::to_string(i) + "]";
    if (m.kind != MoveKind::kRapid && m.kind != MoveKind::kLine && m.kind != MoveKind::kArc) {
      problems.add(field + ".kind", "= " + std::to_string(static_cast<int>(m.kind)) + ": not a MoveKind");
      continue;
    }
    check_point(m.start, field + ".start", problems);
    check_point(m.end, field + ".end", problems);
    check_continuity(moves, i, field, problems);
    if (m.kind == MoveKind::kArc) check_arc(m, field, problems);
    if (i < blocks.size()) check_block(blocks[i], m.kind, i, problems);
  }
  if (!options.feed_comments.empty() && options.feed_comments.size() != moves.size()) {
    problems.add("feed_comments", "has " + std::to_string(options.feed_comments.size()) + " entries for " +
                                      std::to_string(moves.size()) + " moves: one per move, or none");
  }
  if (!std::isfinite(program.dwell_at_end_s) || program.dwell_at_end_s < 0.0) {
    problems.add("program.dwell_at_end_s", "= " + number(program.dwell_at_end_s) + ": must be finite and ≥ 0 s");
  }
}

// The text of one program, written block by block with the controller's modal state in mind.
class Writer {
 public:
  explicit Writer(const WriterOptions& options)
      : options_(options),
        iso_(options.dialect != Dialect::kLinuxCnc),
        step_mm_(1.0 / detail::grid_steps_per_unit(options.decimals)),
        line_number_(options.line_number_step) {}

  std::string write(const geometry::Program& program) {
    write_start();
    const auto& moves = program.path.moves;
    // Coolant comes on right after the spindle starts, or before the approach if it never does.
    coolant_pending_ = options_.coolant;
    if (!moves.empty()) write_spindle(program.blocks.front());
    const bool spindle_runs = std::any_of(program.blocks.begin(), program.blocks.end(), [](const BlockCommand& b) {
      return b.spindle != SpindleDirection::kOff;
    });
    if (coolant_pending_ && !spindle_runs) write_coolant_on();
    std::vector<bool> part_named(program.path.part_names.size(), false);
    for (std::size_t i = 0; i < moves.size(); ++i) {
      const BlockCommand& command = program.blocks[i];
      if (i == 0) {
        write_approach(moves.front().start);
        write_part_comment(program.path, moves[i].part, part_named);
      } else {
        write_part_comment(program.path, moves[i].part, part_named);
        write_spindle(command);
      }
      write_dwell(command.dwell_before_s);
      feed_comment_ = i < options_.feed_comments.size() ? options_.feed_comments[i] : std::string();
      write_move(moves[i], command.feed_mm_per_min);
    }
    write_dwell(program.dwell_at_end_s);
    write_end();
    return text_;
  }

 private:
  // --- Lines and words --------------------------------------------------------------------------

  void raw_line(const std::string& line) {
    text_ += line;
    text_ += '\n';
  }

  void block(const std::string& words) {
    if (options_.line_numbers) {
      text_ += 'N';
      text_ += std::to_string(line_number_);
      text_ += ' ';
      line_number_ = line_number_ > kMaxLineNumber - options_.line_number_step
                         ? options_.line_number_step
                         : line_number_ + options_.line_number_step;
    }
    raw_line(words);
  }

  std::string safe(const std::string& text) const {
    return detail::safe_comment_text(text, iso_, iso_ ? kIsoCommentLength : kLinuxCncCommentLength);
  }

  void comment(const std::string& body) {
    const std::string text = safe(body);
    if (!text.empty()) raw_line("(" + text + ")");
  }

  // `(part: <name>)` before the first block of part `part` (WriterOptions::part_comments), once per part.
  void write_part_comment(const geometry::ToolPath& path, int part, std::vector<bool>& named) {
    if (!options_.part_comments || part < 0 || static_cast<std::size_t>(part) >= named.size()) return;
    if (named[static_cast<std::size_t>(part)]) return;
    named[static_cast<std::size_t>(part)] = true;
    std::string body = "part: ";
    body += path.part_names[static_cast<std::size_t>(part)];
    comment(body);
  }

  std::string g_code(int number) const {
    char text[8];
    std::snprintf(text, sizeof text, iso_ ? "G%02d" : "G%d", number);
    return text;
  }

  std::string m_code(int number) const {
    char text[8];
    std::snprintf(text, sizeof text, iso_ ? "M%02d" : "M%d", number);
    return text;
  }

  std::string coordinate(char letter, long long steps) const {
    return " " + std::string(1, letter) + detail::grid_text(steps, options_.decimals);
  }

  long long grid(double value_mm) const { return detail::to_grid(value_mm, options_.decimals); }
  double value(long long steps) const { return detail::grid_value(steps, options_.decimals); }

  // --- Program start and end ------------------------------------------------------------------

  void write_start() {
    if (iso_) {
      raw_line("%");
      char number[16];
      std::snprintf(number, sizeof number, options_.dialect == Dialect::kHaas ? "O%05d" : "O%04d",
                    options_.program_number);
      std::string name = safe(options_.program_name);
      // The name opens its comment: a comma after a first word would make it a LinuxCNC active comment.
      std::replace(name.begin(), name.end(), ',', '.');
      raw_line(std::string(number) + " (" + (name.empty() ? std::string("FEEDPLAN") : name) + ")");
    } else if (!safe(options_.program_name).empty()) {
      comment("program: " + options_.program_name);
    }
    comment("generated by feedplan for " + to_string(options_.dialect));
    for (const auto& [key, value] : options_.header_comments) comment(key + ": " + value);
    if (iso_) {
      block("G21");
      block("G17 G90 G40 G49 G80 G94");
    } else {
      block("G21 G17 G90 G91.1 G40 G49 G80 G94");
    }
    if (options_.work_offset != 0) {
      std::string offset(1, 'G');
      offset += std::to_string(options_.work_offset);
      block(offset);
    }
    if (options_.tool_change) block("T" + std::to_string(options_.tool_number) + " " + m_code(6));
  }

  void write_approach(const Point3& start) {
    std::string words = motion_word(0);
    const long long x = grid(start.x_mm);
    const long long y = grid(start.y_mm);
    const long long z = grid(start.z_mm);
    block(words + coordinate('X', x) + coordinate('Y', y));
    position_[0] = x;
    position_[1] = y;
    const std::string offset = options_.tool_change ? g_code(43) + " H" + std::to_string(options_.tool_number) : "";
    block(offset + (offset.empty() ? coordinate('Z', z).substr(1) : coordinate('Z', z)));
    position_[2] = z;
  }

  void write_end() {
    if (options_.retract_z_mm && position_[2]) {
      const long long z = grid(*options_.retract_z_mm);
      if (*position_[2] < z) {
        motion_block(motion_word(0), coordinate('Z', z));
        position_[2] = z;
      }
    }
    if (options_.safe_return) write_safe_return();
    block(m_code(5));
    if (options_.coolant) block(m_code(9));
    if (iso_) {
      block(m_code(30));
      raw_line("%");
    } else {
      block(m_code(2));
    }
  }

  // Straight up to the machine's Z home (WriterOptions::safe_return). LinuxCNC: G53 in machine
  // coordinates, with its G0 written even when modal (G53 needs G0 or G1 in effect). Fanuc and Haas:
  // G28 through the intermediate point Z0. under G91 — where the tool is — then back to G90.
  void write_safe_return() {
    if (iso_) {
      std::string words = g_code(91);
      words += ' ';
      words += g_code(28);
      words += coordinate('Z', 0);
      block(words);
      block(g_code(90));
    } else {
      std::string words = g_code(53);
      words += ' ';
      words += g_code(0);
      words += coordinate('Z', 0);
      block(words);
      motion_ = 0;
    }
    position_[2].reset();  // a machine position: where it is in the program's coordinates is not known here
  }

  // --- Spindle and dwell ------------------------------------------------------------------------

  void write_spindle(const BlockCommand& command) {
    if (command.spindle == SpindleDirection::kOff) {
      if (spindle_ != SpindleDirection::kOff) block(m_code(5));
      spindle_ = SpindleDirection::kOff;
      return;
    }
    const long long rpm = std::llround(command.spindle_rpm);
    std::string words;
    if (!spindle_rpm_ || *spindle_rpm_ != rpm) words = "S" + std::to_string(rpm);
    if (command.spindle != spindle_) {
      if (!words.empty()) words += ' ';
      words += m_code(command.spindle == SpindleDirection::kClockwise ? 3 : 4);
    }
    if (!words.empty()) block(words);
    spindle_rpm_ = rpm;
    spindle_ = command.spindle;
    if (coolant_pending_) write_coolant_on();
  }

  void write_coolant_on() {
    block(m_code(8));
    coolant_pending_ = false;
  }

  void write_dwell(double dwell_s) {
    const long long ms = detail::to_grid(dwell_s, kDwellDecimals);
    if (ms <= 0) return;
    const std::string seconds = detail::grid_text(ms, kDwellDecimals);
    block(g_code(4) + (options_.dialect == Dialect::kFanuc ? " X" : " P") + seconds);
  }

  // --- Moves ----------------------------------------------------------------------------------

  // The G word when `motion` is not the modal one (and makes it modal), "" otherwise.
  std::string motion_word(int motion) {
    if (motion == motion_) return "";
    motion_ = motion;
    return g_code(motion);
  }

  std::string feed_word(double feed_mm_per_min) {
    const long long steps = detail::to_grid(feed_mm_per_min, kFeedDecimals);
    if (feed_ && *feed_ == steps) return "";
    feed_ = steps;
    std::string word = " F";
    word += detail::grid_text(steps, kFeedDecimals);
    // The move's feed comment goes with its F word, the last word of the block (WriterOptions::feed_comments).
    std::string body = "F: ";
    body += feed_comment_;
    const std::string text = feed_comment_.empty() ? std::string() : safe(body);
    if (!text.empty()) {
      word += " (";
      word += text;
      word += ')';
    }
    feed_comment_.clear();
    return word;
  }

  // Joins a motion word and further words (each starting with a space) into one block.
  void motion_block(const std::string& motion, const std::string& rest) {
    block(motion.empty() ? rest.substr(1) : motion + rest);
  }

  void write_move(const Move& move, double feed_mm_per_min) {
    switch (move.kind) {
      case MoveKind::kRapid: write_straight(0, move.end, 0.0); break;
      case MoveKind::kLine: write_straight(1, move.end, feed_mm_per_min); break;
      case MoveKind::kArc: write_arc(move, feed_mm_per_min); break;
    }
  }

  // G0 or G1 to `end`; nothing when it rounds to where the tool is.
  void write_straight(int motion, const Point3& end, double feed_mm_per_min) {
    const std::array<long long, 3> target = {grid(end.x_mm), grid(end.y_mm), grid(end.z_mm)};
    std::string axes;
    for (std::size_t a = 0; a < 3; ++a) {
      if (position_[a] && *position_[a] == target[a]) continue;
      axes += coordinate("XYZ"[a], target[a]);
      position_[a] = target[a];
    }
    if (axes.empty()) return;
    const std::string g = motion_word(motion);
    motion_block(g, axes + (motion == 0 ? std::string() : feed_word(feed_mm_per_min)));
  }

  // Splits the arc into sub-arcs of at most max_arc_sweep_deg and writes each.
  void write_arc(const Move& move, double feed_mm_per_min) {
    const double max_sweep_rad = deg_to_rad(options_.max_arc_sweep_deg);
    const int pieces = std::max(1, static_cast<int>(std::ceil(move.sweep_rad / max_sweep_rad - 1e-9)));
    const double radius = geometry::arc_radius_mm(move);
    const double start_angle = std::atan2(move.start.y_mm - move.center.y_mm, move.start.x_mm - move.center.x_mm);
    const double sign = move.ccw ? 1.0 : -1.0;
    const double piece_sweep = move.sweep_rad / pieces;
    Point3 piece_start = move.start;
    for (int k = 1; k <= pieces; ++k) {
      Point3 piece_end = move.end;
      if (k < pieces) {
        const double angle = start_angle + sign * k * piece_sweep;
        const double fraction = static_cast<double>(k) / pieces;
        piece_end = {move.center.x_mm + radius * std::cos(angle), move.center.y_mm + radius * std::sin(angle),
                     move.start.z_mm + fraction * (move.end.z_mm - move.start.z_mm)};
      }
      const double piece_start_angle = start_angle + sign * (k - 1) * piece_sweep;
      write_arc_piece(move.center, radius, piece_start_angle, piece_sweep, move.ccw, piece_start, piece_end,
                      feed_mm_per_min, 0);
      piece_start = piece_end;
    }
  }

  // Writes one arc of at most max_arc_sweep_deg; halves it when its rounded words would not make the
  // controller run it (see try_arc), and writes a G1 for a piece whose chord is within half a last
  // digit of the arc.
  void write_arc_piece(const Point2& center, double radius, double start_angle, double sweep, bool ccw,
                       const Point3& start, const Point3& end, double feed_mm_per_min, int halvings) {
    if (try_arc(center, radius, sweep, ccw, end, feed_mm_per_min)) return;
    const double chord_deviation = sweep >= kPi ? radius : radius * (1.0 - std::cos(0.5 * sweep));
    if (chord_deviation <= 0.5 * step_mm_ || halvings >= kMaxArcHalvings) {
      write_straight(1, end, feed_mm_per_min);
      return;
    }
    const double half = 0.5 * sweep;
    const double middle_angle = start_angle + (ccw ? half : -half);
    const Point3 middle{center.x_mm + radius * std::cos(middle_angle), center.y_mm + radius * std::sin(middle_angle),
                        0.5 * (start.z_mm + end.z_mm)};
    write_arc_piece(center, radius, start_angle, half, ccw, start, middle, feed_mm_per_min, halvings + 1);
    write_arc_piece(center, radius, middle_angle, half, ccw, middle, end, feed_mm_per_min, halvings + 1);
  }

  // Writes G2/G3 from the position as written to `end` about `center` and returns true, if the
  // rounded words describe the intended arc: radii that agree within what LinuxCNC and our reader
  // accept, and the swept angle — as LinuxCNC computes it from the programmed centre and as our reader
  // does after putting both ends on one circle — within 4 last digits of arc length of `sweep`.
  // Returns false, writing nothing, otherwise.
  bool try_arc(const Point2& center, double radius, double sweep, bool ccw, const Point3& end,
               double feed_mm_per_min) {
    assert(position_[0] && position_[1] && position_[2]);
    const long long sx = *position_[0];
    const long long sy = *position_[1];
    const long long ex = grid(end.x_mm);
    const long long ey = grid(end.y_mm);
    const long long ez = grid(end.z_mm);
    const Point2 start_xy{value(sx), value(sy)};
    const Point2 end_xy{value(ex), value(ey)};

    // I J candidates: grid offsets from the written start within kCentreCandidateSteps of the centre.
    const double steps = detail::grid_steps_per_unit(options_.decimals);
    const double ci = (center.x_mm - start_xy.x_mm) * steps;
    const double cj = (center.y_mm - start_xy.y_mm) * steps;
    std::optional<std::array<long long, 2>> best;
    double best_difference = 0.0;
    double best_distance = 0.0;
    for (const double i : {std::floor(ci), std::floor(ci) + 1.0}) {
      for (const double j : {std::floor(cj), std::floor(cj) + 1.0}) {
        const double distance = std::hypot(i - ci, j - cj);
        if (distance > kCentreCandidateSteps) continue;
        const Point2 c{start_xy.x_mm + i / steps, start_xy.y_mm + j / steps};
        const double difference = std::abs(std::hypot(start_xy.x_mm - c.x_mm, start_xy.y_mm - c.y_mm) -
                                           std::hypot(end_xy.x_mm - c.x_mm, end_xy.y_mm - c.y_mm));
        if (!best || difference < best_difference - 1e-12 ||
            (difference <= best_difference + 1e-12 && distance < best_distance)) {
          best = std::array<long long, 2>{static_cast<long long>(i), static_cast<long long>(j)};
          best_difference = difference;
          best_distance = distance;
        }
      }
    }
    if (!best) return false;
    const Point2 c{start_xy.x_mm + value((*best)[0]), start_xy.y_mm + value((*best)[1])};
    const double start_radius = std::hypot(start_xy.x_mm - c.x_mm, start_xy.y_mm - c.y_mm);
    const double end_radius = std::hypot(end_xy.x_mm - c.x_mm, end_xy.y_mm - c.y_mm);
    if (!(std::min(start_radius, end_radius) > kContinuityMm)) return false;
    const bool radii_agree =
        best_difference <= kArcRadiusDifferenceMm ||
        (best_difference <= kArcRadiusDifferenceRelativeMm &&
         best_difference <= kArcRadiusDifferenceRelative * std::max(start_radius, end_radius));
    if (!radii_agree) return false;
    const double sweep_tolerance_mm = 4.0 * step_mm_;
    const double linuxcnc_sweep = detail::sweep_rad(start_xy, end_xy, c, ccw, 1);
    if (std::abs(linuxcnc_sweep - sweep) * radius > sweep_tolerance_mm) return false;
    const detail::ArcCircle reader_arc = detail::arc_from_center(start_xy, start_xy, end_xy, c, ccw, 1, 1.0);
    if (!reader_arc.problem.empty() || std::abs(reader_arc.sweep_rad - sweep) * radius > sweep_tolerance_mm) {
      return false;
    }

    std::string words = coordinate('X', ex) + coordinate('Y', ey);
    if (*position_[2] != ez) words += coordinate('Z', ez);
    words += coordinate('I', (*best)[0]) + coordinate('J', (*best)[1]);
    words += feed_word(feed_mm_per_min);
    motion_block(motion_word(ccw ? 3 : 2), words);
    position_ = {ex, ey, ez};
    return true;
  }

  const WriterOptions& options_;
  const bool iso_;        // Fanuc or Haas: two-digit codes, %, O number, upper-case comments
  const double step_mm_;  // one last digit of a coordinate, mm
  std::string text_;
  int line_number_;
  std::array<std::optional<long long>, 3> position_;  // X Y Z as written, grid steps; unknown at the start
  int motion_ = -1;                                   // modal G0–G3; none at the start
  std::optional<long long> feed_;                     // modal F as written, 0.1 mm/min steps
  std::optional<long long> spindle_rpm_;              // S as written
  SpindleDirection spindle_ = SpindleDirection::kOff;
  bool coolant_pending_ = false;  // M8 is still to be written
  std::string feed_comment_;      // the current move's feed comment, until its F word is written
};

}  // namespace

std::vector<InputProblem> validate(const WriterOptions& options) {
  std::vector<InputProblem> problems;
  auto add = [&problems](const std::string& field, std::string message) {
    problems.push_back({field, std::move(message)});
  };
  const bool known_dialect = options.dialect == Dialect::kLinuxCnc || options.dialect == Dialect::kFanuc ||
                             options.dialect == Dialect::kHaas;
  if (!known_dialect) {
    add("dialect", "= " + std::to_string(static_cast<int>(options.dialect)) + ": must be linuxcnc, fanuc or haas");
  }
  if (options.decimals < 1 || options.decimals > 6) {
    add("decimals", "= " + std::to_string(options.decimals) + ": must be in 1..6 (digits after the point of X Y Z I J)");
  }
  if (options.line_number_step < 1 || options.line_number_step > kMaxLineNumber) {
    add("line_number_step", "= " + std::to_string(options.line_number_step) + ": must be in 1..99999");
  }
  if (options.tool_number < 1 || options.tool_number > 999) {
    add("tool_number", "= " + std::to_string(options.tool_number) + ": must be in 1..999");
  }
  if (options.dialect == Dialect::kFanuc && (options.program_number < 1 || options.program_number > 9999)) {
    add("program_number", "= " + std::to_string(options.program_number) + ": must be in 1..9999 for fanuc (O0001-O9999)");
  }
  if (options.dialect == Dialect::kHaas && (options.program_number < 1 || options.program_number > 99999)) {
    add("program_number", "= " + std::to_string(options.program_number) + ": must be in 1..99999 for haas (O00001-O99999)");
  }
  for (std::size_t i = 0; i < options.header_comments.size(); ++i) {
    const std::string& key = options.header_comments[i].first;
    const bool ok = !key.empty() && key.size() <= 32 && std::isalpha(static_cast<unsigned char>(key.front())) &&
                    std::all_of(key.begin(), key.end(), is_valid_key_character);
    if (!ok) {
      add("header_comments[" + std::to_string(i) + "].key",
          "= " + quoted(key) + ": must be 1..32 letters, digits, spaces and _ . / -, starting with a letter "
          "(the key opens the comment, so it must not be able to form a LinuxCNC active comment like \"(MSG,\")");
    }
  }
  if (options.retract_z_mm &&
      (!std::isfinite(*options.retract_z_mm) || std::abs(*options.retract_z_mm) > kCoordinateLimitMm)) {
    add("retract_z_mm", "= " + number(*options.retract_z_mm) + ": must be finite and within ±99999 mm");
  }
  if (options.work_offset != 0 && (options.work_offset < 54 || options.work_offset > 59)) {
    add("work_offset", "= " + std::to_string(options.work_offset) + ": must be 54..59 (G54 … G59), or 0 for none");
  }
  if (!std::isfinite(options.max_arc_sweep_deg) || options.max_arc_sweep_deg < 1.0 ||
      options.max_arc_sweep_deg > 360.0) {
    add("max_arc_sweep_deg", "= " + number(options.max_arc_sweep_deg) + ": must be in [1, 360]");
  }
  return problems;
}

std::string write_gcode(const geometry::Program& program, const WriterOptions& options) {
  ProblemList problems = ProblemList::capped(kMaxProblems, ProblemCap::kStopAfter, "program");
  problems.add_all(validate(options));
  check_program(program, options, problems);
  problems.throw_if_any();
  return Writer(options).write(program);
}

std::string write_gcode_file(const std::filesystem::path& path, const geometry::Program& program,
                             const WriterOptions& options) {
  const std::string text = write_gcode(program, options);
  return write_file_atomically(path, text);
}

}  // namespace feedplan::gcode
