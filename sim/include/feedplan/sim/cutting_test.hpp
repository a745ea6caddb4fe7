#pragma once
// A virtual cutting test: the straight cut a process engineer runs on a dynamometer to identify a
// force model — constant radial depth, axial depth, feed and spindle speed — as a Program and the
// stock it cuts, so the model database can be filled without a machine.

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::sim {

//! Which side of the tool the material is on.
enum class MillingMode {
  kDown,  //!< climb milling: material on the right of the feed (M3), teeth exit at the finished wall
  kUp,    //!< conventional milling: material on the left, teeth enter at the finished wall
};

//! A straight cut at constant conditions.
struct CuttingTest {
  double radial_depth_mm = 1.5;     //!< a_e: radial depth of cut, mm (a full slot when ≥ the diameter)
  double axial_depth_mm = 10.0;     //!< a_p: axial depth of cut, mm
  double feed_mm_per_min = 1000.0;  //!< programmed feed F, mm/min
  double spindle_rpm = 2800.0;      //!< spindle speed S, rev/min
  double cut_length_mm = 40.0;      //!< length of the workpiece along the feed, mm
  MillingMode mode = MillingMode::kDown;  //!< down (climb) or up (conventional) milling
};

//! The program and stock of a cutting test.
struct CuttingTestSetup {
  geometry::Program program;  //!< rapid to the start beside the block, one G1 through it, rapid up
  geometry::Stock stock;      //!< the block: x in [0, cut_length], the cut a_e deep into its side
};

//! Checks the test's fields ("cutting_test.radial_depth_mm", …): all finite and positive, a_e at most
//! the tool diameter, a cut length of at least two tool diameters (so there is a steady stretch).
std::vector<InputProblem> validate(const CuttingTest& test, const geometry::Tool& tool);

//! Builds the cut along +X at tip z = −a_p below the block's top face z = 0, entering the block at
//! x = 0 and leaving it at x = cut_length:
//!   1. rapid from (−r − 5, 0, 5) down to (−r − 5, 0, −a_p), clear of the block;
//!   2. feed at F to (cut_length + r + 5, 0, −a_p) with the spindle at S (M3);
//!   3. rapid up to z = 5.
//! Down milling puts the material at y < 0 (the finished wall at y = −r), up milling at y > 0.
//! Throws InputError with validate's problems.
CuttingTestSetup make_cutting_test(const CuttingTest& test, const geometry::Tool& tool);

}  // namespace feedplan::sim
