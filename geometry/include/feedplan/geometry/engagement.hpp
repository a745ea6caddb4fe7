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
  //! Without evaluation_z_mm, the engagement is found on every layer of material between the tool tip
  //! and the stock top (EngagementLayer); layers closer than this are not told apart (the lower one's
  //! engaged set, a superset, stands for both), mm (> 0).
  double layer_resolution_mm = 0.1;
};

//! The engagement on one band of heights above the tool tip at a sample: the engaged set is the one at
//! the band's bottom height, which contains the engaged set at every height inside the band (material
//! only disappears upwards: an earlier cut removes everything above its tip).
struct EngagementLayer {
  double bottom_z_mm = 0.0;      //!< absolute height where the band starts, mm
  double top_z_mm = 0.0;         //!< absolute height where it ends, mm
  int interval_begin = 0;        //!< first interval in EngagementProfile::intervals
  int interval_count = 0;        //!< number of engaged intervals (≥ 1)
  double engagement_rad = 0.0;   //!< total engaged angle on the band, rad
  double chip_factor = 0.0;      //!< largest sin φ over the engaged set (0 on plunges)
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
  //! Axial depth of cut the force model sees here, mm: the height of material in contact above the tip
  //! (material_height_mm) where engaged, else the move's planned axial depth
  double axial_depth_mm = 0.0;
  int interval_begin = 0;            //!< first interval in EngagementProfile::intervals
  int interval_count = 0;            //!< number of engaged intervals (0 when not engaged)
  //! Height from the tool tip to the top of the highest layer with engaged material, mm (0 when not
  //! engaged, and with EngagementOptions::evaluation_z_mm)
  double material_height_mm = 0.0;
  //! The tool descends here and its end face meets material inside the tool circle that the circle
  //! itself does not reach (engagement_rad is 0): a plunge onto an island or the rim of a hole. Found on
  //! concentric circles at 5 %, 25 %, 50 %, 75 % and 95 % of the radius, just above the tip.
  bool end_face_in_material = false;
  int layer_begin = 0;               //!< first layer in EngagementProfile::layers
  int layer_count = 0;               //!< layers with engaged material, lowest first (0 when not engaged)
};

//! Engagement along a whole path.
struct EngagementProfile {
  double tool_radius_mm = 0.0;              //!< tool radius used, mm
  double ds_mm = 0.0;                       //!< requested sample spacing, mm
  std::vector<EngagementSample> samples;    //!< in path order; the last move's end point is the last sample
  std::vector<EngagedInterval> intervals;   //!< engaged intervals of all samples, by interval_begin/count
  std::vector<EngagementLayer> layers;      //!< engaged layers of all samples, by layer_begin/count
  std::vector<std::string> part_names;      //!< copied from the ToolPath
  std::vector<std::string> warnings;        //!< e.g. a rapid or air move that meets material
};

//! Computes the engagement of a tool of radius `tool_radius_mm` along `path` on `stock`.
//!
//! A point q of the tool circle is engaged at a height h when it lies inside the initial stock (XY
//! region and z range) and farther than the tool radius from every earlier position of the tool centre
//! whose tip was at or below h — earlier moves of `path` up to the sample, and `stock.removed`.
//!
//! Every layer the tool meets is examined: from just above the tip up to the stock top. Because an
//! earlier cut removes everything above its tip, the engaged set can only shrink with the height, so
//! equal sets at two heights mean equal sets between them; the heights are bisected until the sets
//! agree or lie closer than `options.layer_resolution_mm`, and each band keeps the set at its bottom
//! (a superset of the set anywhere inside it). The sample's engagement, chip factor and contact length
//! are those of the lowest layer — the largest; its axial depth is the height of material in contact
//! (on a helix, the layer the previous turn left: about one pitch; on a 2.5D cut, its depth). A
//! move of any kind that meets material on any layer is engaged, so a plunge or ramp into material,
//! or the first helix turn below the stock top, is never taken for air.
//!
//! With `options.evaluation_z_mm`, only that one height is evaluated (the virtual machine's layers).
//!
//! The engaged set is computed in closed form — intersections of the tool circle with lines and
//! circles bounding the earlier swept regions (segment ⊕ disc, arc ⊕ disc) and the stock
//! boundary — with no rasterisation and no polygonal approximation of circles. Candidate swept
//! regions come from a box-intersection index (CGAL).
//!
//! Requires a consistent path (see consistency_defects), tool_radius_mm > 0, ds_mm > 0 and
//! layer_resolution_mm > 0; these are asserted, as callers validate user input first.
EngagementProfile compute_engagement(const ToolPath& path, const Stock& stock, double tool_radius_mm,
                                     const EngagementOptions& options = {});

}  // namespace feedplan::geometry
