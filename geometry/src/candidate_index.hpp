#pragma once
// Which earlier swept pieces can touch the tool while it travels a given piece: pairs of pieces
// whose bounding boxes (grown by the tool and sweep radii) overlap, found with CGAL's
// box-intersection algorithm in O(n log n + pairs). Internal to geometry.

#include <cstdint>
#include <vector>

#include "swept_piece.hpp"

namespace feedplan::geometry::detail {

//! For each piece i ≥ first_query, the indices j < i of pieces whose grown boxes overlap piece i's
//! grown box, most recent first. Pieces are in chronological order.
std::vector<std::vector<std::uint32_t>> earlier_candidates(const std::vector<SweptPiece>& pieces,
                                                           double tool_radius_mm, std::size_t first_query);

}  // namespace feedplan::geometry::detail
