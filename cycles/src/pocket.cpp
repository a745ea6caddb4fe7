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
#include "pocket_corner_clean_up.hpp"
#include "pocket_wall_stock.hpp"
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
// Largest engagement the corner clean-up, the semi-finishing contours and the wall pass are laid out
// for (docs/method.md §5.1 forms). The roughing of the sample pocket already runs at up to 56° (the
// spiral's first turn); the sample model (S50C, Ø10, 10 mm deep) holds 300 N at the machine's minimum
// feed up to about 71°, so 55° leaves the planner room to feed above its minimum.
constexpr double kMaxEngagementRad = deg_to_rad(55.0);
// Smallest corner radius of a semi-finishing contour's tool-centre path, per tool radius, where the
// concentric one (R_c − r − offset) would be smaller or vanish.
constexpr double kMinContourCornerPerRadius = 0.1;

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
  detail::CornerCleanUp clean_up;      // corner trochoids before the wall passes
  double thickest_wall_stock = 0;      // on the walls after roughing and clean-up
  std::vector<double> contour_offsets; // semi-finishing contours, allowance left on the walls, outermost first
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

// The corner centres Q_i and slot end centres O_i in the canonical frame of the wall pass (a along
// the long axis, b along its normal), in the wall pass's corner order.
struct CornerPoint {
  double a, b;
};
std::vector<CornerPoint> corner_centres(const PocketSpec& spec, const PocketPlan& p) {
  const double qa = 0.5 * p.long_side - spec.corner_radius_mm, qb = 0.5 * p.short_side - spec.corner_radius_mm;
  return {{qa, -qb}, {qa, qb}, {-qa, qb}, {-qa, -qb}};
}
std::vector<CornerPoint> slot_ends(const PocketPlan& p) {
  return {{p.slot_length, 0}, {p.slot_length, 0}, {-p.slot_length, 0}, {-p.slot_length, 0}};
}

// The corner clean-up (pocket_corner_clean_up.hpp), canonical frame; and the semi-finishing contours
// that bring the thickest wall stock down to the allowance a in steps of at most r(1 − cos α_max)
// (docs/method.md §5.1, straight cut).
void plan_finishing(const PocketSpec& spec, PocketPlan& p) {
  std::vector<Point2> corners, ends;
  for (const auto& q : corner_centres(spec, p)) corners.push_back({q.a, q.b});
  for (const auto& o : slot_ends(p)) ends.push_back({o.a, o.b});
  p.clean_up = detail::plan_corner_clean_up(corners, ends, p.rough_radius, spec.corner_radius_mm, p.r, p.trochoid_pitch,
                                            kMaxEngagementRad);
  detail::QuarterPocket quarter{0.5 * p.long_side, 0.5 * p.short_side, spec.corner_radius_mm, p.slot_length,
                                p.rough_radius};
  // All four corners are alike (symmetric about both axes): corner 2 is the quarter's.
  for (const auto& t : p.clean_up.trochoids) {
    if (t.end.x_mm > 0 && t.end.y_mm > 0) {
      quarter.clean_up_start_x_mm = t.start.x_mm;
      quarter.clean_up_start_y_mm = t.start.y_mm;
      quarter.clean_up_reach_mm = p.clean_up.reach_mm;
    }
  }
  p.thickest_wall_stock = detail::thickest_wall_stock_mm(quarter);
  const double step_max = p.r * (1.0 - std::cos(kMaxEngagementRad));
  if (p.thickest_wall_stock > p.allowance + 1e-6) {
    const int n = static_cast<int>(std::ceil((p.thickest_wall_stock - p.allowance) / step_max - 1e-9));
    const double step = (p.thickest_wall_stock - p.allowance) / n;
    for (int k = n - 1; k >= 0; --k) {
      const double offset = p.allowance + k * step;
      // A contour needs room inside the pocket: its tool centre at least ρ_min from the centre line.
      if (0.5 * p.short_side - p.r - offset >= kMinContourCornerPerRadius * p.r) p.contour_offsets.push_back(offset);
    }
  }
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

// A contour's canonical coordinates: a along the long axis, b along its left normal, mirrored for
// kCw; positions at the cutting depth z_c. The contour runs `offset` inside the finished walls (tool
// centre r + offset from them) with corner arcs of radius `corner` (the wall pass: offset 0,
// corner R_c − r).
struct WallFrame {
  WallFrame(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z, double offset, double corner)
      : c(spec.center),
        ex(p.ex),
        ey(p.ey),
        sign(spec.direction == Direction::kCcw ? 1.0 : -1.0),
        z_cut(z.top_z_mm - spec.depth_mm),
        hx(0.5 * p.long_side - p.r - offset),
        hy(0.5 * p.short_side - p.r - offset),
        sx(hx - corner),
        sy(hy - corner) {}
  WallFrame(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z)
      : WallFrame(spec, p, z, 0.0, spec.corner_radius_mm - p.r) {}
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
  double hx, hy;     // half sizes of the tool-centre contour
  double sx, sy;     // corner centres of the contour
};

// Motion step 4: the corner clean-up, one trochoid per corner that needs one, in the wall pass's
// corner order (pocket_corner_clean_up.hpp).
void clean_corners(const PocketSpec& spec, const PocketPlan& p, const geometry::Tool& tool, const ZLevels& z,
                   Cycle& cycle) {
  const WallFrame w(spec, p, z);
  const auto corners = corner_centres(spec, p);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    for (const auto& t : p.clean_up.trochoids) {
      if (std::abs(t.end.x_mm - corners[i].a) > 1e-12 || std::abs(t.end.y_mm - corners[i].b) > 1e-12) continue;
      const Cycle trochoid = generate_trochoid({w.xy(t.start.x_mm, t.start.y_mm), w.xy(t.end.x_mm, t.end.y_mm),
                                                p.clean_up.loop_radius_mm, p.clean_up.pitch_mm, spec.direction},
                                               tool, spec.depth_mm, z);
      append_sub_cycle(cycle, trochoid, "corner " + std::to_string(i + 1) + ": ");
    }
  }
  if (!p.clean_up.trochoids.empty()) {
    cycle.notes.push_back("corners: trochoids of loop radius " + six_digit_number_text(p.clean_up.loop_radius_mm) +
                          " mm leave " + six_digit_number_text(spec.corner_radius_mm - p.clean_up.reach_mm) +
                          " mm in the corners for the wall pass");
  }
}

