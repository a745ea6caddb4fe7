#include "path_index.hpp"

#include <cassert>

namespace feedplan::learning::detail {

PathIndex::PathIndex(const planner::PlanResult& plan, double reach_mm) : reach_mm_(reach_mm) {
  for (const auto& sample : plan.samples) {
    points_.push_back(sample.position);
    s_.push_back(sample.s_mm);
  }
  assert(!points_.empty());
  if (points_.size() == 1) {  // one point: one segment of length zero
    points_.push_back(points_.front());
    s_.push_back(s_.front());
  }
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
    const auto& a = points_[k];
    const auto& b = points_[k + 1];
    const double dx = b.x_mm - a.x_mm, dy = b.y_mm - a.y_mm, dz = b.z_mm - a.z_mm;
    const double xy = dx * dx + dy * dy, xyz = xy + dz * dz;
    segments_.push_back({a.x_mm, a.y_mm, a.z_mm, dx, dy, dz, xyz > 0.0 ? 1.0 / xyz : 0.0, xy > 0.0 ? 1.0 / xy : 0.0});
  }
  double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
  for (const auto& p : points_) {
    x_min = std::min(x_min, p.x_mm);
    x_max = std::max(x_max, p.x_mm);
    y_min = std::min(y_min, p.y_mm);
    y_max = std::max(y_max, p.y_mm);
  }
  x0_ = x_min - reach_mm_;
  y0_ = y_min - reach_mm_;
  const double width = x_max - x_min + 2.0 * reach_mm_;
  const double height = y_max - y_min + 2.0 * reach_mm_;
  // Cells a quarter of the reach, so a point's cell lists few segments beyond those within reach; larger
  // on a large part (at most ~4 million cells) or a long path (at most ~20 million listings).
  const double listings_per_segment_at_quarter_reach = 11.0 * 11.0;
  const double long_path_scale = std::sqrt(std::max(1.0, segment_count() * listings_per_segment_at_quarter_reach / 2e7));
  cell_mm_ = std::max({0.25 * reach_mm_ * long_path_scale, 0.05, std::sqrt(width * height / 4e6)});
  nx_ = static_cast<int>(width / cell_mm_) + 1;
  ny_ = static_cast<int>(height / cell_mm_) + 1;
  // Compressed rows: the segments of cell c are listed at cell_segments_[cell_start_[c], cell_start_[c + 1]).
  cell_start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
  const auto for_cells_of = [&](int k, auto&& visit) {
    const auto& a = points_[static_cast<std::size_t>(k)];
    const auto& b = points_[static_cast<std::size_t>(k) + 1];
    const int i0 = cell_x(std::min(a.x_mm, b.x_mm) - reach_mm_);
    const int i1 = cell_x(std::max(a.x_mm, b.x_mm) + reach_mm_);
    const int j0 = cell_y(std::min(a.y_mm, b.y_mm) - reach_mm_);
    const int j1 = cell_y(std::max(a.y_mm, b.y_mm) + reach_mm_);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) visit(index(i, j));
    }
  };
  for (int k = 0; k < segment_count(); ++k) for_cells_of(k, [&](std::size_t c) { ++cell_start_[c + 1]; });
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_segments_.resize(cell_start_.back());
  std::vector<std::size_t> next(cell_start_.begin(), cell_start_.end() - 1);
  for (int k = 0; k < segment_count(); ++k) {
    for_cells_of(k, [&](std::size_t c) { cell_segments_[next[c]++] = k; });  // in segment order
  }
}

}  // namespace feedplan::learning::detail
