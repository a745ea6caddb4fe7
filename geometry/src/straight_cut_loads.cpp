#include "feedplan/geometry/straight_cut_loads.hpp"

#include "feedplan/geometry/chip_load.hpp"

namespace feedplan::geometry {

double StraightCutLoads::peak_mm(double engagement_rad, double depth_mm) {
  const auto key = std::make_pair(engagement_rad, depth_mm);
  {
    const std::lock_guard lock(mutex_);
    if (const auto it = known_.find(key); it != known_.end()) return it->second;
  }
  const double peak = straight_cut_chip_load_mm(engagement_rad, depth_mm, tool_);
  const std::lock_guard lock(mutex_);
  known_.emplace(key, peak);
  return peak;
}

}  // namespace feedplan::geometry
