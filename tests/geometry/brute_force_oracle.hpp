#pragma once
// Brute-force engagement oracle for tests, written independently of the library's kernels: it
// samples the tool circle densely and asks, for each point, the defining question of docs/method.md
// §5.2 — inside the initial stock, and farther than the sweep radius from every earlier tool
// position at or below the evaluation height? Transitions between engaged and free points are then
// refined by bisection. Distances to earlier moves are point-to-segment and point-to-arc; a move
// whose z changes (a helix) counts only over the fraction whose tip is at or below the height.
// Besides the engaged arcs, it answers what the planner's tests need of a place on a program: the chip
// factor of the arcs, the height of material in contact above the tip (by bisection over heights), and
// whether a point of the tool's disc was material before the move began (a rapid's or a plunge's bottom).

#include <algorithm>
#include <cassert>
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

// Distance from q to the contour's boundary.
inline double dist_to_boundary(const Contour& c, XY q) {
  if (c.is_circle()) return std::abs(std::hypot(q.x - c.center.x_mm, q.y - c.center.y_mm) - c.radius_mm);
  double best = 1e300;
  const auto& v = c.vertices;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % v.size()];
    const double dx = b.x_mm - a.x_mm, dy = b.y_mm - a.y_mm;
    const double l2 = dx * dx + dy * dy;
    const double t = l2 > 0 ? std::clamp(((q.x - a.x_mm) * dx + (q.y - a.y_mm) * dy) / l2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(q.x - a.x_mm - t * dx, q.y - a.y_mm - t * dy));
  }
  return best;
}

