#pragma once
// The peak chip loads of straight cuts with one tool, remembered: a plan asks for the straight cut with
// the same t_m as each of its samples (planner/feed_limit.hpp), the samples of a repeated feature (every
// loop of a trochoid, every pass of a pocket) ask for the same ones again, and so does every re-plan of
// the same path. Safe to share between threads.

#include <map>
#include <mutex>
#include <utility>

#include "feedplan/geometry/tool.hpp"

namespace feedplan::geometry {

class StraightCutLoads {
 public:
  //! Keeps a copy of `tool`.
  explicit StraightCutLoads(const Tool& tool) : tool_(tool) {}

  //! straight_cut_chip_load_mm(engagement_rad, depth_mm, tool) (chip_load.hpp): the same value, computed
  //! once per (engagement_rad, depth_mm).
  double peak_mm(double engagement_rad, double depth_mm);

  const Tool& tool() const { return tool_; }

 private:
  Tool tool_;
  std::mutex mutex_;
  std::map<std::pair<double, double>, double> known_;
};

}  // namespace feedplan::geometry
