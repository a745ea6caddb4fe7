#pragma once
// Constant-feed programs on the virtual machine: the baselines a planned program's time saving is
// quoted against when it was run there too (`feedplan plan --simulate`) — the spec's own feed, and the
// constant feed whose simulated largest per-revolution peak equals the plan's (the program a CAM
// programmer would need to cut as safely as the plan did, found by running it).

#include <string>
#include <vector>

#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/trial/virtual_machine_run.hpp"

namespace feedplan::trial {

//! Relative distance of the simulated peak from the peak sought at which the search stops.
inline constexpr double kEqualPeakTolerance = 0.01;
//! Most runs of the virtual machine the search makes.
inline constexpr int kEqualPeakMaxRuns = 8;

//! One constant-feed program run on the virtual machine.
struct ConstantFeedRun {
  double feed_mm_per_min = 0.0;  //!< F on every feed move, mm/min
  double cycle_time_s = 0.0;     //!< simulated cycle time, s
  double max_peak_n = 0.0;       //!< largest per-revolution peak |F_xy| of the true force, N
};

//! Runs planner::constant_feed_program(path, feed, machine.spindle_rpm) on `machine` (the program as
//! moves, not through G-code text: one F per move loses nothing in the writer). Throws InputError when
//! the virtual machine refuses the request.
ConstantFeedRun run_constant_feed(const VirtualMachine& machine, const geometry::ToolPath& path, double feed_mm_per_min);

//! The constant feed with a given simulated peak, and how it was found.
struct EqualPeakFeed {
  ConstantFeedRun run;                //!< the run whose peak is closest to the one sought
  std::vector<ConstantFeedRun> runs;  //!< every run made or given, in order
  bool converged = false;             //!< run.max_peak_n within kEqualPeakTolerance of the peak sought
  std::string method;                 //!< how it was found, in words
};

//! Searches the feed in the machine's range [min_feed, max_feed] whose constant-feed program peaks at
//! `peak_n` on `machine`: starting from `known` runs (e.g. the spec's feed, already simulated) or else at
//! `start_feed_mm_per_min`, a secant step on log peak against log F (the peak grows like a power of the
//! feed), kept inside the bracket once there is one (geometric bisection when the step leaves it), until
//! the peak is within kEqualPeakTolerance or kEqualPeakMaxRuns runs were made, or the range's end is
//! reached (then that end, not converged, and the method says so). Needs peak_n > 0.
EqualPeakFeed equal_peak_constant_feed(const VirtualMachine& machine, const geometry::ToolPath& path, double peak_n,
                                       double start_feed_mm_per_min, const std::vector<ConstantFeedRun>& known = {});

}  // namespace feedplan::trial
