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
  geometry::Point2 end;          //!< where the arc ends, mm: the programmed end, or the point of the circle on its ray
  double sweep_rad = 0.0;        //!< swept angle in the arc's direction, > 0
  double center_shift_mm = 0.0;  //!< how far the centre was moved to put both ends on one circle
  double end_shift_mm = 0.0;     //!< how far the end was moved onto the circle instead
  std::string problem;           //!< empty when the arc is valid; else why not (no line, no word)
};

//! Angle swept from `start` to `end` about `center` in the direction `ccw`, in (0, 2π], plus
//! (turns − 1)·2π. Start and end closer than 1e-9 mm make a full circle (2π per turn).
double sweep_rad(const geometry::Point2& start, const geometry::Point2& end, const geometry::Point2& center,
                 bool ccw, int turns);

//! Arc by centre (I/J form) from the programmed start `programmed_start` to `end` about `center`, as
//! LinuxCNC reads it: a problem when the start radius is ≤ 1e-6 mm or the end radius differs from it
//! by more than `tolerance_mm`; within the tolerance LinuxCNC keeps the centre and both ends and
//! drives a spiral. The arc returned is a circle that starts at `start` — where the path is, which
//! differs from the programmed start by an earlier arc's `end_shift_mm` — and keeps what it can:
//! either the centre moves onto the perpendicular bisector of `start` and `end` (its projection;
//! `center_shift_mm`) or the end moves along its ray from the centre onto the circle through `start`
//! (`end_shift_mm`), whichever is the smaller move. A short arc's bisector lies far from its centre
//! (on a 0.05 mm chord of a 3 mm radius, a radius difference of 0.5 µm moves the centre by 30 µm and
//! the radius by 1 %), so short arcs keep their centre and end within the rounding of their words;
//! half circles move their centre by half the radius difference. The end never moves by more than
//! `tolerance_mm` (else the centre moves, however far), so the path stays within it of the program.
//! The swept angle is LinuxCNC's, from the programmed start, end and centre (full circles and P
//! turns included), adjusted by the moves of the start, end and centre.
ArcCircle arc_from_center(const geometry::Point2& programmed_start, const geometry::Point2& start,
                          const geometry::Point2& end, const geometry::Point2& center, bool ccw, int turns,
                          double tolerance_mm);

//! Arc by radius (R form): positive R the arc of at most 180°, negative R the longer one (LinuxCNC).
//! A problem when start and end coincide (R cannot give a full circle) or |R| falls short of half
//! the chord by more than `tolerance_mm`; within it the arc is the half circle over the chord.
ArcCircle arc_from_radius(const geometry::Point2& start, const geometry::Point2& end, double radius_mm, bool ccw,
                          int turns, double tolerance_mm);

}  // namespace feedplan::gcode::detail
