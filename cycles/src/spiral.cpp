#include "feedplan/cycles/spiral.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "path_builder.hpp"
#include "problems.hpp"

namespace feedplan::cycles {

using geometry::Point2;

std::vector<InputProblem> validate(const SpiralSpec& spec, const geometry::Tool& tool, double axial_depth_mm) {
  using namespace detail;
  std::vector<InputProblem> problems = validate_tool(tool);
  const bool tool_ok = problems.empty();
  const double d = tool.diameter_mm;
  const double r = tool.radius_mm();
  check(problems, "axial_depth_mm", axial_depth_mm, above(0), "the depth of the bore below the stock top");
  check_finite(problems, "spiral.center", spec.center);
  bool initial_ok = false;
  if (tool_ok) {
    initial_ok = check(problems, "spiral.initial_radius_mm", spec.initial_radius_mm, above(r),
                       "the tool (radius " + six_digit_number_text(r) + ") does not fit in the bore");
  } else {
    initial_ok = check(problems, "spiral.initial_radius_mm", spec.initial_radius_mm, above(0));
  }
  if (initial_ok) {
    check(problems, "spiral.final_radius_mm", spec.final_radius_mm, above(spec.initial_radius_mm),
          "the spiral expands the bore beyond initial_radius_mm = " + six_digit_number_text(spec.initial_radius_mm));
  } else {
    check(problems, "spiral.final_radius_mm", spec.final_radius_mm, above(0));
  }
  if (tool_ok) {
    check(problems, "spiral.pitch_mm", spec.pitch_mm, open_range(0, d),
          "a pitch of at least the tool diameter leaves uncut material between turns");
  } else {
    check(problems, "spiral.pitch_mm", spec.pitch_mm, above(0));
  }
  return problems;
}

Cycle generate_spiral(const SpiralSpec& spec, const geometry::Tool& tool, double axial_depth_mm, const ZLevels& z) {
  if (auto problems = validate(spec, tool, axial_depth_mm); !problems.empty()) throw InputError(std::move(problems));
  using detail::on_circle;
  const double r = tool.radius_mm();
  const Point2 o = spec.center;
  const double rho0 = spec.initial_radius_mm - r;
  const double rho1 = spec.final_radius_mm - r;
  const int n = std::max(1, static_cast<int>(std::ceil((rho1 - rho0) / spec.pitch_mm - 1e-9)));
  const double pitch = (rho1 - rho0) / n;
  const double z_cut = z.top_z_mm - axial_depth_mm;
  const double ad = axial_depth_mm;
  const Point2 o_shifted{o.x_mm + 0.5 * pitch, o.y_mm};

  // Built counter-clockwise; kCw is the mirror image about the X axis through O.
  detail::PathBuilder b({});
  b.begin_part("entry");
  b.enter(o, z, z_cut);
  b.line_to(on_circle(o, rho0, 0, z_cut), false, 0);
  for (int k = 0; k < n; ++k) {
    b.begin_part("spiral turn " + std::to_string(k + 1));
    const double rho = rho0 + k * pitch;
    b.arc_to(on_circle(o, rho, kPi, z_cut), o, true, kPi, true, ad);
    // About O' the end point at angle 2π is O + (ρ + p', 0), computed from O so no error accumulates.
    b.arc_to(on_circle(o, rho + pitch, 0, z_cut), o_shifted, true, kPi, true, ad);
  }
  b.begin_part("finishing circle");
  b.circle(o, true, true, ad);
  b.begin_part("exit");
  b.line_to({o.x_mm, o.y_mm, z_cut}, false, 0);
  b.retract(z);

  Cycle cycle;
  cycle.tool = tool;
  cycle.path = b.finish();
  const double half = spec.final_radius_mm + 2.0 * tool.diameter_mm;
  const geometry::StockRegion region{
      geometry::Contour::rectangle({o.x_mm - half, o.y_mm - half}, {o.x_mm + half, o.y_mm + half}),
      {geometry::Contour::circle(o, spec.initial_radius_mm)}};
  cycle.stock = detail::block_stock({region}, z, axial_depth_mm);
  if (spec.direction == Direction::kCw) {
    cycle.path = detail::mirrored(cycle.path, o, {1.0, 0.0});
    cycle.stock = detail::mirrored(cycle.stock, o, {1.0, 0.0});
  }
  if (pitch < spec.pitch_mm - 1e-12) {
    cycle.notes.push_back("spiral pitch reduced from " + six_digit_number_text(spec.pitch_mm) + " to " +
                          six_digit_number_text(pitch) + " mm to end on the final radius (" + std::to_string(n) +
                          " turns)");
  }
  return cycle;
}

}  // namespace feedplan::cycles
