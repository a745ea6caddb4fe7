#pragma once
// The moves of LinuxCNC's drilling canned cycles in the XY plane (interp_cycles.cc, convert_cycle_xy and
// convert_cycle_g73 … g89), checked against the installed rs274. Internal to the gcode module.
//
// The initial level is the Z the tool was at when the cycles began (the first cycle block after another
// motion mode or G80); G91's R is measured from it. Before the holes: when the initial level is below the
// R plane the tool rapids straight up to R. Clearance: G99 the R plane, G98 the higher of the initial
// level and R. Each hole (L repeats; under G91 each one a step further):
//   1. rapid to the hole's XY: for the first hole of the block, when the tool is above R, at its height,
//      else at the clearance;
//   2. rapid down to R, unless already there;
//   3. the cycle's own moves:
//      G81  feed to the bottom; rapid to the clearance.
//      G82  feed to the bottom; dwell P; rapid to the clearance.
//      G83  pecks: feed Q deeper (from R) while above the bottom, rapid up to R, rapid back down to
//           0.254 mm (0.010 in) above the depth reached; then feed to the bottom; rapid to the clearance.
//      G73  chip breaking: feed Q deeper while above the bottom, rapid back 0.254 mm; then feed to the
//           bottom; rapid to the clearance.
//      G85  feed to the bottom; feed back up to R; rapid to the clearance.
//      G86  feed to the bottom; dwell P; spindle stop; rapid to the clearance; spindle restart.
//      G89  feed to the bottom; dwell P; feed to the clearance.

#include <vector>

#include "feedplan/geometry/point.hpp"

namespace feedplan::gcode::detail {

//! One drilling cycle block, its lengths in the program's unit (LinuxCNC computes in them: the pecks'
//! comparisons with the bottom then agree with its own).
struct DrillRequest {
  int code = 810;                      //!< 730, 810, 820, 830, 850, 860 or 890 (G number in tenths)
  geometry::Point3 position;           //!< where the tool is, mm
  double initial_level = 0.0;          //!< Z when the cycles began (LinuxCNC's cycle_il)
  geometry::Point2 first_hole;         //!< XY of the first hole, mm
  geometry::Point2 step;               //!< XY step from one repeat's hole to the next (G91), mm; 0 in G90
  int repeats = 1;                     //!< L
  double r = 0.0;                      //!< R plane (absolute)
  double bottom = 0.0;                 //!< bottom Z (absolute), ≤ r
  bool retract_to_r = false;           //!< G99 (else G98)
  double peck = 0.0;                   //!< Q of G73/G83, > 0
  double dwell_s = 0.0;                //!< P of G82/G86/G89
  double unit_mm = 1.0;                //!< mm per program unit
};

//! One move of a cycle, mm.
struct DrillMove {
  bool feed = false;                   //!< a feed move (else a rapid)
  geometry::Point3 end;                //!< where it ends, mm
  double dwell_before_s = 0.0;         //!< a dwell before it
  bool spindle_stopped = false;        //!< G86's retract, spindle stopped
};

//! About how many moves drill_moves makes (a bound, as a double: Q may be tiny and L large).
double drill_move_count(const DrillRequest& request);

//! The moves of the cycle, in order; `end` gets where the tool is after it, mm. Moves of zero length
//! are included (the caller drops them, as the reader drops zero-length moves).
std::vector<DrillMove> drill_moves(const DrillRequest& request, geometry::Point3& end);

}  // namespace feedplan::gcode::detail
