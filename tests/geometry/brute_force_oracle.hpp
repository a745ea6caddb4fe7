#pragma once
// Brute-force engagement oracle for tests, written independently of the library's kernels: it
// samples the tool circle densely and asks, for each point, the defining question of docs/method.md
// §5.2 — inside the initial stock, and farther than the sweep radius from every earlier tool
// position at or below the evaluation height? Transitions between engaged and free points are then
// refined by bisection. Distances to earlier moves are point-to-segment and point-to-arc; a move
// whose z changes (a helix) counts only over the fraction whose tip is at or below the height.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::geometry::oracle {

struct XY {
  double x, y;
};

inline bool in_contour(const Contour& c, XY q) {
  if (c.is_circle()) return std::hypot(q.x - c.center.x_mm, q.y - c.center.y_mm) < c.radius_mm;
  int winding = 0;
  const auto& v = c.vertices;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % v.size()];
    const double side = (b.x_mm - a.x_mm) * (q.y - a.y_mm) - (q.x - a.x_mm) * (b.y_mm - a.y_mm);
    if (a.y_mm <= q.y) {
      if (b.y_mm > q.y && side > 0) ++winding;
    } else if (b.y_mm <= q.y && side < 0) {
      --winding;
    }
  }
  return winding != 0;
}

inline bool in_initial_stock(const Stock& stock, XY q, double height_mm) {
  if (height_mm < stock.z_bottom_mm || height_mm > stock.z_top_mm) return false;
  for (const auto& region : stock.regions) {
    if (!in_contour(region.outer, q)) continue;
    bool in_hole = false;
    for (const auto& hole : region.holes) in_hole = in_hole || in_contour(hole, q);
    if (!in_hole) return true;
  }
  return false;
}

// An earlier tool-centre move (or the part of the current one travelled so far) as the oracle sees
// it: the fractions [from, upto] of the move whose tool tip is at or below the evaluation height.
struct Earlier {
  Move move;
  double travelled = 1.0;         // fraction of the move that was travelled
  double sweep_radius_mm = 0.0;
  double lo_x = 0, lo_y = 0, hi_x = 0, hi_y = 0;  // XY bounding box of the whole move
  double from = 0.0, upto = 1.0;  // part below the height (set by clip)
  bool active = true;
};

inline double dist_segment(XY q, XY a, XY b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((q.x - a.x) * dx + (q.y - a.y) * dy) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(q.x - a.x - t * dx, q.y - a.y - t * dy);
}

inline Earlier make_earlier(const Move& m, double travelled, double radius) {
  Earlier e{m, travelled, radius, 1e300, 1e300, -1e300, -1e300, 0.0, travelled, true};
  const int n = 64;
  for (int i = 0; i <= n; ++i) {
    const Point3 s = point_at(m, travelled * i / n);
    e.lo_x = std::min(e.lo_x, s.x_mm), e.lo_y = std::min(e.lo_y, s.y_mm);
    e.hi_x = std::max(e.hi_x, s.x_mm), e.hi_y = std::max(e.hi_y, s.y_mm);
  }
  // Arcs bulge up to the sagitta of one 1/64 step beyond the sampled points.
  const double bulge = m.kind == MoveKind::kArc ? arc_radius_mm(m) * (1 - std::cos(m.sweep_rad * travelled / (2 * n))) : 0.0;
  e.lo_x -= bulge, e.lo_y -= bulge, e.hi_x += bulge, e.hi_y += bulge;
  return e;
}

// Keeps the part of the travelled move whose tip z (linear along the move) is at or below height_mm.
inline void clip(Earlier& e, double height_mm) {
  const double z0 = e.move.start.z_mm;
  const double z1 = point_at(e.move, e.travelled).z_mm;
  const double h = height_mm + 1e-9;
  e.active = true;
  e.from = 0.0;
  e.upto = e.travelled;
  if (z0 <= h && z1 <= h) return;
  if (z0 > h && z1 > h) {
    e.active = false;
    return;
  }
  const double t = e.travelled * (height_mm - z0) / (z1 - z0);
  if (z0 <= h) e.upto = t; else e.from = t;
}

