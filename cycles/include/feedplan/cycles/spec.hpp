#pragma once
// What a cycle spec says: the tool, the cutting conditions, the machine, and the geometry of one
// canned cycle (docs/method.md §4). Plain structs; read_cycle_spec (spec_reader.hpp) fills and checks
// them from YAML, and programs may fill them directly and call validate (cycle.hpp).
//
// Conventions shared by every cycle: an M3 (clockwise) spindle and climb (down) milling, so the
// material is on the RIGHT of the feed direction and the default turning sense is counter-clockwise.
// `Direction::kCw` mirrors the whole cycle; with an M3 spindle a mirrored cycle mills conventionally
// (up milling). Positions are tool-centre positions in program coordinates unless a field says it is
// a finished wall.

#include <optional>
#include <string>
#include <variant>

#include "feedplan/geometry/machine_limits.hpp"
#include "feedplan/geometry/point.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cycles {

//! Turning sense of a cycle, seen from +z.
enum class Direction {
  kCcw,  //!< counter-clockwise (G3): climb milling with an M3 spindle
  kCw,   //!< clockwise (G2): the mirror image of kCcw
};

//! "ccw" or "cw", as written in specs.
const char* to_string(Direction direction);

//! Corner rounding (seed 003 Fig. 5): finishing an internal (concave) corner between two straight
//! walls, the walls on the tool's right, the path turning left. The material before the cut is what
//! an earlier pass of the same tool, `radial_depth_mm` further from the walls, left (docs/method.md §5.1).
struct CornerSpec {
  geometry::Point2 corner_point;                //!< intersection of the two finished wall lines, mm
  double entry_heading_deg = 0.0;               //!< direction of travel along wall 1, counter-clockwise from +X, deg
  double corner_angle_deg = 90.0;               //!< interior angle between the walls on the tool's side, deg, in (0, 180)
  double corner_radius_mm = 0.0;                //!< radius R of the FINISHED wall at the corner, mm (> tool radius)
  double radial_depth_mm = 0.0;                 //!< radial depth of cut R_d on the walls, mm, in (0, tool diameter]
  double wall_length_mm = 30.0;                 //!< length of each straight wall from its tangent point, mm
  std::optional<double> lead_mm;                //!< air approach/departure beyond the stock, mm (unset: tool diameter)
  Direction direction = Direction::kCcw;        //!< kCw mirrors the corner about wall 1 (walls on the left)
};

//! Trochoidal slotting (seed 003 Fig. 7, Table 2): full circles whose centres advance along the slot
//! axis by one pitch per loop, joined by straight steps tangent to the circles.
struct TrochoidSpec {
  geometry::Point2 start;                 //!< centre of the first loop, mm
  geometry::Point2 end;                   //!< centre of the last loop, mm (≠ start)
  double loop_radius_mm = 0.0;            //!< radius R_t of the tool-centre circles, mm; slot width 2(R_t + r)
  double pitch_mm = 0.0;                  //!< advance p of the loop centre per loop, mm, in (0, tool diameter)
  Direction direction = Direction::kCcw;  //!< kCw mirrors the loops about the slot axis
};

//! Spiral internal-cylinder expansion (seed 003 Fig. 12, Table 3): a pre-drilled bore grows to the
//! final radius by a spiral of semicircles, then one finishing circle.
struct SpiralSpec {
  geometry::Point2 center;                //!< bore axis, mm
  double initial_radius_mm = 0.0;         //!< radius R_init of the pre-drilled bore (its wall), mm (> tool radius)
  double final_radius_mm = 0.0;           //!< radius R_fin of the finished bore wall, mm (> R_init)
  double pitch_mm = 0.0;                  //!< increase of the radius per turn, mm, in (0, tool diameter)
  Direction direction = Direction::kCcw;  //!< kCw mirrors the spiral about the X axis through the centre
};

//! Helical boring into solid material: helix turns down to depth, then one clean-up circle.
struct HelicalBoringSpec {
  geometry::Point2 center;                //!< hole axis, mm
  double hole_diameter_mm = 0.0;          //!< finished hole diameter D_h, mm, in (tool diameter, 2 × tool diameter]
  double pitch_mm = 0.0;                  //!< depth per helix turn, mm, in (0, tool diameter)
  double depth_mm = 0.0;                  //!< hole depth below the stock top, mm
  Direction direction = Direction::kCcw;  //!< kCw mirrors the helix about the X axis through the centre
};

//! Rectangular pocket with rounded corners, cut by the canned cycles of seed 003 Fig. 3: helical
//! boring at the centre, spiral expansion, trochoidal slots along the long axis, wall finishing.
struct PocketSpec {
  geometry::Point2 center;                     //!< pocket centre, mm
  double width_mm = 0.0;                       //!< size along X (finished walls), mm
  double height_mm = 0.0;                      //!< size along Y (finished walls), mm
  double depth_mm = 0.0;                       //!< depth below the stock top, mm
  double corner_radius_mm = 0.0;               //!< finished corner radius, mm, in (tool radius, min(width, height) / 2]
  std::optional<double> finish_allowance_mm;   //!< wall stock left for the finishing pass, mm (unset: 0.15 × tool diameter)
  std::optional<double> helix_pitch_mm;        //!< pitch of the centre bore's helix, mm (unset: 0.1 × tool diameter)
  std::optional<double> spiral_pitch_mm;       //!< radius increase per spiral turn, mm (unset: 0.1 × tool diameter)
  std::optional<double> trochoid_pitch_mm;     //!< loop advance of the slots, mm (unset: 0.1 × tool diameter)
  Direction direction = Direction::kCcw;       //!< kCw runs every sub-cycle and the wall pass mirrored
};

//! The geometry of one cycle: exactly one of the five.
using CycleGeometry = std::variant<CornerSpec, TrochoidSpec, SpiralSpec, HelicalBoringSpec, PocketSpec>;

//! One job: which cycle, with which tool, in which material, on which machine.
struct CycleSpec {
  std::string cycle;                      //!< "corner" | "trochoid" | "spiral" | "helical_boring" | "pocket"
  geometry::Tool tool;                    //!< the end mill
  std::string material;                   //!< workpiece material name, e.g. "S50C" ("" when not given)
  double spindle_rpm = 0.0;               //!< spindle speed, rev/min (0 = not given)
  double axial_depth_mm = 0.0;            //!< axial depth of cut A_d of corner, trochoid and spiral, mm (0 for
                                          //!< helical boring and pocket, which use their own depth_mm)
  double target_force_n = 0.0;            //!< cutting force to hold, N (0 = not given)
  //! The constant feed a CAM programmer would program for this cycle, mm/min (unset: not given): the
  //! baseline a plan's time saving is quoted against; in the machine's feed range.
  std::optional<double> feed_mm_per_min;
  geometry::MachineLimits machine;        //!< machine limits
  double clearance_z_mm = 5.0;            //!< rapid height above the stock top, mm (≥ 1)
  std::optional<geometry::Stock> stock;   //!< user-given stock; unset: the stock the cycle implies
  CycleGeometry geometry;                 //!< the cycle's own parameters; its type matches `cycle`
};

//! The name of the cycle whose parameters `geometry` holds ("corner", "trochoid", ...).
const char* cycle_name(const CycleGeometry& geometry);

}  // namespace feedplan::cycles
