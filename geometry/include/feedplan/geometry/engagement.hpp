#pragma once
// The cutter's engagement along a tool path: at each sample, which part of the tool circle is in
// material, and the quantities the force model needs (docs/method.md §5).
//
// Angles of tool points are immersion angles φ as in Altintas: measured clockwise (the sense in
// which an M3 spindle turns the teeth) from the left-hand normal of the feed direction. φ = 0 is the
// left side, π/2 the front, π the right side; the back is 3π/2 ≡ −π/2. Intervals are reported in
// [−π/2, 3π/2) so that no engaged interval is split at the back of the tool. Down (climb) milling
// with the material on the right exits at φ = π; a full slot is engaged over [0, π].

#include <optional>
#include <string>
#include <vector>

#include "feedplan/geometry/point.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::geometry {

//! How finely to sample the path.
struct EngagementOptions {
  double ds_mm = 0.05;  //!< sample spacing along the path (3D arc length), mm; each move gets
                        //!< ceil(length / ds) equal steps
  //! When set, the engagement is evaluated on this absolute height (mm) instead of the default layer
  //! (half the move's axial depth above the tip): one axial layer of the stock, as the virtual
  //! machine needs for helices. Samples whose tool tip is at or above this height do not reach the
  //! layer and have no engagement there.
  std::optional<double> evaluation_z_mm = std::nullopt;
};

//! One engaged interval of the tool circle, in immersion angles (radians, entry < exit).
struct EngagedInterval {
  double entry_rad = 0.0;  //!< where a tooth enters the material
  double exit_rad = 0.0;   //!< where it leaves
};

//! The engagement at one sample of the path.
struct EngagementSample {
  double s_mm = 0.0;                 //!< arc length from the start of the path (in space), mm
  Point3 position;                   //!< tool tip position, mm
  double feed_direction_rad = 0.0;   //!< direction of XY travel, counter-clockwise from +X, rad
  double xy_speed_ratio = 1.0;       //!< XY speed / path speed (cos of the ramp angle; 0 on plunges)
  int move_index = 0;                //!< index of the move in ToolPath::moves
  int part = 0;                      //!< cycle part, index into EngagementProfile::part_names
  bool cutting = false;              //!< the move is a cutting move (false: air or rapid)
  double engagement_rad = 0.0;       //!< total engaged angle α_en, rad, in [0, 2π]
  double entry_rad = 0.0;            //!< entry of the first engaged interval, rad (0 when not engaged)
  double exit_rad = 0.0;             //!< exit of the last engaged interval, rad (0 when not engaged)
  double chip_factor = 0.0;          //!< k = t_m / f_z: the largest cos of a tool point's angle from the
                                     //!< feed direction over the engaged set, in [0, 1] (docs/method.md §5.1)
  double contact_length_mm = 0.0;    //!< L = r · α_en, mm
  //! ρ ≥ 1: uncut chip area over that of the straight cut with the same t_m and L (chip_area_ratio.hpp);
  //! 1 on straight cuts and steady arcs, up to 2 where the tool enters material
  double chip_area_ratio = 1.0;
  double axial_depth_mm = 0.0;       //!< axial depth of cut the force model sees here, mm
  int interval_begin = 0;            //!< first interval in EngagementProfile::intervals
  int interval_count = 0;            //!< number of engaged intervals (0 when not engaged)
};

//! Engagement along a whole path.
struct EngagementProfile {
  double tool_radius_mm = 0.0;              //!< tool radius used, mm
  double ds_mm = 0.0;                       //!< requested sample spacing, mm
  std::vector<EngagementSample> samples;    //!< in path order; the last move's end point is the last sample
  std::vector<EngagedInterval> intervals;   //!< engaged intervals of all samples, by interval_begin/count
  std::vector<std::string> part_names;      //!< copied from the ToolPath
  std::vector<std::string> warnings;        //!< e.g. a rapid or air move that meets material
};

//! Computes the engagement of a tool of radius `tool_radius_mm` along `path` on `stock`.
//!
//! A point q of the tool circle is engaged when it lies inside the initial stock (XY region and z
//! range) and farther than the tool radius from every earlier position of the tool centre whose tip
//! was at or below the evaluation height — earlier moves of `path` up to the sample, and
//! `stock.removed`. The evaluation height is the middle of the layer being cut (tip z + half the
//! move's axial depth): on 2.5D moves any height within the cut gives the same answer; on a helix
//! it is the layer one pitch deep that the previous turn left (an approximation: end cutting and the
//! variation of the cross-section over the pitch are not modelled, as in seed 003).
//!
//! The engaged set is computed in closed form — intersections of the tool circle with lines and
//! circles bounding the earlier swept regions (segment ⊕ disc, arc ⊕ disc) and the stock
//! boundary — with no rasterisation and no polygonal approximation of circles. Candidate swept
//! regions come from a box-intersection index (CGAL).
//!
//! Requires a consistent path (see consistency_defects), tool_radius_mm > 0 and ds_mm > 0; these are
//! asserted, as callers validate user input first.
EngagementProfile compute_engagement(const ToolPath& path, const Stock& stock, double tool_radius_mm,
                                     const EngagementOptions& options = {});

}  // namespace feedplan::geometry
