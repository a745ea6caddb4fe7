#pragma once
// The circle of a G2/G3 arc in the XY plane from its programmed words: centre from I/J or from R,
// and the swept angle. Follows LinuxCNC's interpreter (interp_arc.cc) so that its canonical output
// is an oracle. Internal to the gcode module.

#include <string>

#include "feedplan/geometry/point.hpp"

namespace feedplan::gcode::detail {

//! An arc's circle, or the reason there is none.
struct ArcCircle {
  geometry::Point2 center;       //!< centre, mm; start and end are equidistant from it
  double sweep_rad = 0.0;        //!< swept angle in the arc's direction, > 0
  double center_shift_mm = 0.0;  //!< how far the centre was moved to put both ends on one circle
  std::string problem;           //!< empty when the arc is valid; else why not (no line, no word)
};

//! Angle swept from `start` to `end` about `center` in the direction `ccw`, in (0, 2π], plus
//! (turns − 1)·2π. Start and end closer than 1e-9 mm make a full circle (2π per turn).
double sweep_rad(const geometry::Point2& start, const geometry::Point2& end, const geometry::Point2& center,
                 bool ccw, int turns);

//! Arc by centre (I/J form). A problem when the start radius is ≤ 1e-6 mm or the end radius differs
//! from it by more than `tolerance_mm`; within the tolerance the centre is moved onto the
//! perpendicular bisector of start and end (its projection; `center_shift_mm` says by how much).
ArcCircle arc_from_center(const geometry::Point2& start, const geometry::Point2& end,
                          const geometry::Point2& center, bool ccw, int turns, double tolerance_mm);

//! Arc by radius (R form): positive R the arc of at most 180°, negative R the longer one (LinuxCNC).
//! A problem when start and end coincide (R cannot give a full circle) or |R| falls short of half
//! the chord by more than `tolerance_mm`; within it the arc is the half circle over the chord.
ArcCircle arc_from_radius(const geometry::Point2& start, const geometry::Point2& end, double radius_mm, bool ccw,
                          int turns, double tolerance_mm);

}  // namespace feedplan::gcode::detail
