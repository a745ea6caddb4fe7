#pragma once
// The part of a tool circle that lies inside a stock's initial material (its XY regions and z
// range), in closed form: circle–segment and circle–circle intersections, with the arcs between
// them classified by an inside test. Internal to geometry.

#include "angle_set.hpp"
#include "feedplan/geometry/stock.hpp"
#include "vec2.hpp"

namespace feedplan::geometry::detail {

//! Angles θ for which p + r·(cos θ, sin θ) is inside the initial material of `stock` at
//! `height_mm` (removed sweeps are not considered here).
AngleIntervals initial_material(const Stock& stock, Vec2 p, double r, double height_mm);

//! True when the point is strictly inside the contour (crossing number for polygons).
bool inside_contour(const Contour& contour, Vec2 q);

}  // namespace feedplan::geometry::detail
