#include "feedplan/cycles/trochoid.hpp"

#include <cmath>
#include <string>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "path_builder.hpp"
#include "problems.hpp"

namespace feedplan::cycles {

using geometry::Point2;

namespace {

// Number of pitch steps from the first to the last loop centre; the 1e-9 keeps an exact multiple
// (9 mm at 1 mm) from gaining a step through rounding.
int step_count(double length_mm, double pitch_mm) {
  return std::max(1, static_cast<int>(std::ceil(length_mm / pitch_mm - 1e-9)));
}

}  // namespace

std::vector<InputProblem> validate(const TrochoidSpec& spec, const geometry::Tool& tool, double axial_depth_mm) {
  using namespace detail;
  std::vector<InputProblem> problems = validate_tool(tool);
  const bool tool_ok = problems.empty();
  const double d = tool.diameter_mm;
  check(problems, "axial_depth_mm", axial_depth_mm, above(0), "the depth of the slot below the stock top");
  const bool start_ok = check_finite(problems, "trochoid.start", spec.start);
  const bool end_ok = check_finite(problems, "trochoid.end", spec.end);
  if (start_ok && end_ok &&
      !(std::hypot(spec.end.x_mm - spec.start.x_mm, spec.end.y_mm - spec.start.y_mm) > 1e-9)) {
    problems.push_back({"trochoid.end", "= " + format_point(spec.end) + ": must differ from start " +
                                            format_point(spec.start) + " — the slot needs a direction"});
  }
  bool pitch_ok = false;
  if (tool_ok) {
    pitch_ok = check(problems, "trochoid.pitch_mm", spec.pitch_mm, open_range(0, d),
                     "a pitch of at least the tool diameter leaves uncut material between loops");
  } else {
    pitch_ok = check(problems, "trochoid.pitch_mm", spec.pitch_mm, above(0));
  }
  if (check(problems, "trochoid.loop_radius_mm", spec.loop_radius_mm, above(0),
            "the radius of the tool-centre circles") &&
      pitch_ok && !(spec.loop_radius_mm > spec.pitch_mm)) {
    problems.push_back({"trochoid.loop_radius_mm",
                        "= " + six_digit_number_text(spec.loop_radius_mm) + ": must be > pitch_mm = " +
                            six_digit_number_text(spec.pitch_mm) +
                            " — with smaller loops the step between loops cuts into solid material"});
  }
  return problems;
}

Cycle generate_trochoid(const TrochoidSpec& spec, const geometry::Tool& tool, double axial_depth_mm,
                        const ZLevels& z) {
  if (auto problems = validate(spec, tool, axial_depth_mm); !problems.empty()) throw InputError(std::move(problems));
  using detail::on_circle;
  const double r = tool.radius_mm();
  const double rt = spec.loop_radius_mm;
  const double dx = spec.end.x_mm - spec.start.x_mm;
  const double dy = spec.end.y_mm - spec.start.y_mm;
  const double length = std::hypot(dx, dy);
  const Point2 u{dx / length, dy / length};
  const Point2 v{-u.y_mm, u.x_mm};
  const int n = step_count(length, spec.pitch_mm);
  const double pitch = length / n;
  const double z_cut = z.top_z_mm - axial_depth_mm;
  const double ad = axial_depth_mm;

  auto along = [&](double s, double t) {  // start + s·u + t·v
    return Point2{spec.start.x_mm + s * u.x_mm + t * v.x_mm, spec.start.y_mm + s * u.y_mm + t * v.y_mm};
  };
  auto at = [&](const Point2& p) { return geometry::Point3{p.x_mm, p.y_mm, z_cut}; };

  // Built counter-clockwise; kCw is the mirror image about the slot axis.
  detail::PathBuilder b({});
  b.begin_part("entry");
  b.enter(along(0, -rt), z, z_cut);
  for (int k = 0; k <= n; ++k) {
    b.begin_part("loop " + std::to_string(k + 1));
    if (k > 0) b.line_to(at(along(k * pitch, -rt)), true, ad);
    b.circle(along(k * pitch, 0), true, true, ad);
  }
  b.begin_part("exit");
  b.line_to(at(along(n * pitch, 0)), false, 0);
  b.retract(z);

  Cycle cycle;
  cycle.tool = tool;
  cycle.path = b.finish();
  const double reach = rt + r;
  const double side = rt + 3.0 * r;
  const geometry::Contour block = geometry::Contour::polygon(
      {along(reach - pitch, -side), along(length + side, -side), along(length + side, side), along(reach - pitch, side)});
  cycle.stock = detail::block_stock({{block, {}}}, z, axial_depth_mm);
  if (spec.direction == Direction::kCw) {
    cycle.path = detail::mirrored(cycle.path, spec.start, u);
    cycle.stock = detail::mirrored(cycle.stock, spec.start, u);
  }
  if (pitch < spec.pitch_mm - 1e-12) {
    cycle.notes.push_back("trochoid pitch reduced from " + six_digit_number_text(spec.pitch_mm) + " to " +
                          six_digit_number_text(pitch) + " mm so that " + std::to_string(n) +
                          " equal steps end on the last loop centre");
  }
  return cycle;
}

}  // namespace feedplan::cycles
