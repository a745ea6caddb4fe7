#pragma once
// How the planner expects a CNC to run a program (the controller model of feed_plan.hpp): on the
// engagement samples as nodes, each interval between two nodes runs at most at its cap (the block's F,
// the centripetal limit, the rapid rate), the speed changes at most at the acceleration limit with
// look-ahead over everything, and the machine stops where a node is marked as a stop.

#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! The predicted run.
struct ControllerRun {
  std::vector<double> speed_mm_per_s;  //!< path speed at each node, mm/s
  std::vector<double> time_s;          //!< time at each node from the start, s
  double cycle_time_s = 0.0;           //!< time at the last node, s
  double cutting_time_s = 0.0;         //!< time on intervals of cutting moves, s
  double air_time_s = 0.0;             //!< time on every other interval, s
};

//! Where the controller stops on `path` sampled as `engagement`: the first and last node, nodes where a
//! rapid and a feed move meet, and move junctions whose 3D tangent turns by more than
//! kTangentJunctionToleranceRad. One flag per engagement sample.
std::vector<bool> controller_stops(const geometry::ToolPath& path, const geometry::EngagementProfile& engagement);

//! Centripetal speed cap √(a R) of interval j's move (infinity for lines and rapids), mm/s, one per
//! interval (engagement.samples.size() − 1 values); R is the arc's XY radius (conservative on helices).
std::vector<double> centripetal_caps_mm_per_s(const geometry::ToolPath& path,
                                              const geometry::EngagementProfile& engagement, double accel_mm_per_s2);

//! Runs the controller model: interval_cap_mm_per_s has one cap per interval (nodes − 1 values, each
//! > 0), stops one flag per node, interval_cutting whether interval j is on a cutting move. Returns
//! speeds and times (asserted sizes).
ControllerRun run_controller(const std::vector<double>& s_mm, const std::vector<double>& interval_cap_mm_per_s,
                             const std::vector<bool>& stops, const std::vector<bool>& interval_cutting,
                             double accel_mm_per_s2);

}  // namespace feedplan::planner
