#include "feedplan/cycles/helical_boring.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "path_builder.hpp"
#include "problems.hpp"

namespace feedplan::cycles {

using geometry::Point2;

std::vector<InputProblem> validate(const HelicalBoringSpec& spec, const geometry::Tool& tool) {
  using namespace detail;
  std::vector<InputProblem> problems = validate_tool(tool);
  const bool tool_ok = problems.empty();
  const double d = tool.diameter_mm;
  check_finite(problems, "helical_boring.center", spec.center);
  if (tool_ok) {
    const Range range{d, false, 2.0 * d, true};
    if (!range.contains(spec.hole_diameter_mm)) {
      const bool too_large = std::isfinite(spec.hole_diameter_mm) && spec.hole_diameter_mm > 2.0 * d;
      check(problems, "helical_boring.hole_diameter_mm", spec.hole_diameter_mm, range,
            too_large ? "a hole larger than twice the tool diameter leaves an uncut core in the middle; bore " +
                            six_digit_number_text(2.0 * d) + " mm and expand it with a spiral cycle"
                      : "the hole must be larger than the tool");
    }
    check(problems, "helical_boring.pitch_mm", spec.pitch_mm, open_range(0, d),
          "the helix descends less than one tool diameter per turn");
  } else {
    check(problems, "helical_boring.hole_diameter_mm", spec.hole_diameter_mm, above(0));
    check(problems, "helical_boring.pitch_mm", spec.pitch_mm, above(0));
  }
  check(problems, "helical_boring.depth_mm", spec.depth_mm, above(0), "the hole depth below the stock top");
  return problems;
}

Cycle generate_helical_boring(const HelicalBoringSpec& spec, const geometry::Tool& tool, const ZLevels& z) {
  if (auto problems = validate(spec, tool); !problems.empty()) throw InputError(std::move(problems));
  using detail::on_circle;
  const Point2 o = spec.center;
  const double rho = 0.5 * (spec.hole_diameter_mm - tool.diameter_mm);
  const double p = spec.pitch_mm;
  const double z_bottom = z.top_z_mm - spec.depth_mm;
  const int turns = std::max(1, static_cast<int>(std::ceil(spec.depth_mm / p - 1e-9)));

  // Built counter-clockwise; kCw is the mirror image about the X axis through O.
  detail::PathBuilder b({});
  b.begin_part("entry");
  b.enter({o.x_mm + rho, o.y_mm}, z, z.top_z_mm);
  for (int k = 1; k <= turns; ++k) {
    b.begin_part("helix turn " + std::to_string(k));
    if (k < turns) {
      b.arc_to({b.position().x_mm, b.position().y_mm, z.top_z_mm - k * p}, o, true, kTwoPi, true, p);
    } else {
      // The last turn ends exactly at the bottom: partial when depth / p is not an integer.
      const double fraction = spec.depth_mm / p - (turns - 1);
      const double sweep = std::abs(fraction - 1.0) < 1e-9 ? kTwoPi : kTwoPi * fraction;
      b.arc_to(on_circle(o, rho, sweep, z_bottom), o, true, sweep, true, p);
    }
  }
  b.begin_part("bottom circle");
  b.circle(o, true, true, p);
  b.begin_part("exit");
  b.line_to({o.x_mm, o.y_mm, z_bottom}, false, 0);
  b.retract(z);

  Cycle cycle;
  cycle.tool = tool;
  cycle.path = b.finish();
  const double half = 0.5 * spec.hole_diameter_mm + 2.0 * tool.diameter_mm;
  cycle.stock = detail::block_stock(
      {{geometry::Contour::rectangle({o.x_mm - half, o.y_mm - half}, {o.x_mm + half, o.y_mm + half}), {}}}, z,
      spec.depth_mm);
  if (spec.direction == Direction::kCw) {
    cycle.path = detail::mirrored(cycle.path, o, {1.0, 0.0});
    cycle.stock = detail::mirrored(cycle.stock, o, {1.0, 0.0});
  }
  const double last_turn = spec.depth_mm / p - (turns - 1);
  if (last_turn < 1.0 - 1e-9) {
    cycle.notes.push_back("the last helix turn is partial (" + six_digit_number_text(last_turn) +
                          " turn) so the helix ends exactly at depth " + six_digit_number_text(spec.depth_mm) +
                          " mm");
  }
  return cycle;
}

}  // namespace feedplan::cycles
