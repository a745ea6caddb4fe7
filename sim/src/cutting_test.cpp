#include "feedplan/sim/cutting_test.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "feedplan/core/number_text.hpp"

namespace feedplan::sim {

namespace {

constexpr double kClearanceMm = 5.0;

void check(std::vector<InputProblem>& problems, const std::string& field, double value, double low, double high,
           const std::string& why) {
  if (!(std::isfinite(value) && value > low && value <= high)) {
    std::ostringstream message;
    message << "= " << value << ": must be ";
    if (std::isfinite(high)) {
      message << "in (" << low << ", " << high << "]";
    } else {
      message << "> " << low;
    }
    message << " — " << why;
    problems.push_back({"cutting_test." + field, message.str()});
  }
}

geometry::Move straight(geometry::MoveKind kind, geometry::Point3 from, geometry::Point3 to, bool cutting, double ad) {
  geometry::Move move;
  move.kind = kind;
  move.start = from;
  move.end = to;
  move.cutting = cutting;
  move.axial_depth_mm = cutting ? ad : 0.0;
  return move;
}

}  // namespace

std::vector<InputProblem> validate(const CuttingTest& test, const geometry::Tool& tool) {
  std::vector<InputProblem> problems;
  const double d = std::isfinite(tool.diameter_mm) && tool.diameter_mm > 0 ? tool.diameter_mm : INFINITY;
  check(problems, "radial_depth_mm", test.radial_depth_mm, 0, d, "radial depth a_e, at most the tool diameter (a slot)");
  check(problems, "axial_depth_mm", test.axial_depth_mm, 0, INFINITY, "axial depth a_p");
  check(problems, "feed_mm_per_min", test.feed_mm_per_min, 0, INFINITY, "programmed feed F");
  check(problems, "spindle_rpm", test.spindle_rpm, 0, INFINITY, "spindle speed S");
  if (std::isfinite(d) && !(std::isfinite(test.cut_length_mm) && test.cut_length_mm >= 2.0 * d)) {
    problems.push_back({"cutting_test.cut_length_mm",
                        "= " + six_digit_number_text(test.cut_length_mm) + ": must be ≥ " +
                            six_digit_number_text(2.0 * d) +
                            " (two tool diameters) — the cut needs a steady stretch between entry and exit"});
  }
  return problems;
}

CuttingTestSetup make_cutting_test(const CuttingTest& test, const geometry::Tool& tool) {
  if (auto problems = validate(test, tool); !problems.empty()) throw InputError(std::move(problems));
  const double r = tool.radius_mm();
  const double ap = test.axial_depth_mm;
  const double x0 = -r - 5.0;
  const double x1 = test.cut_length_mm + r + 5.0;
  CuttingTestSetup setup;
  auto& path = setup.program.path;
  path.part_names = {"cutting test"};
  path.moves.push_back(straight(geometry::MoveKind::kRapid, {x0, 0, kClearanceMm}, {x0, 0, -ap}, false, 0));
  path.moves.push_back(straight(geometry::MoveKind::kLine, {x0, 0, -ap}, {x1, 0, -ap}, true, ap));
  path.moves.push_back(straight(geometry::MoveKind::kRapid, {x1, 0, -ap}, {x1, 0, kClearanceMm}, false, 0));
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    geometry::BlockCommand block;
    block.feed_mm_per_min = path.moves[i].kind == geometry::MoveKind::kRapid ? 0.0 : test.feed_mm_per_min;
    block.spindle_rpm = test.spindle_rpm;
    block.spindle = geometry::SpindleDirection::kClockwise;
    setup.program.blocks.push_back(block);
  }
  // The block: the cut takes a_e off its side; it extends two diameters beyond the tool.
  const double ae = std::min(test.radial_depth_mm, 2.0 * r);
  const double far = r + 2.0 * tool.diameter_mm;
  const double near = -r + ae;  // y of the uncut side face for down milling (material at y < near)
  geometry::Point2 lo{0.0, -far};
  geometry::Point2 hi{test.cut_length_mm, near};
  if (test.mode == MillingMode::kUp) {
    lo = {0.0, r - ae};
    hi = {test.cut_length_mm, far};
  }
  if (ae >= 2.0 * r) {  // a slot: material on both sides
    lo = {0.0, -far};
    hi = {test.cut_length_mm, far};
  }
  setup.stock.regions.push_back({geometry::Contour::rectangle(lo, hi), {}});
  setup.stock.z_top_mm = 0.0;
  setup.stock.z_bottom_mm = -ap - 5.0;
  return setup;
}

}  // namespace feedplan::sim
