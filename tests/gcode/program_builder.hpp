#pragma once
// Building geometry::Program objects by hand for the writer's tests: moves chained from a start point,
// each with its own block (feed, spindle, dwell), and the arcs a writer must split, expanded
// independently of the writer. Test-only code.

#include <cmath>
#include <string>
#include <vector>

#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::gcode::testing_support {

inline constexpr double kPi = 3.14159265358979323846;

//! Appends moves to a program, each starting where the previous one ends.
class ProgramBuilder {
 public:
  explicit ProgramBuilder(const geometry::Point3& start) : position_(start) {
    program_.path.part_names = {"test"};
  }

  //! Spindle state for the blocks added from now on.
  ProgramBuilder& spindle(double rpm, geometry::SpindleDirection direction) {
    rpm_ = rpm;
    direction_ = direction;
    return *this;
  }

  //! A dwell before the next move added.
  ProgramBuilder& dwell(double seconds) {
    dwell_s_ = seconds;
    return *this;
  }

  ProgramBuilder& rapid(const geometry::Point3& end) { return straight(geometry::MoveKind::kRapid, end, 0.0); }
  ProgramBuilder& line(const geometry::Point3& end, double feed_mm_per_min) {
    return straight(geometry::MoveKind::kLine, end, feed_mm_per_min);
  }

  //! An arc about `center` sweeping `sweep_rad` from the current position, z changing by `dz_mm`.
  ProgramBuilder& arc(const geometry::Point2& center, double sweep_rad, bool ccw, double dz_mm, double feed_mm_per_min) {
    geometry::Move m;
    m.kind = geometry::MoveKind::kArc;
    m.start = position_;
    m.center = center;
    m.ccw = ccw;
    m.sweep_rad = sweep_rad;
    const double radius = std::hypot(position_.x_mm - center.x_mm, position_.y_mm - center.y_mm);
    const double angle = std::atan2(position_.y_mm - center.y_mm, position_.x_mm - center.x_mm) +
                         (ccw ? sweep_rad : -sweep_rad);
    m.end = {center.x_mm + radius * std::cos(angle), center.y_mm + radius * std::sin(angle), position_.z_mm + dz_mm};
    if (std::abs(std::fmod(sweep_rad, 2 * kPi)) < 1e-12) m.end = {position_.x_mm, position_.y_mm, position_.z_mm + dz_mm};
    m.cutting = true;
    return add(m, feed_mm_per_min);
  }

  ProgramBuilder& dwell_at_end(double seconds) {
    program_.dwell_at_end_s = seconds;
    return *this;
  }

  geometry::Program build() const { return program_; }
  const geometry::Point3& position() const { return position_; }

 private:
  ProgramBuilder& straight(geometry::MoveKind kind, const geometry::Point3& end, double feed_mm_per_min) {
    geometry::Move m;
    m.kind = kind;
    m.start = position_;
    m.end = end;
    m.cutting = kind != geometry::MoveKind::kRapid;
    return add(m, feed_mm_per_min);
  }

  ProgramBuilder& add(const geometry::Move& m, double feed_mm_per_min) {
    program_.path.moves.push_back(m);
    geometry::BlockCommand b;
    b.feed_mm_per_min = m.kind == geometry::MoveKind::kRapid ? 0.0 : feed_mm_per_min;
    b.spindle_rpm = rpm_;
    b.spindle = direction_;
    b.dwell_before_s = dwell_s_;
    dwell_s_ = 0.0;
    program_.blocks.push_back(b);
    position_ = m.end;
    return *this;
  }

  geometry::Program program_;
  geometry::Point3 position_;
  double rpm_ = 0.0;
  geometry::SpindleDirection direction_ = geometry::SpindleDirection::kOff;
  double dwell_s_ = 0.0;
};

//! One move as a controller should run it after the writer splits arcs: `program_move` is the index
//! of the move in the program it comes from.
struct ExpectedMove {
  geometry::Move move;
  std::size_t program_move = 0;
};

//! The program's moves with every arc of more than `max_sweep_deg` split into ⌈sweep / max⌉ equal
//! sub-arcs (same centre, ends on the circle, z linear in the angle) — computed here, not by the writer.
inline std::vector<ExpectedMove> expected_moves(const geometry::Program& program, double max_sweep_deg) {
  std::vector<ExpectedMove> result;
  const double max_sweep_rad = max_sweep_deg * kPi / 180.0;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    const geometry::Move& m = program.path.moves[i];
    if (m.kind != geometry::MoveKind::kArc || m.sweep_rad <= max_sweep_rad + 1e-9) {
      result.push_back({m, i});
      continue;
    }
    const int n = static_cast<int>(std::ceil(m.sweep_rad / max_sweep_rad - 1e-9));
    for (int k = 0; k < n; ++k) {
      geometry::Move piece = m;
      piece.sweep_rad = m.sweep_rad / n;
      piece.start = geometry::point_at(m, static_cast<double>(k) / n);
      piece.end = k + 1 == n ? m.end : geometry::point_at(m, static_cast<double>(k + 1) / n);
      result.push_back({piece, i});
    }
  }
  return result;
}

}  // namespace feedplan::gcode::testing_support
