#pragma once
// The planned path as a polyline through the plan's samples, with a uniform XY grid of its segments:
// which segments can lie within reach of a point, and where on a segment the point's nearest place is.
// Internal to learning (log alignment by positions).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning::detail {

//! A point's nearest place on a segment.
struct Projection {
  double distance_mm = 0.0;  // from the point, mm
  double s_mm = 0.0;         // arc length of the nearest place, mm
};

//! The path's segments (between neighbouring plan samples) and the grid cells each lies within reach of.
class PathIndex {
 public:
  // Needs a plan with samples (asserted); `reach_mm` is the farthest a point may be from a segment
  // that candidates() lists for it.
  PathIndex(const planner::PlanResult& plan, double reach_mm);

  int segment_count() const { return static_cast<int>(points_.size()) - 1; }
  double s_of_segment_start(int k) const { return s_[static_cast<std::size_t>(k)]; }
  double length_mm() const { return s_.back() - s_.front(); }

  // Nearest point of segment k to q, with the squared distance (z compared only when `use_z`).
  Projection project_squared(int k, double x, double y, double z, bool use_z) const {
    const Segment& g = segments_[static_cast<std::size_t>(k)];
    const double qx = x - g.ax, qy = y - g.ay, qz = use_z ? z - g.az : 0.0;
    const double dz = use_z ? g.dz : 0.0;
    const double inverse = use_z ? g.inverse_length2 : g.inverse_length2_xy;
    const double t = std::clamp((qx * g.dx + qy * g.dy + qz * dz) * inverse, 0.0, 1.0);
    const double ex = qx - t * g.dx, ey = qy - t * g.dy, ez = qz - t * dz;
    const double sa = s_[static_cast<std::size_t>(k)];
    const double sb = s_[static_cast<std::size_t>(k) + 1];
    return {ex * ex + ey * ey + ez * ez, sa + t * (sb - sa)};
  }

  // Nearest point of segment k to q (z compared only when finite).
  Projection project(int k, double x, double y, double z) const {
    Projection p = project_squared(k, x, y, z, std::isfinite(z));
    p.distance_mm = std::sqrt(p.distance_mm);
    return p;
  }

  // Distance from q to the whole path (linear in its length; for messages only).
  double distance_to_path(double x, double y, double z) const {
    double best = 1e300;
    for (int k = 0; k < segment_count(); ++k) best = std::min(best, project(k, x, y, z).distance_mm);
    return best;
  }

  // Segment containing s (the last one starting at or before it).
  int segment_at(double s_mm) const {
    const auto it = std::upper_bound(s_.begin(), s_.end() - 1, s_mm);
    return std::max(0, static_cast<int>(it - s_.begin()) - 1);
  }

  // Every segment within reach of q is in this list (sorted by index), with others near it; empty
  // outside the grid.
  std::span<const int> candidates(double x, double y) const {
    const double fx = (x - x0_) / cell_mm_, fy = (y - y0_) / cell_mm_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx < nx_ && fy < ny_)) return {};
    const std::size_t c = index(static_cast<int>(fx), static_cast<int>(fy));
    return {cell_segments_.data() + cell_start_[c], cell_start_[c + 1] - cell_start_[c]};
  }

 private:
  int cell_x(double x) const { return std::clamp(static_cast<int>((x - x0_) / cell_mm_), 0, nx_ - 1); }
  int cell_y(double y) const { return std::clamp(static_cast<int>((y - y0_) / cell_mm_), 0, ny_ - 1); }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
  }

  // Segment k from points_[k]: its start, its direction (end − start) and 1 / its squared length, in 3D
  // and in XY (0 for a segment of no length, so its start is the nearest place).
  struct Segment {
    double ax, ay, az, dx, dy, dz, inverse_length2, inverse_length2_xy;
  };

  double reach_mm_;
  std::vector<geometry::Point3> points_;
  std::vector<Segment> segments_;
  std::vector<double> s_;
  double x0_ = 0, y0_ = 0, cell_mm_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::size_t> cell_start_;  // per cell, and one past the last
  std::vector<int> cell_segments_;
};

}  // namespace feedplan::learning::detail
