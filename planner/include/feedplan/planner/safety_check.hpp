#pragma once
// The safety check every plan passes before it may be called ok: from the written program alone — its
// moves and their F words — and the stock it cuts, re-derive where the tool is in material and what feed
// its engagement there allows, and name every place a feed move runs faster, or a rapid meets material.
//
// It shares none of the planner's bookkeeping (sample limits, blocks' smallest limits, the command
// profile): it cuts the program's own moves on the stock again (geometry::compute_engagement, every
// layer from the tip to the stock top), at its own samples, and evaluates the force model there as the
// planner's rule says (feed_limit.hpp), with the plunge limit of the tool. The invariants:
//   1. no rapid (G0) meets material;
//   2. a feed move that meets material on any layer — whatever the path called it (air, entry, plunge,
//      ramp, helix) — runs at most at the feed the force model allows there at the target (the minimum
//      feed of the machine where no feed meets the target, which the plan reports as target not met);
//   3. a feed move that descends into material — with its circle, or with its end face onto material
//      the circle does not reach (geometry::EngagementSample::end_face_in_material) — runs at most at
//      the tool's plunge feed per tooth;
//   4. an engagement that cannot be computed (not a number) is a violation, never air.
// A move straight up (no XY travel) removes nothing — the tool body already fills the space it climbs
// through — so a retract that still touches the wall it has just cut is not a rapid in material.
// The planner's samples and the check's lie at different places along a move, and the limit changes
// between them: a feed above the limit by no more than `relative_tolerance` is not reported.

#include <vector>

#include "feedplan/geometry/point.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! What the check looks at besides the program.
struct SafetyCheckInput {
  const geometry::Stock* stock = nullptr;  //!< the material before the program
  const geometry::Tool* tool = nullptr;    //!< the end mill
  const PlanSettings* settings = nullptr;  //!< model, target, spindle, machine, uncertainty, correction
  //! Arc length of every engagement sample the settings' force_correction belongs to (the plan's), mm;
  //! the correction at a place between two of them is the larger of the two. Empty: no correction.
  std::vector<double> correction_s_mm;
  double ds_mm = 0.05;                 //!< spacing of the check's samples, mm (> 0)
  //! Optional: the planner's engagement and the chip-load ratio it computed at each of its samples. A
  //! check sample at a planner sample's place whose own engagement there is the same (every layer and
  //! engaged set to 1e-9) takes that ratio instead of computing it again: the same function of inputs
  //! the check derived itself. Null (or a mismatch anywhere): computed.
  const geometry::EngagementProfile* planned_engagement = nullptr;
  const std::vector<double>* planned_load_ratio = nullptr;
  double relative_tolerance = 0.01;    //!< a feed this much above the limit is not reported
};

//! Why a place is unsafe.
enum class SafetyProblem {
  kRapidInMaterial,     //!< a rapid (G0) meets material
  kAboveForceLimit,     //!< F above the feed the force model allows at the target
  kAbovePlungeLimit,    //!< F above the tool's plunge feed per tooth while descending into material
  kEngagementUnknown,   //!< the engagement could not be computed (not a number)
};

//! "rapid through material", "above the force limit", "above the plunge limit", "engagement unknown".
std::string to_string(SafetyProblem problem);

//! The worst place of one program move that breaks an invariant.
struct SafetyViolation {
  SafetyProblem problem = SafetyProblem::kAboveForceLimit;  //!< which invariant
  int move_index = 0;                      //!< index of the move in the program (program.path.moves)
  int source_line = 0;                     //!< the move's line in the program text when known (else 0)
  double s_mm = 0.0;                       //!< arc length along the program, mm
  geometry::Point3 position;               //!< tool tip there, mm
  double feed_mm_per_min = 0.0;            //!< the move's F (the rapid rate on rapids), mm/min
  double allowed_mm_per_min = 0.0;         //!< the largest feed the engagement allows there, mm/min
  double engagement_rad = 0.0;             //!< engaged angle on the lowest layer there, rad
  double material_height_mm = 0.0;         //!< height of material in contact above the tip, mm
};

//! The check's samples along the program with the feed their engagement allows.
struct AllowedFeed {
  double s_mm = 0.0;                 //!< arc length along the program, mm
  int move_index = 0;                //!< program move the sample belongs to
  //! The largest feed allowed there, mm/min: the smaller of the force and plunge limits where the tool
  //! meets material; +∞ where it does not; 0 where no feed is safe (a rapid in material, an unknown
  //! engagement).
  double mm_per_min = 0.0;
};

//! What check_safety finds.
struct SafetyCheck {
  //! Every program move that breaks an invariant, with its worst place (the largest F / allowed), in
  //! program order; empty when the program is safe.
  std::vector<SafetyViolation> violations;
  std::vector<AllowedFeed> allowed;  //!< every sample of the check, in program order
};

//! Checks `program` (file comment). Requires the input's pointers set and a consistent program path
//! (asserted: plan() and tests call it on programs they made).
SafetyCheck check_safety(const geometry::Program& program, const SafetyCheckInput& input);

//! One sentence naming the violation: the move, its line when known, s, x, y, z, F and the limit.
std::string describe(const SafetyViolation& violation);

}  // namespace feedplan::planner
