#include "feedplan/trial/depth_step_slot.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "feedplan/gcode/reader.hpp"

namespace feedplan::trial {

namespace {

// The ramp between two depths along x, mm (step 4 of the file comment).
double ramp_length_mm(double from_mm, double to_mm) { return std::max(2.0, 2.0 * std::abs(to_mm - from_mm)); }

std::string number(double value) { return shortest_number_text(value); }

// The parts joined, built in place.
template <typename... Parts>
std::string joined(const Parts&... parts) {
  std::string out;
  (out += ... += parts);
  return out;
}

}  // namespace

std::vector<InputProblem> validate(const DepthStepSlotRequest& request, const std::string& field_prefix) {
  ProblemList problems(field_prefix);
  const double diameter = request.tool.diameter_mm;
  if (request.depths_mm.size() < 2) {
    problems.add_value("depths_mm", joined(std::to_string(request.depths_mm.size()), " values"),
                       "must hold at least 2 depths (a step needs two)");
  }
  for (std::size_t i = 0; i < request.depths_mm.size(); ++i) {
    const double d = request.depths_mm[i];
    if (!(std::isfinite(d) && d > 0.0 && d <= diameter)) {
      problems.add_value(joined("depths_mm[", std::to_string(i), "]"), number(d),
                         joined("must be finite and in (0, ", number(diameter), "] mm — the tool's diameter"));
    }
  }
  if (!(std::isfinite(request.step_length_mm) && request.step_length_mm > diameter)) {
    problems.add_value("step_length_mm", number(request.step_length_mm),
                       joined("must be finite and > ", number(diameter), " mm — the tool's diameter"));
  }
  problems.positive("feed_mm_per_min", request.feed_mm_per_min);
  problems.positive("spindle_rpm", request.spindle_rpm);
  problems.positive("clearance_z_mm", request.clearance_z_mm);
  return problems.take();
}

DepthStepSlot make_depth_step_slot(const DepthStepSlotRequest& request) {
  if (auto problems = validate(request); !problems.empty()) throw InputError(std::move(problems));
  const double r = request.tool.radius_mm();
  const double length = request.step_length_mm;
  DepthStepSlot slot;
  std::string& g = slot.gcode;
  g += "G21 G90 G17\n";
  g += joined("G0 X", number(-r - 1.0), " Y0 Z", number(request.clearance_z_mm), " S", number(request.spindle_rpm), " M3\n");
  g += joined("G0 Z", number(-request.depths_mm.front()), "\n");
  double x = 0.0;
  for (std::size_t i = 0; i < request.depths_mm.size(); ++i) {
    const double depth = request.depths_mm[i];
    if (i == 0) {
      g += joined("G1 X", number(length), " F", number(request.feed_mm_per_min), "\n");
    } else {
      x += ramp_length_mm(request.depths_mm[i - 1], depth);
      g += joined("G1 X", number(x), " Z", number(-depth), "\n");
      g += joined("G1 X", number(x + length), "\n");
    }
    slot.segments.push_back({depth, x, x + length, x + 0.5 * length});
    x += length;
  }
  const double block_end = x + r;
  g += joined("G1 X", number(block_end + r + 1.0), "\n");
  g += joined("G0 Z", number(request.clearance_z_mm), "\n");
  g += "M5\nM30\n";
  slot.program = gcode::read_program(g, "depth-step slot");
  const double half_width = r + 10.0;
  const double deepest = *std::max_element(request.depths_mm.begin(), request.depths_mm.end());
  slot.stock.regions.push_back({geometry::Contour::rectangle({0.0, -half_width}, {block_end, half_width}), {}});
  slot.stock.z_top_mm = 0.0;
  slot.stock.z_bottom_mm = -(deepest + 5.0);
  return slot;
}

}  // namespace feedplan::trial
