#pragma once
// Points in the machine's program coordinates, millimetres.

namespace feedplan::geometry {

//! A point or offset in the XY plane.
struct Point2 {
  double x_mm = 0.0;  //!< X, mm
  double y_mm = 0.0;  //!< Y, mm
};

//! A point in space; z is the tool tip (the bottom of a flat end mill).
struct Point3 {
  double x_mm = 0.0;  //!< X, mm
  double y_mm = 0.0;  //!< Y, mm
  double z_mm = 0.0;  //!< Z of the tool tip, mm
};

constexpr Point2 xy(const Point3& p) { return {p.x_mm, p.y_mm}; }

}  // namespace feedplan::geometry
