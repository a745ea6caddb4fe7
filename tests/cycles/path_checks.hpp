#pragma once
// Small geometric helpers the cycle tests share: angle differences, moves of a named part, and
// tangent continuity between consecutive feed moves.

#include <cmath>
#include <string>
#include <vector>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::cycles::testing {

//! a − b wrapped into (−π, π].
inline double angle_difference_rad(double a, double b) {
  double d = std::fmod(a - b, kTwoPi);
  if (d <= -kPi) d += kTwoPi;
  if (d > kPi) d -= kTwoPi;
  return d;
}

//! Indices of the moves whose part is called `name`.
inline std::vector<std::size_t> moves_of(const geometry::ToolPath& path, const std::string& name) {
  std::vector<std::size_t> result;
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    if (path.part_names[path.moves[i].part] == name) result.push_back(i);
  }
  return result;
}

//! Names of the parts in the order of their first move.
inline std::vector<std::string> part_order(const geometry::ToolPath& path) {
  std::vector<std::string> names;
  for (const auto& move : path.moves) {
    const std::string& name = path.part_names[move.part];
    if (names.empty() || names.back() != name) names.push_back(name);
  }
  return names;
}

//! Largest change of travel direction between consecutive cutting moves, rad.
inline double max_kink_between_cutting_moves_rad(const geometry::ToolPath& path) {
  double worst = 0;
  for (std::size_t i = 1; i < path.moves.size(); ++i) {
    const auto& a = path.moves[i - 1];
    const auto& b = path.moves[i];
    if (!a.cutting || !b.cutting) continue;
    worst = std::max(worst, std::abs(angle_difference_rad(geometry::tangent_angle_rad(a, 1.0),
                                                          geometry::tangent_angle_rad(b, 0.0))));
  }
  return worst;
}

}  // namespace feedplan::cycles::testing
