#pragma once
// The pocket's corner clean-up (seed 003 Fig. 3, "corner rounding"): before the wall pass, one
// trochoid per corner from inside the roughed stadium along the line from the slot end centre O to
// the corner centre Q, with loops of radius R_t = R_q − r, where R_q < R_c is how far from Q the
// loops cut. Internal to the cycles module.
//
// Why: the wall pass follows the finished corner on an arc of radius ρ = R_c − r about Q. With the
// stock left concentric at R_d below the finished corner it engages (docs/method.md §5.1, internal
// arc) cos α = [(R_c − R_d)² − ρ² − r²] / (2 r ρ) — 74° for R_c = 8, r = 5, R_d = a = 1.5, and 144°
// on the corner stock the round slot ends leave. The clean-up leaves R_d = R_c − R_q chosen for a
// given bound α_max; a trochoid of loop radius R_t and pitch p meets, at the front of each loop, the
// same configuration (tool centre R_t + p from the last loop's centre, material beyond R_t + r), so
// p = R_d keeps its steady front under the same bound (0.8·R_d keeps the start of each loop there too).
//
// Every loop disc stays inside the pocket: O and Q are corners or inner points of the pocket's inner
// rectangle (the finished outline is that rectangle grown by R_c), so a disc of radius R_q < R_c about
// any point of O–Q lies inside the finished outline.

#include <vector>

#include "feedplan/geometry/point.hpp"

namespace feedplan::cycles::detail {

//! Radial depth R_d at which a tool of radius `tool_radius_mm` on an internal arc about a finished
//! wall of radius `wall_radius_mm` (> tool radius) engages `engagement_rad` (in (0, π/2]): the inverse
//! of the internal-arc form of docs/method.md §5.1, mm.
double internal_arc_radial_depth_mm(double tool_radius_mm, double wall_radius_mm, double engagement_rad);

//! One corner's trochoid: loop centres from `start` to `end` (= the corner centre Q).
struct CornerTrochoid {
  geometry::Point2 start;  //!< first loop centre, mm, inside the roughed stadium
  geometry::Point2 end;    //!< last loop centre: the corner centre Q, mm
};

//! What the clean-up cuts in every corner.
struct CornerCleanUp {
  double loop_radius_mm = 0.0;   //!< R_t = R_q − r, mm
  double reach_mm = 0.0;         //!< R_q: the loops cut the corner up to this distance from Q, mm
  double pitch_mm = 0.0;         //!< largest loop advance, mm
  std::vector<CornerTrochoid> trochoids;  //!< the corners that need one, in the wall pass's order
};

//! Plans the clean-up of the corners with centres `corners` (wall pass order), each cleaned from the
//! slot end centre in `slot_ends` (same index) whose roughed disc has radius `rough_radius_mm`
//! (R_s). `corner_radius_mm` R_c (> r), `pitch_mm` the largest pitch the spec allows, `engagement_rad`
//! the bound for the loops and the wall pass's corner arcs. A corner whose loops would all lie in the
//! roughed disc gets no trochoid.
CornerCleanUp plan_corner_clean_up(const std::vector<geometry::Point2>& corners,
                                   const std::vector<geometry::Point2>& slot_ends, double rough_radius_mm,
                                   double corner_radius_mm, double tool_radius_mm, double pitch_mm,
                                   double engagement_rad);

}  // namespace feedplan::cycles::detail