// In the initial stock and at least depth_mm inside its XY boundary (outer contour and holes).
inline bool deep_in_initial_stock(const Stock& stock, XY q, double height_mm, double depth_mm) {
  if (!in_initial_stock(stock, q, height_mm)) return false;
  for (const auto& region : stock.regions) {
    if (!in_contour(region.outer, q)) continue;
    if (dist_to_boundary(region.outer, q) < depth_mm) return false;
    for (const auto& hole : region.holes) {
      if (dist_to_boundary(hole, q) < depth_mm) return false;
    }
  }
  return true;
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
  // Of the active part (set by clip): its end points and, on arcs, the circle radius and start angle.
  XY a{}, b{};
  double rho = 0.0, a0 = 0.0;
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

// The end points (and arc circle) of the active part, for dist_to.
inline void cache_active_part(Earlier& e) {
  const Point3 a = point_at(e.move, e.from);
  const Point3 b = point_at(e.move, e.upto);
  e.a = {a.x_mm, a.y_mm};
  e.b = {b.x_mm, b.y_mm};
  if (e.move.kind != MoveKind::kArc) return;
  e.rho = std::hypot(a.x_mm - e.move.center.x_mm, a.y_mm - e.move.center.y_mm);
  e.a0 = std::atan2(a.y_mm - e.move.center.y_mm, a.x_mm - e.move.center.x_mm);
}

// Keeps the part of the travelled move whose tip z (linear along the move) is at or below height_mm.
inline void clip(Earlier& e, double height_mm) {
  const double z0 = e.move.start.z_mm;
  const double z1 = point_at(e.move, e.travelled).z_mm;
  const double h = height_mm + 1e-9;
  e.active = true;
  e.from = 0.0;
  e.upto = e.travelled;
  if (z0 > h && z1 > h) {
    e.active = false;
    return;
  }
  if (!(z0 <= h && z1 <= h)) {
    const double t = e.travelled * (height_mm - z0) / (z1 - z0);
    if (z0 <= h) e.upto = t; else e.from = t;
  }
  cache_active_part(e);
}

// Distance in XY from q to the active part of the move.
inline double dist_to(const Earlier& e, XY q) {
  if (!e.active) return 1e300;
  const XY a = e.a;
  const XY b = e.b;
  if (e.move.kind != MoveKind::kArc) return dist_segment(q, a, b);
  // Arc: radial distance if q's angle is within the active sweep, else the nearer end point.
  const double cx = e.move.center.x_mm, cy = e.move.center.y_mm;
  const double rho = e.rho;
  const double a0 = e.a0;
  const double aq = std::atan2(q.y - cy, q.x - cx);
  double offset = e.move.ccw ? aq - a0 : a0 - aq;
  const double two_pi = 2 * std::numbers::pi;
  offset = std::fmod(offset, two_pi);
  if (offset < 0) offset += two_pi;
  const double sweep = (e.upto - e.from) * e.move.sweep_rad;
  if (offset <= sweep || sweep >= two_pi) return std::abs(std::hypot(q.x - cx, q.y - cy) - rho);
  return std::min(std::hypot(q.x - a.x, q.y - a.y), std::hypot(q.x - b.x, q.y - b.y));
}

//! An engaged arc of the tool circle in world angles (counter-clockwise from +X), begin < end; an arc
//! may run past 2π.
struct Arc {
  double begin_rad = 0.0;
  double end_rad = 0.0;
};

//! The largest cos of a tool point's angle from the feed direction ψ over the arcs, at least 0: the chip
//! factor t_m / f_z of docs/method.md §5.1, in closed form over each arc (1 where an arc holds ψ, else the
//! nearer end).
inline double chip_factor(const std::vector<Arc>& arcs, double feed_direction_rad) {
  const double two_pi = 2 * std::numbers::pi;
  double best = 0.0;
  for (const Arc& a : arcs) {
    double psi = std::fmod(feed_direction_rad - a.begin_rad, two_pi);
    if (psi < 0) psi += two_pi;
    if (psi <= a.end_rad - a.begin_rad) return 1.0;
    best = std::max({best, std::cos(a.begin_rad - feed_direction_rad), std::cos(a.end_rad - feed_direction_rad)});
  }
  return best;
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
    double total = 0.0;
    for (const Arc& a : engaged_arcs(move_index, f, samples_per_turn)) total += a.end_rad - a.begin_rad;
    return total;
  }

  //! The engaged arcs of the tool circle at the given place (on the layer prepare() chooses): the circle
  //! sampled at `samples_per_turn` angles, each boundary between an engaged and a free sample refined by
  //! bisection. Arcs narrower than one step between two free samples are not seen.
  std::vector<Arc> engaged_arcs(std::size_t move_index, double f, int samples_per_turn = 3600) {
    prepare(move_index, f);
    const double two_pi = 2 * std::numbers::pi;
    const double step = two_pi / samples_per_turn;
    std::vector<char> state(samples_per_turn);
    int free_index = -1;
    for (int i = 0; i < samples_per_turn; ++i) {
      state[i] = engaged(step * i);
      if (!state[i]) free_index = i;
    }
    if (free_index < 0) return {Arc{0.0, two_pi}};
    // Walk once around from a free sample, so that no arc is split at the start.
    std::vector<Arc> arcs;
    for (int k = 1; k <= samples_per_turn; ++k) {
      const int i = (free_index + k) % samples_per_turn;
      if (!state[i] || state[(i + samples_per_turn - 1) % samples_per_turn]) continue;
      int last = k;
      while (state[(free_index + last + 1) % samples_per_turn]) ++last;
      const double a = step * (free_index + k);
      const double b = step * (free_index + last);
      arcs.push_back({refine(a - step, a), refine(b, b + step)});
      k = last;
    }
    return arcs;
  }

  //! Whether the tool-circle point at world angle θ is engaged (after prepare or engagement_rad).
  bool engaged(double theta) const {
    const XY q{p_.x + r_ * std::cos(theta), p_.y + r_ * std::sin(theta)};
    if (!in_initial_stock(stock_, q, height_)) return false;
    // The tool circle itself is at exactly the sweep radius from the current position: only points
    // clearly inside an earlier sweep are free.
    for (std::size_t i : candidates_) {
      if (inside_sweep(moves_[i], q)) return false;
    }
    return !inside_sweep(current_, q);
  }

  //! Whether the tool-circle point at world angle θ is engaged with material at least `depth_mm` deep: at
  //! least that far inside the initial stock's boundary and farther than the sweep radius + depth_mm from
  //! every earlier move. The current move's own sweep is not widened (its circle is the tool's).
  //! Tangent contact (the tool where an earlier move already was, material exactly at its circle) is not.
  bool engaged_deeper_than(double theta, double depth_mm) const {
    assert(depth_mm <= 0.01);
    const XY q{p_.x + r_ * std::cos(theta), p_.y + r_ * std::sin(theta)};
    if (!deep_in_initial_stock(stock_, q, height_, depth_mm)) return false;
    for (std::size_t i : candidates_) {
      if (dist_to(moves_[i], q) < moves_[i].sweep_radius_mm + depth_mm) return false;
    }
    return !inside_sweep(current_, q);
  }

  //! Whether the point q (XY, at the current height) was material before the current move began: in the
  //! initial stock and outside every earlier sweep at or below the height; the current move itself is
  //! not counted (after prepare; q within the tool's reach of the current position).
  bool material_before_move(XY q) const {
    if (!in_initial_stock(stock_, q, height_)) return false;
    for (std::size_t i : candidates_) {
      if (inside_sweep(moves_[i], q)) return false;
    }
    return true;
  }

  //! Places the tool at fraction `f` of move `move_index` and evaluates on the lowest layer, just above
  //! the tip (or height_above_tip_mm_ above it).
  void prepare(std::size_t move_index, double f) {
    const Move& move = path_.moves[move_index];
    const Point3 pos = point_at(move, f);
    p_ = {pos.x_mm, pos.y_mm};
    tip_z_ = pos.z_mm;
    move_index_ = move_index;
    current_ = make_earlier(move, f, r_);
    // Earlier moves that can reach the tool's disc at all (their XY box, widened by their sweep radius,
    // meets the disc's box): the only ones any point of the disc or circle is compared with.
    candidates_.clear();
    for (std::size_t i = 0; i < first_path_move_ + move_index_; ++i) {
      const Earlier& e = moves_[i];
      const double reach = e.sweep_radius_mm + r_ + 0.01;  // 0.01: the most engaged_deeper_than widens sweeps by
      if (p_.x < e.lo_x - reach || p_.x > e.hi_x + reach || p_.y < e.lo_y - reach || p_.y > e.hi_y + reach) continue;
      candidates_.push_back(i);
    }
    // The lowest layer, just above the tip: what compute_engagement reports as the sample's engagement
    // (every higher layer's engaged set lies inside it).
    set_height(height_above_tip_mm_ ? pos.z_mm + *height_above_tip_mm_ : pos.z_mm + 1e-6);
  }

  //! Evaluates at the absolute height `height_mm` from now on (after prepare).
  void set_height(double height_mm) {
    height_ = height_mm;
    clip(current_, height_);
    for (std::size_t i : candidates_) clip(moves_[i], height_);
  }

  //! The height of material in contact above the tip (after engaged_arcs at the lowest layer, whose arcs
  //! `lowest` are): the highest height up to the stock top at which a point of those arcs is still
  //! engaged (the engaged set only shrinks upwards), by bisection to `resolution_mm`, minus the tip;
  //! points every `step_rad` inside the arcs are tried (a sliver narrower than that is missed, so the
  //! height errs low). Leaves the oracle on the lowest layer again.
  double material_height_mm(const std::vector<Arc>& lowest, double step_rad, double resolution_mm) {
    if (lowest.empty()) return 0.0;
    const double lowest_height = height_;
    const auto any_engaged = [&](double h) {
      set_height(h);
      for (const Arc& a : lowest) {
        const double width = a.end_rad - a.begin_rad;
        const int n = std::max(1, static_cast<int>(std::ceil(width / step_rad)));
        for (int j = 0; j < n; ++j) {
          if (engaged(a.begin_rad + width * (j + 0.5) / n)) return true;
        }
      }
      return false;
    };
    double lo = lowest_height;
    double hi = stock_.z_top_mm;
    double found = lo;
    if (hi > lo && any_engaged(hi - 1e-9)) {
      found = hi;
    } else {
      while (hi - lo > resolution_mm) {
        const double mid = 0.5 * (lo + hi);
        (any_engaged(mid) ? lo : hi) = mid;
      }
      found = lo;
    }
    set_height(lowest_height);
    return std::max(0.0, found - tip_z_);
  }

  //! Tool tip height at the current place, mm.
  double tip_z_mm() const { return tip_z_; }
  //! Tool centre at the current place (XY), mm.
  XY centre() const { return p_; }

 private:
  // Whether q lies clearly inside the sweep of the active part of e (its box first).
  static bool inside_sweep(const Earlier& e, XY q) {
    if (q.x < e.lo_x - e.sweep_radius_mm || q.x > e.hi_x + e.sweep_radius_mm || q.y < e.lo_y - e.sweep_radius_mm ||
        q.y > e.hi_y + e.sweep_radius_mm) {
      return false;
    }
    return dist_to(e, q) < e.sweep_radius_mm - 1e-9;
  }

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
  std::vector<std::size_t> candidates_;
  Earlier current_;
  XY p_{};
  double tip_z_ = 0;
  double height_ = 0;

 public:
  //! Evaluate at this height above the tip instead of the lowest layer (unset: the lowest layer).
  std::optional<double> height_above_tip_mm_;
};

}  // namespace feedplan::geometry::oracle
