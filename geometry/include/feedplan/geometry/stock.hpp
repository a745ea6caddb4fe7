#pragma once
// The workpiece material before a cycle: an initial 2D region extruded over a z range, minus the
// material that earlier cuts swept away. Carrying a Stock from one cycle to the next is how a later
// cycle sees what an earlier one removed (docs/method.md §5.2).

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/move.hpp"
#include "feedplan/geometry/point.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::geometry {

//! A closed boundary: a simple polygon (vertices in order, not repeated at the end) or, when
//! `vertices` is empty, a circle.
struct Contour {
  std::vector<Point2> vertices;  //!< polygon vertices, mm; empty for a circle
  Point2 center;                 //!< circle centre, mm
  double radius_mm = 0.0;        //!< circle radius, mm

  bool is_circle() const { return vertices.empty(); }
  static Contour polygon(std::vector<Point2> vertices) { return Contour{std::move(vertices), {}, 0.0}; }
  static Contour circle(Point2 center, double radius_mm) { return Contour{{}, center, radius_mm}; }
  static Contour rectangle(Point2 min_corner, Point2 max_corner) {
    return polygon({min_corner, {max_corner.x_mm, min_corner.y_mm}, max_corner, {min_corner.x_mm, max_corner.y_mm}});
  }
};

//! Material inside `outer` and outside every hole.
struct StockRegion {
  Contour outer;               //!< outer boundary
  std::vector<Contour> holes;  //!< holes (pre-drilled bores, earlier pockets), inside outer, disjoint
};

//! Material an earlier cut removed: everything within the tool radius of the move, above its tip.
struct SweptMove {
  Move move;                   //!< the earlier move of the tool centre
  double tool_radius_mm = 0.0; //!< radius of the tool that made it, mm
};

//! The workpiece: (union of regions) × [z_bottom_mm, z_top_mm] minus the swept moves.
struct Stock {
  std::vector<StockRegion> regions;  //!< initial material in XY; regions must not overlap
  double z_bottom_mm = -50.0;        //!< bottom of the material, mm
  double z_top_mm = 0.0;             //!< top face of the material, mm
  std::vector<SweptMove> removed;    //!< earlier cuts, in the order they were made
};

//! Checks a stock: non-empty, finite coordinates, polygons simple with ≥ 3 vertices and non-zero
//! area, circles with positive radius, holes inside their outer contour and disjoint, z_top > z_bottom.
//! Polygon checks use CGAL's exact predicates. `field` prefixes every problem ("stock").
std::vector<InputProblem> validate(const Stock& stock, const std::string& field = "stock");

//! The stock after `path` has been cut with a tool of `tool_radius_mm`: every move of the path is
//! appended to `removed` (a move above the stock removes nothing; a rapid through material is a
//! collision, which compute_engagement reports, and the material is gone afterwards either way).
Stock after_cutting(const Stock& stock, const ToolPath& path, double tool_radius_mm);

}  // namespace feedplan::geometry
