#include "feedplan/cycles/pocket.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/helical_boring.hpp"
#include "feedplan/cycles/spiral.hpp"
#include "feedplan/cycles/trochoid.hpp"
#include "path_builder.hpp"
#include "problems.hpp"

namespace feedplan::cycles {

using geometry::Point2;
using geometry::Point3;

namespace {

// Defaults as fractions of the tool diameter.
constexpr double kAllowancePerDiameter = 0.15;
constexpr double kPitchPerDiameter = 0.1;
// Centre bore diameter per tool diameter, and the smallest room across the pocket beyond the tool
// and the allowances (the bore needs a hole larger than the tool).
constexpr double kBorePerDiameter = 1.6;
constexpr double kBoreRoomPerDiameter = 0.1;
// Below this the spiral would expand the bore by less than a micrometre: bore to size instead.
constexpr double kMinSpiralGrowthMm = 1e-3;

struct PocketPlan {
  double r = 0, d = 0;
  double allowance = 0, helix_pitch = 0, spiral_pitch = 0, trochoid_pitch = 0;
  double long_side = 0, short_side = 0;
  Point2 ex, ey;              // long axis and its left normal
  std::string plus, minus;    // slot names: "+x"/"-x" or "+y"/"-y"
  double rough_radius = 0;    // R_s = S/2 − a: spiral and slot half-width
  double hole_diameter = 0;   // centre bore
  bool clamped_hole = false;  // hole smaller than 1.6·D to fit
  bool spiral = false;
  double slot_length = 0;     // (L − S) / 2: last loop centre from C
  double loop_radius = 0;     // R_t = R_s − r
  bool reduced_trochoid_pitch = false;
};

double short_side_of(const PocketSpec& spec) { return std::min(spec.width_mm, spec.height_mm); }
const char* short_field(const PocketSpec& spec) {
  return spec.width_mm <= spec.height_mm ? "pocket.width_mm" : "pocket.height_mm";
}

// Largest short side whose corners the slot and the wall pass still reach: the wall pass clears
// 2r from the walls, so the inner rounded rectangle inset by 2r (corner radius ρ = max(R_c − 2r, 0))
// must lie inside the roughed stadium of radius R_s = S/2 − a. Its farthest point from the slot end
// centre is √2·(S/2 − 2r − ρ) + ρ away.
double max_short_side(double r, double allowance, double corner_radius) {
  const double rho = std::max(corner_radius - 2.0 * r, 0.0);
  return 2.0 * (std::sqrt(2.0) * (2.0 * r + rho) - rho - allowance) / (std::sqrt(2.0) - 1.0);
}

PocketPlan plan_of(const PocketSpec& spec, const geometry::Tool& tool) {
  PocketPlan p;
  p.d = tool.diameter_mm;
  p.r = tool.radius_mm();
  p.allowance = spec.finish_allowance_mm.value_or(kAllowancePerDiameter * p.d);
  p.helix_pitch = spec.helix_pitch_mm.value_or(kPitchPerDiameter * p.d);
  p.spiral_pitch = spec.spiral_pitch_mm.value_or(kPitchPerDiameter * p.d);
  const double trochoid_pitch = spec.trochoid_pitch_mm.value_or(kPitchPerDiameter * p.d);
  const bool long_x = spec.width_mm >= spec.height_mm;
  p.long_side = std::max(spec.width_mm, spec.height_mm);
  p.short_side = short_side_of(spec);
  p.ex = long_x ? Point2{1, 0} : Point2{0, 1};
  p.ey = long_x ? Point2{0, 1} : Point2{-1, 0};
  p.plus = long_x ? "+x" : "+y";
  p.minus = long_x ? "-x" : "-y";
  p.rough_radius = 0.5 * p.short_side - p.allowance;
  p.hole_diameter = kBorePerDiameter * p.d;
  p.spiral = 2.0 * p.rough_radius - p.hole_diameter > 2.0 * kMinSpiralGrowthMm;
  if (!p.spiral) {
    p.clamped_hole = 2.0 * p.rough_radius < p.hole_diameter;
    p.hole_diameter = 2.0 * p.rough_radius;
  }
  p.slot_length = 0.5 * (p.long_side - p.short_side);
  p.loop_radius = p.rough_radius - p.r;
  p.trochoid_pitch = std::min(trochoid_pitch, 0.5 * p.loop_radius);
  p.reduced_trochoid_pitch = p.trochoid_pitch < trochoid_pitch;
  return p;
}

}  // namespace

std::vector<InputProblem> validate(const PocketSpec& spec, const geometry::Tool& tool) {
  using namespace detail;
  std::vector<InputProblem> problems = validate_tool(tool);
  const bool tool_ok = problems.empty();
  const double r = tool.radius_mm();
  const double d = tool.diameter_mm;
  check_finite(problems, "pocket.center", spec.center);
  bool sizes_ok = check(problems, "pocket.width_mm", spec.width_mm, above(0), "the pocket's size along X");
  sizes_ok &= check(problems, "pocket.height_mm", spec.height_mm, above(0), "the pocket's size along Y");
  check(problems, "pocket.depth_mm", spec.depth_mm, above(0), "the pocket's depth below the stock top");
  bool allowance_ok = true;
  if (spec.finish_allowance_mm) {
    allowance_ok = tool_ok ? check(problems, "pocket.finish_allowance_mm", *spec.finish_allowance_mm, open_range(0, r),
                                   "the finishing pass takes less than the tool radius")
                           : check(problems, "pocket.finish_allowance_mm", *spec.finish_allowance_mm, above(0));
  }
  for (const auto& [field, value, what] :
       {std::tuple{"pocket.helix_pitch_mm", spec.helix_pitch_mm, "helix turns"},
        std::tuple{"pocket.spiral_pitch_mm", spec.spiral_pitch_mm, "spiral turns"},
        std::tuple{"pocket.trochoid_pitch_mm", spec.trochoid_pitch_mm, "trochoid loops"}}) {
    if (!value) continue;
    if (tool_ok) {
      check(problems, field, *value, open_range(0, d),
            std::string("a pitch of at least the tool diameter leaves uncut material between ") + what);
    } else {
      check(problems, field, *value, above(0));
    }
  }
  bool corner_ok = false;
  if (tool_ok && sizes_ok && 0.5 * short_side_of(spec) <= r) {
    // The pocket is too narrow for the tool: the width check below says so; the corner radius can
    // only be checked against the tool here.
    check(problems, "pocket.corner_radius_mm", spec.corner_radius_mm, above(r),
          "the tool cannot cut a corner radius of at most its radius " + six_digit_number_text(r));
  } else if (tool_ok && sizes_ok) {
    const double s = short_side_of(spec);
    corner_ok = check(problems, "pocket.corner_radius_mm", spec.corner_radius_mm, {r, false, 0.5 * s, true},
                      "more than the tool radius " + six_digit_number_text(r) + " (the tool cannot cut a smaller corner) and " +
                          "at most half the short side " + six_digit_number_text(s));
  } else {
    check(problems, "pocket.corner_radius_mm", spec.corner_radius_mm, above(0));
  }
  if (tool_ok && sizes_ok && allowance_ok) {
    const double a = spec.finish_allowance_mm.value_or(kAllowancePerDiameter * d);
    const double s = short_side_of(spec);
    const double s_min = d + 2.0 * a + kBoreRoomPerDiameter * d;
    if (s < s_min) {
      problems.push_back({short_field(spec), "= " + six_digit_number_text(s) + ": must be ≥ " + six_digit_number_text(s_min) +
                                                 " — the tool (" + six_digit_number_text(d) + " mm), the finishing allowance " +
                                                 "on both walls (2 × " + six_digit_number_text(a) + " mm) and room for the " +
                                                 "centre bore (" + six_digit_number_text(kBoreRoomPerDiameter * d) +
                                                 " mm) must fit across the pocket"});
    } else if (corner_ok) {
      const double s_max = max_short_side(r, a, spec.corner_radius_mm);
      if (s > s_max) {
        problems.push_back(
            {short_field(spec),
             "= " + six_digit_number_text(s) + ": must be ≤ " + six_digit_number_text(s_max) + " for a " + six_digit_number_text(d) +
                 " mm tool with corner_radius_mm = " + six_digit_number_text(spec.corner_radius_mm) +
                 " and finish_allowance_mm = " + six_digit_number_text(a) +
                 " — this pocket cycle cuts one slot along the pocket and one wall pass, which cannot reach material "
                 "more than 2 tool radii from the walls in the corners of a wider pocket; use a larger tool or "
                 "split the pocket"});
      }
    }
  }
  return problems;
}

namespace {


// Appends a sub-cycle's path and notes, both under `prefix`.
void append_sub_cycle(Cycle& cycle, const Cycle& sub, const std::string& prefix) {
  detail::append(cycle.path, sub.path, prefix);
  for (const auto& note : sub.notes) cycle.notes.push_back(prefix + note);
}

// Motion step 1: the helical boring at C.
void bore_centre(const PocketSpec& spec, const PocketPlan& p, const geometry::Tool& tool, const ZLevels& z,
                 Cycle& cycle) {
  const Cycle boring =
      generate_helical_boring({spec.center, p.hole_diameter, p.helix_pitch, spec.depth_mm, spec.direction}, tool, z);
  append_sub_cycle(cycle, boring, "boring: ");
  if (p.clamped_hole) {
    cycle.notes.push_back("boring: hole diameter " + six_digit_number_text(p.hole_diameter) + " mm instead of " +
                          six_digit_number_text(kBorePerDiameter * p.d) + " mm to fit the pocket; no spiral");
  }
}

// Motion step 2: the spiral from the bore out to R_s.
void expand_bore(const PocketSpec& spec, const PocketPlan& p, const geometry::Tool& tool, const ZLevels& z,
                 Cycle& cycle) {
  const Cycle spiral = generate_spiral(
      {spec.center, 0.5 * p.hole_diameter, p.rough_radius, p.spiral_pitch, spec.direction}, tool, spec.depth_mm, z);
  append_sub_cycle(cycle, spiral, "spiral: ");
}

// Motion step 3: the trochoid slots along the long axis, + first.
void cut_slots(const PocketSpec& spec, const PocketPlan& p, const geometry::Tool& tool, const ZLevels& z,
               Cycle& cycle) {
  const Point2 c = spec.center;
  for (const double sign : {1.0, -1.0}) {
    const std::string prefix = "slot " + (sign > 0 ? p.plus : p.minus) + ": ";
    const Point2 end{c.x_mm + sign * p.slot_length * p.ex.x_mm, c.y_mm + sign * p.slot_length * p.ex.y_mm};
    const Cycle slot =
        generate_trochoid({c, end, p.loop_radius, p.trochoid_pitch, spec.direction}, tool, spec.depth_mm, z);
    append_sub_cycle(cycle, slot, prefix);
  }
  if (p.reduced_trochoid_pitch) {
    cycle.notes.push_back("slots: trochoid pitch reduced to " + six_digit_number_text(p.trochoid_pitch) +
                          " mm, half the loop radius " + six_digit_number_text(p.loop_radius) + " mm");
  }
}

// The wall pass's canonical coordinates: a along the long axis, b along its left normal, mirrored for
// kCw; positions at the cutting depth z_c.
struct WallFrame {
  WallFrame(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z)
      : c(spec.center),
        ex(p.ex),
        ey(p.ey),
        sign(spec.direction == Direction::kCcw ? 1.0 : -1.0),
        z_cut(z.top_z_mm - spec.depth_mm),
        hx(0.5 * p.long_side - p.r),
        hy(0.5 * p.short_side - p.r),
        sx(hx - (spec.corner_radius_mm - p.r)),
        sy(hy - (spec.corner_radius_mm - p.r)) {}
  bool ccw() const { return sign > 0; }
  Point2 xy(double a, double b) const {
    return Point2{c.x_mm + a * ex.x_mm + sign * b * ey.x_mm, c.y_mm + a * ex.y_mm + sign * b * ey.y_mm};
  }
  Point3 at(double a, double b) const {
    const Point2 q = xy(a, b);
    return Point3{q.x_mm, q.y_mm, z_cut};
  }

