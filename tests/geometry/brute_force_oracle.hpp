#pragma once
// Brute-force engagement oracle for tests, written independently of the library's kernels: it
// samples the tool circle densely and asks, for each point, the defining question of DESIGN.md
// §5.2 — inside the initial stock, and farther than the sweep radius from every earlier tool
// position at or below the evaluation height? Transitions between engaged and free points are then
// refined by bisection. Distances to earlier moves are point-to-segment and point-to-arc in closed
// form for moves at constant z, and to densely sampled points for moves whose z changes.

#include <algorithm>
#include <cmath>
#include <numbers>
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

// An earlier tool-centre path piece (the part of a move up to some fraction), as the oracle sees it.
struct Earlier {
  Move move;
  double upto = 1.0;  // fraction of the move that was travelled
  double sweep_radius_mm = 0.0;
  std::vector<XY> dense;  // for z-varying moves: the points at or below the height
};

inline double dist_segment(XY q, XY a, XY b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double l2 = dx * dx + dy * dy;
  double t = l2 > 0 ? ((q.x - a.x) * dx + (q.y - a.y) * dy) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(q.x - a.x - t * dx, q.y - a.y - t * dy);
}

inline double dist_to(const Earlier& e, XY q) {
  if (!e.dense.empty()) {
    double best = 1e300;
    for (std::size_t i = 0; i + 1 < e.dense.size(); ++i) best = std::min(best, dist_segment(q, e.dense[i], e.dense[i + 1]));
    if (e.dense.size() == 1) best = std::hypot(q.x - e.dense[0].x, q.y - e.dense[0].y);
    return best;
  }
  const Point3 end = point_at(e.move, e.upto);
  if (e.move.kind != MoveKind::kArc) return dist_segment(q, {e.move.start.x_mm, e.move.start.y_mm}, {end.x_mm, end.y_mm});
  // Arc: radial distance if q's angle is within the travelled sweep, else the nearer end point.
  const double cx = e.move.center.x_mm, cy = e.move.center.y_mm;
  const double rho = std::hypot(e.move.start.x_mm - cx, e.move.start.y_mm - cy);
  const double a0 = std::atan2(e.move.start.y_mm - cy, e.move.start.x_mm - cx);
  const double aq = std::atan2(q.y - cy, q.x - cx);
  double offset = e.move.ccw ? aq - a0 : a0 - aq;
  const double two_pi = 2 * std::numbers::pi;
  offset = std::fmod(offset, two_pi);
  if (offset < 0) offset += two_pi;
  const double sweep = e.upto * e.move.sweep_rad;
  if (offset <= sweep || sweep >= two_pi) return std::abs(std::hypot(q.x - cx, q.y - cy) - rho);
  return std::min(std::hypot(q.x - e.move.start.x_mm, q.y - e.move.start.y_mm), std::hypot(q.x - end.x_mm, q.y - end.y_mm));
}

//! Engagement oracle at fraction `f` of move `move_index` of `path`.
class EngagementOracle {
 public:
  EngagementOracle(const ToolPath& path, const Stock& stock, double tool_radius_mm)
      : path_(path), stock_(stock), r_(tool_radius_mm) {}

  //! Total engaged angle (rad) of the tool circle at the given place, and the engaged set as a
  //! predicate for further checks.
  double engagement_rad(std::size_t move_index, double f, int samples_per_turn = 3600) {
    prepare(move_index, f);
    const double two_pi = 2 * std::numbers::pi;
    std::vector<char> state(samples_per_turn);
    for (int i = 0; i < samples_per_turn; ++i) state[i] = engaged(two_pi * i / samples_per_turn);
    double total = 0.0;
    // Each run of engaged samples, with both ends refined by bisection.
    for (int i = 0; i < samples_per_turn; ++i) {
      if (!state[i]) continue;
      const int prev = (i + samples_per_turn - 1) % samples_per_turn;
      const int next = (i + 1) % samples_per_turn;
      const double step = two_pi / samples_per_turn;
      const double a = two_pi * i / samples_per_turn;
      // Each engaged sample stands for half a step either side; where a neighbour is free, the
      // boundary between them is found by bisection instead.
      double contribution = state[prev] ? step / 2 : a - refine(a - step, a);
      contribution += state[next] ? step / 2 : refine(a, a + step) - a;
      total += contribution;
    }
    return total;
  }

  //! Whether the tool-circle point at world angle θ is engaged (call engagement_rad or prepare first).
  bool engaged(double theta) const {
    const XY q{p_.x + r_ * std::cos(theta), p_.y + r_ * std::sin(theta)};
    if (!in_initial_stock(stock_, q, height_)) return false;
    for (const auto& e : earlier_) {
      // The tool circle itself is at exactly the sweep radius from the current position: only points
      // clearly inside an earlier sweep are free.
      if (dist_to(e, q) < e.sweep_radius_mm - 1e-9) return false;
    }
    return true;
  }

  void prepare(std::size_t move_index, double f) {
    const Move& move = path_.moves[move_index];
    const Point3 pos = point_at(move, f);
    p_ = {pos.x_mm, pos.y_mm};
    height_ = pos.z_mm + std::max(0.5 * move.axial_depth_mm, 1e-6);
    earlier_.clear();
    auto add = [&](const Move& m, double upto, double radius) {
      if (upto <= 0) return;
      Earlier e{m, upto, radius, {}};
      if (m.start.z_mm != m.end.z_mm) {
        const double len = length_mm(m) * upto;
        const int n = std::max(2, static_cast<int>(len / 0.01));
        for (int i = 0; i <= n; ++i) {
          const Point3 s = point_at(m, upto * i / n);
          if (s.z_mm <= height_ + 1e-9) e.dense.push_back({s.x_mm, s.y_mm});
        }
        if (e.dense.empty()) return;
      } else if (m.start.z_mm > height_ + 1e-9) {
        return;
      }
      earlier_.push_back(std::move(e));
    };
    for (const auto& s : stock_.removed) add(s.move, 1.0, s.tool_radius_mm);
    for (std::size_t i = 0; i < move_index; ++i) add(path_.moves[i], 1.0, r_);
    add(move, f, r_);
  }

 private:
  // Bisection for the boundary between a free angle and an engaged one (either order).
  double refine(double a, double b) const {
    bool ea = engaged(a);
    for (int k = 0; k < 50; ++k) {
      const double m = 0.5 * (a + b);
      if (engaged(m) == ea) a = m; else b = m;
    }
    return 0.5 * (a + b);
  }

  const ToolPath& path_;
  const Stock& stock_;
  double r_;
  XY p_{};
  double height_ = 0;
  std::vector<Earlier> earlier_;
};

}  // namespace feedplan::geometry::oracle
