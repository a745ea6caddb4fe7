// Regression: the sample pocket (60 × 40 × 10 mm, R_c 8, Ø10) left up to 6.5 mm of material in its
// corners for the wall pass, which met 144° of it — more than the sample model can hold at 300 N even
// at the machine's minimum feed (about 71° at 10 mm depth). The corner clean-up and the semi-finishing
// contour bound every pass at the pocket depth; the finished outline is still exactly the spec's.
//
// Oracles: the product's exact engagement (geometry::compute_engagement) against the closed-form
// internal-arc engagement (circle–circle intersection, docs/method.md §5.1) on the wall pass's corner
// arcs and the corner loops; the stock after cutting (geometry::after_cutting) probed on both sides of
// the spec's rounded rectangle.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "feedplan/core/angle.hpp"
#include "feedplan/cycles/pocket.hpp"
#include "feedplan/geometry/analytic_engagement.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "path_checks.hpp"

namespace feedplan::cycles {
namespace {

using testing::moves_of;

const geometry::Tool kTool{"D10", 10.0, 4, 30.0};
constexpr double kToolRadiusMm = 5.0;
// The bound: the clean-up is laid out for 55° with the steady (closed-form) engagement; the exact
// engagement adds little where a pass enters its material. 60° stays clear of the 71° at which the
// sample model predicts 300 N at the minimum feed with 10 mm depth.
constexpr double kBoundDeg = 60.0;

PocketSpec sample_pocket(Direction direction = Direction::kCcw) {
  PocketSpec spec;
  spec.center = {0, 0};
  spec.width_mm = 60;
  spec.height_mm = 40;
  spec.depth_mm = 10;
  spec.corner_radius_mm = 8;
  spec.direction = direction;
  return spec;
}

std::string sub_cycle(const std::string& part) { return part.substr(0, part.find(':')); }

// Largest engagement per sub-cycle over the samples at the pocket's depth (the helix turns of the
// bore cut one pitch deep and are planned for that depth).
std::map<std::string, double> largest_engagement_deg(const Cycle& cycle, const geometry::EngagementProfile& profile) {
  std::map<std::string, double> largest;
  for (const auto& s : profile.samples) {
    const auto& move = cycle.path.moves[static_cast<std::size_t>(s.move_index)];
    if (move.axial_depth_mm < 10.0 - 1e-9) continue;
    double& worst = largest[sub_cycle(profile.part_names[static_cast<std::size_t>(s.part)])];
    worst = std::max(worst, rad_to_deg(s.engagement_rad));
  }
  return largest;
}

TEST(PocketCornerEngagement, EveryPassAtFullDepthStaysBelowTheBound) {
  for (const Direction direction : {Direction::kCcw, Direction::kCw}) {
    const Cycle cycle = generate_pocket(sample_pocket(direction), kTool);
    const auto profile = geometry::compute_engagement(cycle.path, cycle.stock, kToolRadiusMm, {.ds_mm = 0.05});
    EXPECT_TRUE(profile.warnings.empty()) << profile.warnings.front();
    const auto largest = largest_engagement_deg(cycle, profile);
    for (const auto& [name, deg] : largest) {
      std::printf("%s: largest engagement %.2f deg\n", name.c_str(), deg);
      EXPECT_LT(deg, kBoundDeg) << name;
    }
    // The passes that took the corners before are all there.
    for (const char* name : {"corner 1", "corner 2", "corner 3", "corner 4", "semi-finish 1", "walls"}) {
      EXPECT_EQ(largest.count(name), 1u) << name;
    }
  }
}

// The wall pass's corner arc (radius ρ = R_c − r = 3 about the corner centre) meets the ring the corner
// loops left: the loops, of radius R_t about the corner centre, cut to R_t + r, so the radial depth is
// R_d = R_c − (R_t + r), and the steady engagement is the internal-arc form for R = R_c.
TEST(PocketCornerEngagement, WallPassCornerArcsMatchTheInternalArcForm) {
  const PocketSpec spec = sample_pocket();
  const Cycle cycle = generate_pocket(spec, kTool);
  const auto profile = geometry::compute_engagement(cycle.path, cycle.stock, kToolRadiusMm, {.ds_mm = 0.02});
  for (int corner = 1; corner <= 4; ++corner) {
    const std::string loops = "corner " + std::to_string(corner) + ": ";
    // The last loop of the corner trochoid: a full circle about the corner centre.
    double loop_radius = -1;
    geometry::Point2 loop_centre{};
    for (const auto& m : cycle.path.moves) {
      if (cycle.path.part_names[m.part].rfind(loops + "loop", 0) == 0 && m.kind == geometry::MoveKind::kArc) {
        loop_radius = geometry::arc_radius_mm(m);
        loop_centre = m.center;
      }
    }
    ASSERT_GT(loop_radius, 0) << loops;
    const auto& arc = cycle.path.moves[moves_of(cycle.path, "walls: corner " + std::to_string(corner)).at(0)];
    EXPECT_NEAR(loop_centre.x_mm, arc.center.x_mm, 1e-9);
    EXPECT_NEAR(loop_centre.y_mm, arc.center.y_mm, 1e-9);
    const double radial_depth = spec.corner_radius_mm - (loop_radius + kToolRadiusMm);
    const double expected_deg =
        rad_to_deg(geometry::internal_arc_engagement_rad(kToolRadiusMm, spec.corner_radius_mm, radial_depth));
    // The middle third of the arc is steady: the ring ahead and behind is the same.
    const int arc_index = static_cast<int>(moves_of(cycle.path, "walls: corner " + std::to_string(corner)).at(0));
    std::vector<double> steady;
    for (const auto& s : profile.samples) {
      if (s.move_index != arc_index) continue;
      steady.push_back(rad_to_deg(s.engagement_rad));
    }
    ASSERT_GT(steady.size(), 30u);
    const std::size_t third = steady.size() / 3;
    for (std::size_t i = third; i < 2 * third; ++i) EXPECT_NEAR(steady[i], expected_deg, 0.05) << loops << i;
    EXPECT_LT(expected_deg, 56.0);
  }
}

// Whether a removed move's swept region can reach within `margin_mm` of (x, y): its XY bounding box
// (the whole circle for arcs) grown by the tool radius.
bool may_reach(const geometry::SweptMove& swept, double x_mm, double y_mm, double margin_mm) {
  const auto& m = swept.move;
  double lo_x = std::min(m.start.x_mm, m.end.x_mm), hi_x = std::max(m.start.x_mm, m.end.x_mm);
  double lo_y = std::min(m.start.y_mm, m.end.y_mm), hi_y = std::max(m.start.y_mm, m.end.y_mm);
  if (m.kind == geometry::MoveKind::kArc) {
    const double radius = geometry::arc_radius_mm(m);
    lo_x = m.center.x_mm - radius, hi_x = m.center.x_mm + radius;
    lo_y = m.center.y_mm - radius, hi_y = m.center.y_mm + radius;
  }
  const double grow = swept.tool_radius_mm + margin_mm;
  return x_mm >= lo_x - grow && x_mm <= hi_x + grow && y_mm >= lo_y - grow && y_mm <= hi_y + grow;
}

constexpr double kProbeRadiusMm = 0.5;

// Engaged angle of a probe tool of radius 0.5 mm centred at (x, y), on the layers from 5 mm above the
// pocket floor up: 0 where the disc holds no material, 2π where it is all material. Only the removed
// moves that can reach the probe are kept (speed; the others cannot change the answer).
double material_angle_rad(const geometry::Stock& stock, double x_mm, double y_mm) {
  geometry::Stock near = stock;
  near.removed.clear();
  for (const auto& swept : stock.removed) {
    if (may_reach(swept, x_mm, y_mm, 2 * kProbeRadiusMm)) near.removed.push_back(swept);
  }
  geometry::ToolPath probe;
  probe.part_names = {"probe"};
  geometry::Move m;
  m.kind = geometry::MoveKind::kLine;
  m.start = {x_mm, y_mm, -5.0};
  m.end = {x_mm + 1e-4, y_mm, -5.0};
  m.cutting = true;
  m.axial_depth_mm = 1.0;
  probe.moves.push_back(m);
  const auto profile = geometry::compute_engagement(probe, near, kProbeRadiusMm, {.ds_mm = 1.0});
  return profile.samples.front().engagement_rad;
}

// Point on the spec's rounded rectangle at parameter u ∈ [0, 1) along its outline, and its outward
// normal.
struct OutlinePoint {
  double x, y, nx, ny;
};
OutlinePoint outline_point(const PocketSpec& spec, double u) {
  const double rc = spec.corner_radius_mm;
  const double qx = 0.5 * spec.width_mm - rc, qy = 0.5 * spec.height_mm - rc;
  // Quarter outline: the right wall from y = 0 up to qy, the corner arc, the top wall back to x = 0.
  const double lengths[3] = {qy, 0.5 * kPi * rc, qx};
  const double quarter = lengths[0] + lengths[1] + lengths[2];
  const int q = static_cast<int>(u * 4);
  double t = (u * 4 - q) * quarter;
  OutlinePoint p{};
  if (t < lengths[0]) {
    p = {qx + rc, t, 1, 0};
  } else if ((t -= lengths[0]) < lengths[1]) {
    const double a = t / rc;
    p = {qx + rc * std::cos(a), qy + rc * std::sin(a), std::cos(a), std::sin(a)};
  } else {
    t -= lengths[1];
    p = {qx - t, qy + rc, 0, 1};
  }
  // Quarters 1–3 by symmetry: mirror in y, then x.
  if (q == 1 || q == 2) p = {-p.x, p.y, -p.nx, p.ny};
  if (q == 2 || q == 3) p = {p.x, -p.y, p.nx, -p.ny};
  return {spec.center.x_mm + p.x, spec.center.y_mm + p.y, p.nx, p.ny};
}

// Probe discs of radius ρ = 0.5 mm kept δ = 0.02 mm off the outline on either side: inside, none of
// the disc may hold material (nothing left); outside, all of it must (nothing overcut).
TEST(PocketCornerEngagement, TheFinishedOutlineIsExactlyTheSpecsRoundedRectangle) {
  constexpr double kToleranceMm = 0.02;
  constexpr double kOffsetMm = kToleranceMm + kProbeRadiusMm;
  for (const PocketSpec& spec : {sample_pocket(), sample_pocket(Direction::kCw)}) {
    const Cycle cycle = generate_pocket(spec, kTool);
    const geometry::Stock after = geometry::after_cutting(cycle.stock, cycle.path, kToolRadiusMm);
    constexpr int kProbes = 200;
    for (int i = 0; i < kProbes; ++i) {
      const OutlinePoint p = outline_point(spec, (i + 0.5) / kProbes);
      EXPECT_EQ(material_angle_rad(after, p.x - kOffsetMm * p.nx, p.y - kOffsetMm * p.ny), 0.0)
          << "material left near " << p.x << ", " << p.y;
      EXPECT_NEAR(material_angle_rad(after, p.x + kOffsetMm * p.nx, p.y + kOffsetMm * p.ny), kTwoPi, 1e-9)
          << "overcut near " << p.x << ", " << p.y;
    }
    // And nothing is left anywhere inside: a grid over the pocket, the probes kept off the outline.
    for (double x = -28.0; x <= 28.0; x += 2.0) {
      for (double y = -18.0; y <= 18.0; y += 2.0) {
        const double dx = std::max(std::abs(x) - 22.0, 0.0), dy = std::max(std::abs(y) - 12.0, 0.0);
        if (std::hypot(dx, dy) > 8.0 - kOffsetMm) continue;
        EXPECT_EQ(material_angle_rad(after, x, y), 0.0) << x << ", " << y;
      }
    }
  }
}

}  // namespace
}  // namespace feedplan::cycles
