#pragma once
// A generated cycle — the tool-centre path and the material it starts from — and the dispatch from a
// spec to the generator of its cycle.
//
// Heights every generator shares: the path starts at `clearance_z_mm` above the stock top, rapids
// down to kFeedPlaneAboveTopMm above the top (the R plane of canned drilling cycles), feeds from
// there, and ends with a rapid back up to the clearance height. 2.5D cuts are one layer at
// top − axial depth.

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/spec.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::cycles {

//! Height above the stock top at which rapids stop and feed moves begin, mm.
inline constexpr double kFeedPlaneAboveTopMm = 1.0;

//! Margin of implied stock below the deepest cut, mm.
inline constexpr double kStockBelowCutMm = 5.0;

//! The heights a generator works between.
struct ZLevels {
  double top_z_mm = 0.0;        //!< top face of the stock; depths are measured down from here, mm
  double clearance_z_mm = 5.0;  //!< rapid height above top_z_mm, mm (≥ kFeedPlaneAboveTopMm)
};

//! A generated cycle.
struct Cycle {
  geometry::ToolPath path;         //!< tool-centre path; consistency_defects(path) is empty
  geometry::Stock stock;           //!< the material before the cycle (implied by the cycle or given by the spec)
  geometry::Tool tool;             //!< the tool the path is for
  std::vector<std::string> notes;  //!< adjustments the generator made, e.g. "spiral pitch reduced from
                                   //!< 1.1 to 1 mm to end on the final radius (8 turns)"
};

//! Checks the tool on its own: diameter finite and > 0, flutes in [1, 32], helix angle in [0, 60) deg, and a
//! plunge feed per tooth of its own (max_plunge_feed_per_tooth_mm ≠ 0; 0 is the default) in (0, diameter].
//! Every problem's field starts with `field`.
std::vector<InputProblem> validate_tool(const geometry::Tool& tool, const std::string& field = "tool");

//! Checks everything in `spec` a generator relies on: the tool, the machine limits, the cutting
//! conditions, the clearance, the cycle's own parameters (through that generator's validate), a
//! `cycle` name that matches the geometry held, and the stock (geometry::validate). Returns every
//! problem found, each with the field path as YAML would spell it ("trochoid.pitch_mm") and a message
//! naming the value, the allowed range and why; empty when the spec can be generated.
std::vector<InputProblem> validate(const CycleSpec& spec);

//! Generates the cycle `spec` describes, with the stock the spec gives or, without one, the stock the
//! cycle implies. Throws InputError with every problem validate(spec) finds (a spec from
//! read_cycle_spec has none). The returned path is consistent (geometry::consistency_defects is empty).
Cycle generate(const CycleSpec& spec);

}  // namespace feedplan::cycles
