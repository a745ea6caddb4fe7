#include "drill_cycle.hpp"

#include <cmath>

namespace feedplan::gcode::detail {

using geometry::Point3;

namespace {

// LinuxCNC's G83_RAPID_DELTA: how far above the depth reached a peck's rapid stops, inches.
constexpr double kPeckBackInch = 0.010;
constexpr double kMmPerInch = 25.4;

// Collects the moves in program units and converts them to mm.
class Moves {
 public:
  explicit Moves(double unit_mm) : unit_mm_(unit_mm) {}
  void rapid(double x, double y, double z) { add(false, x, y, z); }
  void feed(double x, double y, double z) { add(true, x, y, z); }
  void dwell(double seconds) { dwell_s_ += seconds; }
  void stop_spindle() { spindle_stopped_ = true; }
  std::vector<DrillMove> take() { return std::move(moves_); }

 private:
  void add(bool feed, double x, double y, double z) {
    moves_.push_back({feed, Point3{x * unit_mm_, y * unit_mm_, z * unit_mm_}, dwell_s_, spindle_stopped_});
    dwell_s_ = 0.0;
    spindle_stopped_ = false;
  }
  double unit_mm_;
  double dwell_s_ = 0.0;
  bool spindle_stopped_ = false;
  std::vector<DrillMove> moves_;
};

// The cycle's own moves at (x, y), from R down and back to `clear`.
void hole_moves(const DrillRequest& q, double x, double y, double clear, Moves& out) {
  const double peck_back = kPeckBackInch * kMmPerInch / q.unit_mm;
  switch (q.code) {
    case 820:
    case 860:
      out.feed(x, y, q.bottom);
      out.dwell(q.dwell_s);
      if (q.code == 860) out.stop_spindle();
      out.rapid(x, y, clear);
      break;
    case 830:
    case 730:
      for (double depth = q.r - q.peck; depth > q.bottom; depth -= q.peck) {
        out.feed(x, y, depth);
        if (q.code == 830) out.rapid(x, y, q.r);
        out.rapid(x, y, depth + peck_back);
      }
      out.feed(x, y, q.bottom);
      out.rapid(x, y, clear);
      break;
    case 850:
      out.feed(x, y, q.bottom);
      out.feed(x, y, q.r);
      out.rapid(x, y, clear);
      break;
    case 890:
      out.feed(x, y, q.bottom);
      out.dwell(q.dwell_s);
      out.feed(x, y, clear);
      break;
    default:  // 810
      out.feed(x, y, q.bottom);
      out.rapid(x, y, clear);
      break;
  }
}

}  // namespace

double drill_move_count(const DrillRequest& q) {
  const bool pecks = q.code == 730 || q.code == 830;
  const double pecks_per_hole = pecks && q.peck > 0.0 ? std::ceil((q.r - q.bottom) / q.peck) : 0.0;
  return 1.0 + static_cast<double>(q.repeats) * (4.0 + 3.0 * pecks_per_hole);
}

std::vector<DrillMove> drill_moves(const DrillRequest& q, Point3& end) {
  Moves out(q.unit_mm);
  const double u = q.unit_mm;
  double level = q.initial_level;        // LinuxCNC's old_cc
  double height = q.position.z_mm / u;   // where the tool is (current_cc)
  if (level < q.r) {
    out.rapid(q.position.x_mm / u, q.position.y_mm / u, q.r);
    level = q.r;
    height = q.r;
  }
  const double clear = q.retract_to_r ? q.r : level;
  double x = q.first_hole.x_mm / u - q.step.x_mm / u;
  double y = q.first_hole.y_mm / u - q.step.y_mm / u;
  for (int k = 0; k < q.repeats; ++k) {
    x += q.step.x_mm / u;
    y += q.step.y_mm / u;
    if (k == 0 && height > q.r) {
      out.rapid(x, y, height);
      out.rapid(x, y, q.r);
    } else {
      out.rapid(x, y, clear);
      if (clear > q.r) out.rapid(x, y, q.r);
    }
    hole_moves(q, x, y, clear, out);
  }
  end = {x * u, y * u, clear * u};
  return out.take();
}

}  // namespace feedplan::gcode::detail
