#pragma once
// Internal 2D vector arithmetic for the geometry kernels (mm). Not part of the public API.

#include <cmath>

#include "feedplan/geometry/point.hpp"

namespace feedplan::geometry::detail {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

constexpr Vec2 to_vec(const Point2& p) { return {p.x_mm, p.y_mm}; }
constexpr Vec2 to_vec(const Point3& p) { return {p.x_mm, p.y_mm}; }
constexpr Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
constexpr Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
constexpr Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
// sqrt of the sum of squares: coordinates are in mm, far from overflow, and std::hypot is slow.
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }
inline double angle_of(Vec2 a) { return std::atan2(a.y, a.x); }
inline Vec2 unit_at(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

}  // namespace feedplan::geometry::detail
