#include "feedplan/geometry/stock.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>

#include <cmath>
#include <sstream>

#include "feedplan/core/number_text.hpp"
#include "stock_section.hpp"
#include "vec2.hpp"

namespace feedplan::geometry {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polygon = CGAL::Polygon_2<Kernel>;

bool finite(const Point2& p) { return std::isfinite(p.x_mm) && std::isfinite(p.y_mm); }

Polygon to_cgal(const Contour& contour) {
  Polygon polygon;
  for (const auto& v : contour.vertices) polygon.push_back(Kernel::Point_2(v.x_mm, v.y_mm));
  return polygon;
}

double segment_distance(detail::Vec2 p, detail::Vec2 a, detail::Vec2 b) {
  const detail::Vec2 d = b - a;
  const double len_sq = detail::dot(d, d);
  const double t = len_sq > 0 ? std::clamp(detail::dot(p - a, d) / len_sq, 0.0, 1.0) : 0.0;
  return detail::norm(p - (a + t * d));
}

// Checks one contour on its own; returns false when it is unusable for further checks.
bool check_contour(const Contour& contour, const std::string& field, std::vector<InputProblem>& problems) {
  if (contour.is_circle()) {
    if (!finite(contour.center)) {
      problems.push_back({field + ".center", "is not finite: coordinates must be finite numbers in mm"});
      return false;
    }
    if (!(contour.radius_mm > 0.0) || !std::isfinite(contour.radius_mm)) {
      problems.push_back({field + ".radius_mm", "= " + six_digit_number_text(contour.radius_mm) + ": must be a finite number > 0"});
      return false;
    }
    return true;
  }
  if (contour.vertices.size() < 3) {
    problems.push_back({field + ".polygon", "has " + std::to_string(contour.vertices.size()) + " vertices: needs at least 3"});
    return false;
  }
  for (std::size_t i = 0; i < contour.vertices.size(); ++i) {
    if (!finite(contour.vertices[i])) {
      problems.push_back({field + ".polygon[" + std::to_string(i) + "]", "is not finite: coordinates must be finite numbers in mm"});
      return false;
    }
  }
  const Polygon polygon = to_cgal(contour);
  if (!polygon.is_simple()) {
    problems.push_back({field + ".polygon", "is not simple: its edges cross or touch (vertices must trace the boundary once)"});
    return false;
  }
  if (std::abs(CGAL::to_double(polygon.area())) < 1e-9) {
    problems.push_back({field + ".polygon", "has zero area"});
    return false;
  }
  return true;
}

// True when `inner` lies inside `outer` (strictly, apart from touching within tolerance).
bool contour_inside(const Contour& inner, const Contour& outer) {
  if (outer.is_circle()) {
    const detail::Vec2 c = detail::to_vec(outer.center);
    if (inner.is_circle()) {
      return detail::norm(detail::to_vec(inner.center) - c) + inner.radius_mm <= outer.radius_mm + 1e-9;
    }
    for (const auto& v : inner.vertices) {
      if (detail::norm(detail::to_vec(v) - c) > outer.radius_mm + 1e-9) return false;
    }
    return true;
  }
  const Polygon polygon = to_cgal(outer);
  if (inner.is_circle()) {
    const Kernel::Point_2 center(inner.center.x_mm, inner.center.y_mm);
    if (polygon.bounded_side(center) != CGAL::ON_BOUNDED_SIDE) return false;
    const auto& v = outer.vertices;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (segment_distance(detail::to_vec(inner.center), detail::to_vec(v[i]), detail::to_vec(v[(i + 1) % v.size()])) <
          inner.radius_mm - 1e-9) {
        return false;
      }
    }
    return true;
  }
  for (const auto& v : inner.vertices) {
    if (polygon.bounded_side(Kernel::Point_2(v.x_mm, v.y_mm)) == CGAL::ON_UNBOUNDED_SIDE) return false;
  }
  // Vertices inside is not enough for non-convex outers: no edge of one may cross an edge of the other.
  const Polygon hole = to_cgal(inner);
  for (auto e = hole.edges_begin(); e != hole.edges_end(); ++e) {
    for (auto f = polygon.edges_begin(); f != polygon.edges_end(); ++f) {
      if (CGAL::do_intersect(*e, *f)) return false;
    }
  }
  return true;
}

