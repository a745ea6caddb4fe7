#include "program_stock.hpp"

#include <algorithm>

#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::cli {

geometry::Stock default_stock(const geometry::Program& program, double tool_radius_mm) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300, z_low = 0.0;
  for (const auto& move : program.path.moves) {
    if (move.kind == geometry::MoveKind::kRapid) continue;
    for (double f = 0.0; f <= 1.0; f += 0.125) {
      const auto p = geometry::point_at(move, f);
      x0 = std::min(x0, p.x_mm);
      y0 = std::min(y0, p.y_mm);
      x1 = std::max(x1, p.x_mm);
      y1 = std::max(y1, p.y_mm);
      z_low = std::min(z_low, p.z_mm);
    }
  }
  geometry::Stock stock;
  if (x0 > x1) {
    x0 = y0 = -1.0;
    x1 = y1 = 1.0;
  }
  const double grow = 4.0 * tool_radius_mm;
  stock.regions.push_back({geometry::Contour::rectangle({x0 - grow, y0 - grow}, {x1 + grow, y1 + grow}), {}});
  stock.z_top_mm = 0.0;
  stock.z_bottom_mm = z_low - 5.0;
  return stock;
}

}  // namespace feedplan::cli
