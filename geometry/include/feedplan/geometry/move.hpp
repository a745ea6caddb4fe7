#pragma once
// One motion of the tool centre: a rapid, a straight feed move, or a circular/helical feed move.

#include "feedplan/geometry/point.hpp"

namespace feedplan::geometry {

enum class MoveKind {
  kRapid,  //!< positioning at the rapid rate (G0); never meant to cut
  kLine,   //!< straight feed move (G1), possibly with a z change
  kArc,    //!< circular feed move in the XY plane (G2/G3); a helix when z changes along it
};

//! One move of the tool centre from `start` to `end`.
//!
//! Arcs turn about `center` by `sweep_rad` in the direction given by `ccw`; z changes linearly with
//! the swept angle (a helix). Start and end lie on the same circle about `center`; a full circle has
//! start == end and sweep_rad == 2π. Lines and rapids ignore center, ccw and sweep_rad.
struct Move {
  MoveKind kind = MoveKind::kLine;  //!< rapid, line or arc
  Point3 start;                     //!< tool tip position where the move starts, mm
  Point3 end;                       //!< tool tip position where the move ends, mm
  Point2 center;                    //!< arcs: centre of the XY circle, mm
  bool ccw = true;                  //!< arcs: counter-clockwise seen from +z (G3); false is G2
  double sweep_rad = 0.0;           //!< arcs: swept angle, > 0 (more than 2π for multi-turn helices)
  bool cutting = false;             //!< true for feed moves meant to remove material; false for air
  double axial_depth_mm = 0.0;      //!< axial depth of cut the move is planned for: A_d on 2.5D moves,
                                    //!< the pitch on helices; 0 on air moves
  int part = 0;                     //!< index into ToolPath::part_names (which cycle part it belongs to)
};

}  // namespace feedplan::geometry