bool contours_disjoint(const Contour& a, const Contour& b) {
  // Two holes are disjoint when no vertex/centre of one is inside the other and no boundaries meet.
  auto sample_inside = [](const Contour& x, const Contour& y) {
    if (x.is_circle()) {
      if (detail::inside_contour(y, detail::to_vec(x.center))) return true;
      if (y.is_circle()) {
        return detail::norm(detail::to_vec(x.center) - detail::to_vec(y.center)) < x.radius_mm + y.radius_mm;
      }
      const auto& v = y.vertices;
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (segment_distance(detail::to_vec(x.center), detail::to_vec(v[i]), detail::to_vec(v[(i + 1) % v.size()])) <
            x.radius_mm) {
          return true;
        }
      }
      return false;
    }
    for (const auto& v : x.vertices) {
      if (detail::inside_contour(y, detail::to_vec(v))) return true;
    }
    return false;
  };
  if (sample_inside(a, b) || sample_inside(b, a)) return false;
  if (!a.is_circle() && !b.is_circle()) {
    const Polygon pa = to_cgal(a);
    const Polygon pb = to_cgal(b);
    for (auto e = pa.edges_begin(); e != pa.edges_end(); ++e) {
      for (auto f = pb.edges_begin(); f != pb.edges_end(); ++f) {
        if (CGAL::do_intersect(*e, *f)) return false;
      }
    }
  }
  return true;
}

}  // namespace

std::vector<InputProblem> validate(const Stock& stock, const std::string& field) {
  std::vector<InputProblem> problems;
  if (!std::isfinite(stock.z_bottom_mm)) {
    problems.push_back({field + ".z_bottom_mm", "= " + six_digit_number_text(stock.z_bottom_mm) + ": must be a finite number"});
  }
  if (!std::isfinite(stock.z_top_mm)) {
    problems.push_back({field + ".z_top_mm", "= " + six_digit_number_text(stock.z_top_mm) + ": must be a finite number"});
  }
  if (std::isfinite(stock.z_bottom_mm) && std::isfinite(stock.z_top_mm) && !(stock.z_top_mm > stock.z_bottom_mm)) {
    problems.push_back({field + ".z_top_mm", "= " + six_digit_number_text(stock.z_top_mm) + ": must be > z_bottom_mm = " + six_digit_number_text(stock.z_bottom_mm)});
  }
  if (stock.regions.empty()) {
    problems.push_back({field + ".regions", "is empty: the stock needs at least one region of material"});
  }
  for (std::size_t r = 0; r < stock.regions.size(); ++r) {
    const auto& region = stock.regions[r];
    const std::string region_field = field + ".regions[" + std::to_string(r) + "]";
    const bool outer_ok = check_contour(region.outer, region_field + ".outer", problems);
    for (std::size_t h = 0; h < region.holes.size(); ++h) {
      const std::string hole_field = region_field + ".holes[" + std::to_string(h) + "]";
      if (!check_contour(region.holes[h], hole_field, problems) || !outer_ok) continue;
      if (!contour_inside(region.holes[h], region.outer)) {
        problems.push_back({hole_field, "is not inside the region's outer contour: holes must lie within the material"});
      }
      for (std::size_t k = 0; k < h; ++k) {
        if (!contours_disjoint(region.holes[h], region.holes[k])) {
          problems.push_back({hole_field, "overlaps holes[" + std::to_string(k) + "]: holes must be disjoint (merge them)"});
        }
      }
    }
  }
  return problems;
}

Stock after_cutting(const Stock& stock, const ToolPath& path, double tool_radius_mm) {
  Stock result = stock;
  result.removed.reserve(stock.removed.size() + path.moves.size());
  for (const auto& move : path.moves) result.removed.push_back({move, tool_radius_mm});
  return result;
}

}  // namespace feedplan::geometry
