#pragma once
// A straight full-width slot through a block whose axial depth steps through a list of depths — the
// experiment seeds 000/001/002/004 judge their force controllers on (a cut whose process gain jumps while
// the controller runs), generalising the slot of tests/trial/override_control_test.cpp. The motion, tool
// centre on y = 0, R the tool radius, L the held length:
//   1. rapid to x = −R − 1 mm (the tool clear of the block's face at x = 0), spindle on;
//   2. rapid down to the first depth, in the air;
//   3. feed to x = L: the first depth, the slot full from x = 0 on;
//   4. for every further depth: a ramp to it over max(2 mm, 2 × the depth change) along x, then L held;
//   5. feed out of the block, whose end is R past the last held length's end, to R + 1 mm beyond it;
//   6. rapid up to the clearance, spindle off.
// Each depth's steady window is the second half of its held length: the first half is left to the entry
// or the step's transient (about a second at the papers' feeds).

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::trial {

//! What the slot is made from.
struct DepthStepSlotRequest {
  geometry::Tool tool;             //!< the end mill (its diameter bounds the depths)
  std::vector<double> depths_mm;   //!< the axial depths in order, mm (at least 2; each finite, in (0, diameter])
  double step_length_mm = 30.0;    //!< each depth held for this, mm (finite, > tool diameter)
  double feed_mm_per_min = 0.0;    //!< the programmed feed, mm/min (finite, > 0)
  double spindle_rpm = 0.0;        //!< the programmed S, rev/min (finite, > 0)
  double clearance_z_mm = 5.0;     //!< rapid height above the block, mm (finite, > 0)
};

//! One depth's held length, along the tool centre's x.
struct DepthSegment {
  double depth_mm = 0.0;        //!< the axial depth, mm
  double start_x_mm = 0.0;      //!< where the depth is first held, mm
  double end_x_mm = 0.0;        //!< where the ramp to the next depth (or the exit) starts, mm
  double steady_from_x_mm = 0.0;  //!< start of the steady window (the held length's second half), mm
};

//! The slot: its program (as G-code text and read back, as a machine receives it), the block, the depths.
struct DepthStepSlot {
  std::string gcode;              //!< the program's text (steps 1–6 of the file comment)
  geometry::Program program;      //!< the text read back
  geometry::Stock stock;          //!< the block: x from 0 to the last end + R, y ± (R + 10 mm), below z = 0
  std::vector<DepthSegment> segments;  //!< one per depth, in order
};

//! Every problem with the request, each named "<field_prefix><field>" with its value and the rule
//! ("depth_step.depths_mm[1] = 12: must be finite and in (0, 10] — the tool's diameter"). Empty when usable.
std::vector<InputProblem> validate(const DepthStepSlotRequest& request, const std::string& field_prefix = "depth_step.");

//! The slot of the file comment. Throws InputError with validate()'s problems.
DepthStepSlot make_depth_step_slot(const DepthStepSlotRequest& request);

}  // namespace feedplan::trial
