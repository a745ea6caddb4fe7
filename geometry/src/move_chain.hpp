#pragma once
// Consecutive moves that continue one another — one line or arc written as several blocks, as a plan
// splits a move wherever its feed changes — joined back into one move. The engagement then cuts the
// swept region into as few pieces as the move itself needs: a tool behind a sample is one piece, not
// the dozens of short blocks it was written as. Internal to geometry.

#include <cstddef>
#include <vector>

#include "feedplan/geometry/move.hpp"

namespace feedplan::geometry::detail {

//! Where a move of the path lies on its chain: fraction f of the move is fraction
//! start + f · share of the chain's joined move.
struct ChainPlace {
  std::size_t chain = 0;
  double start = 0.0;
  double share = 1.0;
};

//! The path's moves joined into chains, and every move's place on its chain.
struct MoveChains {
  std::vector<Move> joined;         //!< one move per chain
  std::vector<ChainPlace> places;   //!< one per move of the path
};

//! True when `next` continues `move`: the same kind and flags, starting where `move` ends, on the same
//! line (same direction) or the same circle (centre, radius, turn and pitch).
bool continues(const Move& move, const Move& next);

//! Joins every run of moves that continue one another.
MoveChains join_continuations(const std::vector<Move>& moves);

}  // namespace feedplan::geometry::detail