// Distance in XY from q to the active part of the move.
inline double dist_to(const Earlier& e, XY q) {
  if (!e.active) return 1e300;
  const Point3 a = point_at(e.move, e.from);
  const Point3 b = point_at(e.move, e.upto);
  if (e.move.kind != MoveKind::kArc) return dist_segment(q, {a.x_mm, a.y_mm}, {b.x_mm, b.y_mm});
  // Arc: radial distance if q's angle is within the active sweep, else the nearer end point.
  const double cx = e.move.center.x_mm, cy = e.move.center.y_mm;
  const double rho = std::hypot(a.x_mm - cx, a.y_mm - cy);
  const double a0 = std::atan2(a.y_mm - cy, a.x_mm - cx);
  const double aq = std::atan2(q.y - cy, q.x - cx);
  double offset = e.move.ccw ? aq - a0 : a0 - aq;
  const double two_pi = 2 * std::numbers::pi;
  offset = std::fmod(offset, two_pi);
  if (offset < 0) offset += two_pi;
  const double sweep = (e.upto - e.from) * e.move.sweep_rad;
  if (offset <= sweep || sweep >= two_pi) return std::abs(std::hypot(q.x - cx, q.y - cy) - rho);
  return std::min(std::hypot(q.x - a.x_mm, q.y - a.y_mm), std::hypot(q.x - b.x_mm, q.y - b.y_mm));
}

//! Engagement oracle at fraction `f` of move `move_index` of `path`.
class EngagementOracle {
 public:
  EngagementOracle(const ToolPath& path, const Stock& stock, double tool_radius_mm)
      : path_(path), stock_(stock), r_(tool_radius_mm) {
    for (const auto& s : stock_.removed) moves_.push_back(make_earlier(s.move, 1.0, s.tool_radius_mm));
    first_path_move_ = moves_.size();
    for (const auto& m : path_.moves) moves_.push_back(make_earlier(m, 1.0, r_));
  }

  //! Total engaged angle (rad) of the tool circle at the given place.
  double engagement_rad(std::size_t move_index, double f, int samples_per_turn = 3600) {
    prepare(move_index, f);
    const double two_pi = 2 * std::numbers::pi;
    const double step = two_pi / samples_per_turn;
    std::vector<char> state(samples_per_turn);
    for (int i = 0; i < samples_per_turn; ++i) state[i] = engaged(step * i);
    double total = 0.0;
    for (int i = 0; i < samples_per_turn; ++i) {
      if (!state[i]) continue;
      const int prev = (i + samples_per_turn - 1) % samples_per_turn;
      const int next = (i + 1) % samples_per_turn;
      const double a = step * i;
      // Each engaged sample stands for half a step either side; where a neighbour is free, the
      // boundary between them is found by bisection instead.
      double contribution = state[prev] ? step / 2 : a - refine(a - step, a);
      contribution += state[next] ? step / 2 : refine(a, a + step) - a;
      total += contribution;
    }
    return total;
  }

  //! Whether the tool-circle point at world angle θ is engaged (after prepare or engagement_rad).
  bool engaged(double theta) const {
    const XY q{p_.x + r_ * std::cos(theta), p_.y + r_ * std::sin(theta)};
    if (!in_initial_stock(stock_, q, height_)) return false;
    auto blocks = [&](const Earlier& e) {
      if (q.x < e.lo_x - e.sweep_radius_mm || q.x > e.hi_x + e.sweep_radius_mm || q.y < e.lo_y - e.sweep_radius_mm ||
          q.y > e.hi_y + e.sweep_radius_mm) {
        return false;
      }
      // The tool circle itself is at exactly the sweep radius from the current position: only
      // points clearly inside an earlier sweep are free.
      return dist_to(e, q) < e.sweep_radius_mm - 1e-9;
    };
    for (std::size_t i = 0; i < first_path_move_ + move_index_; ++i) {
      if (blocks(moves_[i])) return false;
    }
    return !blocks(current_);
  }

  void prepare(std::size_t move_index, double f) {
    const Move& move = path_.moves[move_index];
    const Point3 pos = point_at(move, f);
    p_ = {pos.x_mm, pos.y_mm};
    // The lowest layer, just above the tip: what compute_engagement reports as the sample's engagement
    // (every higher layer's engaged set lies inside it).
    height_ = height_above_tip_mm_ ? pos.z_mm + *height_above_tip_mm_ : pos.z_mm + 1e-6;
    move_index_ = move_index;
    current_ = make_earlier(move, f, r_);
    clip(current_, height_);
    for (std::size_t i = 0; i < first_path_move_ + move_index_; ++i) clip(moves_[i], height_);
  }

 private:
  // Bisection for the boundary between a free angle and an engaged one (either order).
  double refine(double a, double b) const {
    const bool ea = engaged(a);
    for (int k = 0; k < 50; ++k) {
      const double m = 0.5 * (a + b);
      if (engaged(m) == ea) a = m; else b = m;
    }
    return 0.5 * (a + b);
  }

  const ToolPath& path_;
  const Stock& stock_;
  double r_;
  std::vector<Earlier> moves_;
  std::size_t first_path_move_ = 0;
  std::size_t move_index_ = 0;
  Earlier current_;
  XY p_{};
  double height_ = 0;

 public:
  //! Evaluate at this height above the tip instead of the lowest layer (unset: the lowest layer).
  std::optional<double> height_above_tip_mm_;

 private:
};

}  // namespace feedplan::geometry::oracle