  Point2 c, ex, ey;  // pocket centre C, long axis, its left normal
  double sign;       // +1 for kCcw, −1 for kCw
  double z_cut;      // z_c = top − depth
  double hx, hy;     // half sizes of the tool-centre contour (walls inset by r)
  double sx, sy;     // corner centres of the contour (radius R_c − r)
};

// Motion step 4: down at C to z_c, then the lead-in: the semicircle with diameter C–E, tangent to
// wall 1 at E. The tool stays inside the roughed disc of radius R_s about C while its centre is within
// R_s − r = hy − a of C, i.e. for the first ψ_t = 2·asin((hy − a) / hy) of the sweep.
void enter_walls(detail::PathBuilder& b, const WallFrame& w, const PocketPlan& p, const ZLevels& z, double depth) {
  const double hy = w.hy;
  b.begin_part("entry");
  b.enter(w.c, z, w.z_cut);
  const double lead_radius = 0.5 * hy;
  const Point2 lead_center = w.xy(0, -lead_radius);
  const double air_sweep = 2.0 * std::asin((hy - p.allowance) / hy);
  const double touch_angle = 0.5 * kPi + air_sweep;
  b.arc_to(w.at(lead_radius * std::cos(touch_angle), -lead_radius + lead_radius * std::sin(touch_angle)), lead_center,
           w.ccw(), air_sweep, false, 0);
  b.begin_part("lead-in");
  b.arc_to(w.at(0, -hy), lead_center, w.ccw(), kPi - air_sweep, true, depth);
}

// Motion step 5: from E along wall 1, the corners and the other walls, and back to E.
void follow_walls(detail::PathBuilder& b, const WallFrame& w, double depth) {
  const bool ccw = w.ccw();
  const double hx = w.hx, hy = w.hy, sx = w.sx, sy = w.sy;
  const double quarter = 0.5 * kPi;
  b.begin_part("wall 1");
  b.line_to(w.at(sx, -hy), true, depth);
  b.begin_part("corner 1");
  b.arc_to(w.at(hx, -sy), w.xy(sx, -sy), ccw, quarter, true, depth);
  b.begin_part("wall 2");
  b.line_to(w.at(hx, sy), true, depth);
  b.begin_part("corner 2");
  b.arc_to(w.at(sx, hy), w.xy(sx, sy), ccw, quarter, true, depth);
  b.begin_part("wall 3");
  b.line_to(w.at(-sx, hy), true, depth);
  b.begin_part("corner 3");
  b.arc_to(w.at(-hx, sy), w.xy(-sx, sy), ccw, quarter, true, depth);
  b.begin_part("wall 4");
  b.line_to(w.at(-hx, -sy), true, depth);
  b.begin_part("corner 4");
  b.arc_to(w.at(-sx, -hy), w.xy(-sx, -sy), ccw, quarter, true, depth);
  b.begin_part("wall 1 end");
  b.line_to(w.at(0, -hy), true, depth);
}

// Motion step 6: back to C in air, up to the clearance height.
void leave_walls(detail::PathBuilder& b, const WallFrame& w, const ZLevels& z) {
  b.begin_part("exit");
  b.line_to(w.at(0, 0), false, 0);
  b.retract(z);
}

// Motion steps 4–6: the wall pass, and a note when the corners hold more than the allowance.
void finish_walls(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z, Cycle& cycle) {
  const WallFrame w(spec, p, z);
  detail::PathBuilder b({});
  enter_walls(b, w, p, z, spec.depth_mm);
  follow_walls(b, w, spec.depth_mm);
  leave_walls(b, w, z);
  detail::append(cycle.path, b.finish(), "walls: ");
  // Thickest wall stock: at the corners, measured from the slot end centre (round slot ends).
  const double s2 = 0.5 * p.short_side;
  const double thickest = std::sqrt(2.0) * (s2 - spec.corner_radius_mm) + spec.corner_radius_mm - p.rough_radius;
  if (thickest > p.allowance + 1e-6) {
    cycle.notes.push_back("walls: the roughing leaves up to " + six_digit_number_text(thickest) +
                          " mm on the walls at the corners (" + six_digit_number_text(p.allowance) +
                          " mm on the long walls); the wall pass takes it with a larger engagement");
  }
}

// The solid block before any sub-cycle: the pocket's rectangle grown by 2·D on each side.
geometry::Stock pocket_stock(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z) {
  const Point2 c = spec.center;
  const double margin = 2.0 * p.d;
  const double hw = 0.5 * spec.width_mm + margin;
  const double hh = 0.5 * spec.height_mm + margin;
  return detail::block_stock(
      {{geometry::Contour::rectangle({c.x_mm - hw, c.y_mm - hh}, {c.x_mm + hw, c.y_mm + hh}), {}}}, z, spec.depth_mm);
}

}  // namespace

Cycle generate_pocket(const PocketSpec& spec, const geometry::Tool& tool, const ZLevels& z) {
  if (auto problems = validate(spec, tool); !problems.empty()) throw InputError(std::move(problems));
  const PocketPlan p = plan_of(spec, tool);
  Cycle cycle;
  cycle.tool = tool;
  bore_centre(spec, p, tool, z, cycle);
  if (p.spiral) expand_bore(spec, p, tool, z, cycle);
  if (p.slot_length > 1e-9) cut_slots(spec, p, tool, z, cycle);
  finish_walls(spec, p, z, cycle);
  cycle.stock = pocket_stock(spec, p, z);
  return cycle;
}

}  // namespace feedplan::cycles
