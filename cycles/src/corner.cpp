#include "feedplan/cycles/corner.hpp"

#include <cmath>
#include <string>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "path_builder.hpp"
#include "problems.hpp"

namespace feedplan::cycles {

using geometry::Point2;
using geometry::Point3;

namespace {

Point2 add(const Point2& p, double s, const Point2& d) { return {p.x_mm + s * d.x_mm, p.y_mm + s * d.y_mm}; }
Point2 add(const Point2& p, double s, const Point2& d, double t, const Point2& e) { return add(add(p, s, d), t, e); }

// The corner's frame: wall directions, left normals (towards the free side), the bisector into the
// free side, and the finished corner arc's centre and tangent points.
struct CornerFrame {
  Point2 k, d1, n1, d2, n2, bisector, q, t1, t2, s1, e2;
  double deflection_rad = 0.0;  // δ = π − γ: how far the travel turns left at the corner
};

CornerFrame frame_of(const CornerSpec& spec) {
  CornerFrame f;
  const double heading = deg_to_rad(spec.entry_heading_deg);
  const double half_angle = 0.5 * deg_to_rad(spec.corner_angle_deg);
  f.deflection_rad = kPi - deg_to_rad(spec.corner_angle_deg);
  f.k = spec.corner_point;
  f.d1 = {std::cos(heading), std::sin(heading)};
  f.n1 = {-f.d1.y_mm, f.d1.x_mm};
  f.d2 = {std::cos(heading + f.deflection_rad), std::sin(heading + f.deflection_rad)};
  f.n2 = {-f.d2.y_mm, f.d2.x_mm};
  // The bisector of the interior angle points between −d1 and d2, into the free side.
  const double bx = f.d2.x_mm - f.d1.x_mm;
  const double by = f.d2.y_mm - f.d1.y_mm;
  const double bn = std::hypot(bx, by);
  f.bisector = {bx / bn, by / bn};
  const double tangent = spec.corner_radius_mm / std::tan(half_angle);  // K to the tangent points
  f.t1 = add(f.k, -tangent, f.d1);
  f.t2 = add(f.k, tangent, f.d2);
  f.q = add(f.t1, spec.corner_radius_mm, f.n1);
  f.s1 = add(f.t1, -spec.wall_length_mm, f.d1);
  f.e2 = add(f.t2, spec.wall_length_mm, f.d2);
  return f;
}

double lead_of(const CornerSpec& spec, const geometry::Tool& tool) { return spec.lead_mm.value_or(tool.diameter_mm); }

// The stock before the cut, counter-clockwise orientation irrelevant: a block from the entry face
// through s1 to the exit face through e2, 2·D behind the walls, bounded on the free side by the
// earlier pass's centre path (inside that pass's sweep), minus that earlier pass.
geometry::Stock implied_stock(const CornerSpec& spec, const geometry::Tool& tool, double axial_depth_mm,
                              const ZLevels& z) {
  const CornerFrame f = frame_of(spec);
  const double r = tool.radius_mm();
  const double offset = r + spec.radial_depth_mm;         // earlier pass's centre from the walls
  const double earlier_radius = spec.corner_radius_mm - offset;  // its corner arc about Q
  const double behind = 2.0 * tool.diameter_mm;
  const double half_angle = 0.5 * deg_to_rad(spec.corner_angle_deg);
  const double z_cut = z.top_z_mm - axial_depth_mm;

  // Earlier pass: lines at `offset`, extended a lead and a diameter beyond the block.
  const double extension = lead_of(spec, tool) + tool.diameter_mm;
  std::vector<Point2> free_side;  // block boundary on the free side, from s1 to e2
  const Point2 first = add(f.s1, -extension, f.d1, offset, f.n1);
  const Point2 last = add(f.e2, extension, f.d2, offset, f.n2);
  auto at = [&](const Point2& p) { return Point3{p.x_mm, p.y_mm, z_cut}; };
  geometry::ToolPath earlier_path;
  {
    detail::PathBuilder pass(at(first));
    pass.begin_part("earlier pass");
    free_side.push_back(add(f.s1, offset, f.n1));
    if (earlier_radius > 0.0) {
      const Point2 a1 = add(f.t1, offset, f.n1);
      const Point2 a2 = add(f.t2, offset, f.n2);
      pass.line_to(at(a1), true, axial_depth_mm);
      pass.arc_to(at(a2), f.q, true, f.deflection_rad, true, axial_depth_mm);
      // Polygon through points of the earlier arc: chords stay within its sweep (sagitta ≪ r).
      const int pieces = std::max(2, static_cast<int>(std::ceil(f.deflection_rad / deg_to_rad(3.0))));
      const double start_angle = std::atan2(a1.y_mm - f.q.y_mm, a1.x_mm - f.q.x_mm);
      for (int i = 0; i <= pieces; ++i) {
        const double angle = start_angle + f.deflection_rad * i / pieces;
        free_side.push_back(geometry::xy(detail::on_circle(f.q, earlier_radius, angle, 0.0)));
      }
    } else {
      const Point2 sharp = add(f.k, offset / std::sin(half_angle), f.bisector);
      pass.line_to(at(sharp), true, axial_depth_mm);
      free_side.push_back(sharp);
    }
    pass.line_to(at(last), true, axial_depth_mm);
    free_side.push_back(add(f.e2, offset, f.n2));
    earlier_path = pass.finish();
  }

  std::vector<Point2> vertices = free_side;
  vertices.push_back(add(f.e2, -behind, f.n2));
  vertices.push_back(add(f.k, -behind / std::sin(half_angle), f.bisector));
  vertices.push_back(add(f.s1, -behind, f.n1));
  geometry::Stock stock = detail::block_stock({{geometry::Contour::polygon(vertices), {}}}, z, axial_depth_mm);
  for (const auto& move : earlier_path.moves) stock.removed.push_back({move, r});
  return stock;
}

}  // namespace

std::vector<InputProblem> validate(const CornerSpec& spec, const geometry::Tool& tool, double axial_depth_mm) {
  using namespace detail;
  std::vector<InputProblem> problems = validate_tool(tool);
  const bool tool_ok = problems.empty();
  const double r = tool.radius_mm();
  const double d = tool.diameter_mm;
  bool ok = tool_ok;
  ok &= check(problems, "axial_depth_mm", axial_depth_mm, above(0), "the depth of the walls below the stock top");
  ok &= check_finite(problems, "corner.corner_point", spec.corner_point);
  ok &= check_finite(problems, "corner.entry_heading_deg", spec.entry_heading_deg);
  ok &= check(problems, "corner.corner_angle_deg", spec.corner_angle_deg, open_range(0, 180),
              "the interior angle of an internal corner between two walls");
  if (tool_ok) {
    ok &= check(problems, "corner.corner_radius_mm", spec.corner_radius_mm, above(r),
                "a corner radius of at most the tool radius " + six_digit_number_text(r) + " cannot be cut with this tool");
    ok &= check(problems, "corner.radial_depth_mm", spec.radial_depth_mm, {0, false, d, true},
                "the radial depth of cut is at most the tool diameter");
  } else {
    ok &= check(problems, "corner.corner_radius_mm", spec.corner_radius_mm, above(0));
    ok &= check(problems, "corner.radial_depth_mm", spec.radial_depth_mm, above(0));
  }
  ok &= check(problems, "corner.wall_length_mm", spec.wall_length_mm, above(0),
              "length of each straight wall from its tangent point");
  if (spec.lead_mm) {
    if (tool_ok) {
      ok &= check(problems, "corner.lead_mm", *spec.lead_mm, above(r),
                  "the tool (radius " + six_digit_number_text(r) + ") must plunge clear of the stock");
    } else {
      ok &= check(problems, "corner.lead_mm", *spec.lead_mm, above(0));
    }
  }
  if (ok) {
    // Very sharp corners with short walls fold the implied block over itself.
    const auto stock_problems = geometry::validate(implied_stock(spec, tool, axial_depth_mm, {}), "stock");
    if (!stock_problems.empty()) {
      problems.push_back({"corner.wall_length_mm",
                          "= " + six_digit_number_text(spec.wall_length_mm) + ": too short for corner_angle_deg = " +
                              six_digit_number_text(spec.corner_angle_deg) + " and radial_depth_mm = " +
                              six_digit_number_text(spec.radial_depth_mm) +
                              " — the implied stock block is not a simple polygon; lengthen the walls (" +
                              stock_problems.front().message + ")"});
    }
  }
  return problems;
}

Cycle generate_corner(const CornerSpec& spec, const geometry::Tool& tool, double axial_depth_mm, const ZLevels& z) {
  if (auto problems = validate(spec, tool, axial_depth_mm); !problems.empty()) throw InputError(std::move(problems));
  const CornerFrame f = frame_of(spec);
  const double r = tool.radius_mm();
  const double lead = lead_of(spec, tool);
  const double z_cut = z.top_z_mm - axial_depth_mm;
  const double ad = axial_depth_mm;
  auto at = [&](const Point2& p) { return Point3{p.x_mm, p.y_mm, z_cut}; };

  // Built turning left (walls on the right); kCw is the mirror image about wall 1's line.
  detail::PathBuilder b({});
  b.begin_part("approach");
  b.enter(add(f.s1, -lead, f.d1, r, f.n1), z, z_cut);
  b.line_to(at(add(f.s1, -r, f.d1, r, f.n1)), false, 0);
  b.begin_part("wall 1");
  b.line_to(at(add(f.t1, r, f.n1)), true, ad);
  b.begin_part("corner");
  b.arc_to(at(add(f.t2, r, f.n2)), f.q, true, f.deflection_rad, true, ad);
  b.begin_part("wall 2");
  b.line_to(at(add(f.e2, r, f.d2, r, f.n2)), true, ad);
  b.begin_part("departure");
  b.line_to(at(add(f.e2, lead, f.d2, r, f.n2)), false, 0);
  b.retract(z);

  Cycle cycle;
  cycle.tool = tool;
  cycle.path = b.finish();
  cycle.stock = implied_stock(spec, tool, axial_depth_mm, z);
  if (spec.direction == Direction::kCw) {
    cycle.path = detail::mirrored(cycle.path, f.k, f.d1);
    cycle.stock = detail::mirrored(cycle.stock, f.k, f.d1);
  }
  if (spec.corner_radius_mm - r - spec.radial_depth_mm <= 0.0) {
    cycle.notes.push_back("the earlier pass turns the corner sharply (corner_radius_mm − tool radius − radial_depth_mm "
                          "= " + six_digit_number_text(spec.corner_radius_mm - r - spec.radial_depth_mm) +
                          " mm ≤ 0), so the surface before this pass is not concentric with the finished corner");
  }
  return cycle;
}

}  // namespace feedplan::cycles
