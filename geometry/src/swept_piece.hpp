#pragma once
// A short piece of an earlier tool-centre move and the region its tool swept (segment ⊕ disc or
// arc ⊕ disc), with the closed-form set of tool-circle angles that fall inside that region.
// Internal to geometry.

#include <vector>

#include "angle_set.hpp"
#include "feedplan/geometry/move.hpp"
#include "vec2.hpp"

namespace feedplan::geometry::detail {

//! A line piece or a counter-clockwise arc piece of at most a quarter turn, with z linear along it.
struct SweptPiece {
  bool is_arc = false;
  Vec2 a;                     //!< start point, mm
  Vec2 b;                     //!< end point, mm
  Vec2 center;                //!< arcs: centre, mm
  double radius_mm = 0.0;     //!< arcs: radius of the centre path, mm
  double start_angle_rad = 0.0;  //!< arcs: angle of a about center
  double sweep_rad = 0.0;     //!< arcs: counter-clockwise sweep from a to b, in (0, π/2]
  double z_a_mm = 0.0;        //!< tool tip z at a
  double z_b_mm = 0.0;        //!< tool tip z at b
  double sweep_radius_mm = 0.0;  //!< radius of the tool that swept it
  Vec2 box_min;               //!< bounding box of the centre path, mm
  Vec2 box_max;
  // Derived once per piece (finish_piece) so the per-sample kernels need no atan2/sincos for them.
  double length_mm = 0.0;     //!< lines: |b − a|
  Vec2 unit;                  //!< lines: (b − a)/|b − a|
  double direction_rad = 0.0;  //!< lines: angle of unit
  double start_normal_rad = 0.0;  //!< arcs: start_angle + π/2 (inward normal of the start ray's half-plane)
  double end_normal_rad = 0.0;    //!< arcs: start_angle + sweep − π/2
  Vec2 start_normal;          //!< arcs: unit vector at start_normal_rad
  Vec2 end_normal;            //!< arcs: unit vector at end_normal_rad
};

//! Splits a move into pieces: arcs into at most quarter turns, both into pieces no longer than
//! `max_piece_length_mm`. Arc pieces are stored counter-clockwise whatever the move's direction
//! (the swept region does not depend on it). `fractions` receives, for each piece, the fraction of
//! the move where it starts (in the move's own direction), plus 1 at the end.
void split_move(const Move& move, double sweep_radius_mm, double max_piece_length_mm,
                std::vector<SweptPiece>& pieces, std::vector<double>* fractions);

//! The sub-piece between fractions f0 < f1 of the piece's own parameter (a → b).
SweptPiece sub_piece(const SweptPiece& piece, double f0, double f1);

//! Appends to `cuts` the angles θ for which p + r·(cos θ, sin θ) lies within the sweep radius of
//! the part of `piece` whose tip is at or below `height_mm`. `start_disc`/`end_disc` are false for
//! an end that is the tool itself (the piece being travelled, whose disc there is the tool disc).
//! Returns true when something was appended.
bool append_excluded(const SweptPiece& piece, Vec2 p, double r, double height_mm, bool start_disc, bool end_disc,
                     AngleIntervals& cuts);

//! Distance from p to the piece's centre path (ignoring z), mm.
double distance_to_path_mm(const SweptPiece& piece, Vec2 p);

}  // namespace feedplan::geometry::detail
