#include "candidate_index.hpp"

#include <CGAL/Box_intersection_d/Box_with_info_d.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <functional>

namespace feedplan::geometry::detail {

std::vector<std::vector<std::uint32_t>> earlier_candidates(const std::vector<SweptPiece>& pieces,
                                                           double tool_radius_mm, std::size_t first_query) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::uint32_t,
                                                         CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<Box> boxes;
  boxes.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const SweptPiece& p = pieces[i];
    // Grow by the larger of the two radii so a tool of tool_radius_mm on one piece and the sweep
    // of the other are both covered (conservative when the radii differ).
    const double grow = std::max(p.sweep_radius_mm, tool_radius_mm);
    double lo[2] = {p.box_min.x - grow, p.box_min.y - grow};
    double hi[2] = {p.box_max.x + grow, p.box_max.y + grow};
    boxes.emplace_back(lo, hi, static_cast<std::uint32_t>(i));
  }
  std::vector<std::vector<std::uint32_t>> candidates(pieces.size());
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(
      boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
        const std::uint32_t later = std::max(a.info(), b.info());
        const std::uint32_t earlier = std::min(a.info(), b.info());
        if (later >= first_query) candidates[later].push_back(earlier);
      });
  for (auto& list : candidates) std::sort(list.begin(), list.end(), std::greater<>());
  return candidates;
}

}  // namespace feedplan::geometry::detail
