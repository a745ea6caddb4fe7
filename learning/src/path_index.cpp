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
  // Cells about twice the reach, so a segment lands in a few cells; at most ~4 million cells.
  cell_mm_ = std::max({2.0 * reach_mm_, 0.25, std::sqrt(width * height / 4e6)});
  nx_ = static_cast<int>(width / cell_mm_) + 1;
  ny_ = static_cast<int>(height / cell_mm_) + 1;
  cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
  for (int k = 0; k < segment_count(); ++k) {
    const auto& a = points_[static_cast<std::size_t>(k)];
    const auto& b = points_[static_cast<std::size_t>(k) + 1];
    const int i0 = cell_x(std::min(a.x_mm, b.x_mm) - reach_mm_);
    const int i1 = cell_x(std::max(a.x_mm, b.x_mm) + reach_mm_);
    const int j0 = cell_y(std::min(a.y_mm, b.y_mm) - reach_mm_);
    const int j1 = cell_y(std::max(a.y_mm, b.y_mm) + reach_mm_);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) cells_[index(i, j)].push_back(k);  // in segment order
    }
  }
}

}  // namespace feedplan::learning::detail