// Down at C to z_c, then the lead-in: the semicircle with diameter C–E, tangent to wall 1 at E. The
// tool stays inside the roughed disc of radius R_s about C while its centre is within R_s − r of C,
// i.e. for the first ψ_t = 2·asin((R_s − r) / hy) of the sweep (all of it when the contour lies
// inside that disc).
void enter_walls(detail::PathBuilder& b, const WallFrame& w, const PocketPlan& p, const ZLevels& z, double depth) {
  const double hy = w.hy;
  b.begin_part("entry");
  b.enter(w.c, z, w.z_cut);
  const double lead_radius = 0.5 * hy;
  const Point2 lead_center = w.xy(0, -lead_radius);
  const double air_sweep = 2.0 * std::asin(std::min((p.rough_radius - p.r) / hy, 1.0));
  const double touch_angle = 0.5 * kPi + air_sweep;
  b.arc_to(w.at(lead_radius * std::cos(touch_angle), -lead_radius + lead_radius * std::sin(touch_angle)), lead_center,
           w.ccw(), air_sweep, false, 0);
  if (kPi - air_sweep > 1e-12) {
    b.begin_part("lead-in");
    b.arc_to(w.at(0, -hy), lead_center, w.ccw(), kPi - air_sweep, true, depth);
  }
}

// From E along wall 1, the corners and the other walls, and back to E.
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

// Back to C in air, up to the clearance height.
void leave_walls(detail::PathBuilder& b, const WallFrame& w, const ZLevels& z) {
  b.begin_part("exit");
  b.line_to(w.at(0, 0), false, 0);
  b.retract(z);
}

// One closed contour `offset` inside the finished walls, entered and left as the wall pass is.
geometry::ToolPath contour(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z, const WallFrame& w) {
  detail::PathBuilder b({});
  enter_walls(b, w, p, z, spec.depth_mm);
  follow_walls(b, w, spec.depth_mm);
  leave_walls(b, w, z);
  return b.finish();
}

// Motion step 5: the semi-finishing contours, outermost first, each leaving its offset on the walls;
// corner arcs concentric with the finished corners where they can be (radius R_c − r − offset), else
// of radius ρ_min, which cuts no deeper into the corner (its centre lies farther from the walls).
void semi_finish_walls(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z, Cycle& cycle) {
  for (std::size_t k = 0; k < p.contour_offsets.size(); ++k) {
    const double offset = p.contour_offsets[k];
    const double hy = 0.5 * p.short_side - p.r - offset;
    const double corner =
        std::min(std::max(spec.corner_radius_mm - p.r - offset, kMinContourCornerPerRadius * p.r), hy);
    const WallFrame w(spec, p, z, offset, corner);
    detail::append(cycle.path, contour(spec, p, z, w), "semi-finish " + std::to_string(k + 1) + ": ");
  }
  if (!p.contour_offsets.empty()) {
    cycle.notes.push_back("walls: the roughing and the corner clean-up leave up to " +
                          six_digit_number_text(p.thickest_wall_stock) + " mm on the walls; " +
                          std::to_string(p.contour_offsets.size()) + " semi-finishing contour(s) bring it to " +
                          six_digit_number_text(p.allowance) + " mm");
  }
}

// Motion step 6: the wall pass.
void finish_walls(const PocketSpec& spec, const PocketPlan& p, const ZLevels& z, Cycle& cycle) {
  detail::append(cycle.path, contour(spec, p, z, WallFrame(spec, p, z)), "walls: ");
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
  PocketPlan p = plan_of(spec, tool);
  plan_finishing(spec, p);
  Cycle cycle;
  cycle.tool = tool;
  bore_centre(spec, p, tool, z, cycle);
  if (p.spiral) expand_bore(spec, p, tool, z, cycle);
  if (p.slot_length > 1e-9) cut_slots(spec, p, tool, z, cycle);
  clean_corners(spec, p, tool, z, cycle);
  semi_finish_walls(spec, p, z, cycle);
  finish_walls(spec, p, z, cycle);
  cycle.stock = pocket_stock(spec, p, z);
  return cycle;
}

}  // namespace feedplan::cycles
