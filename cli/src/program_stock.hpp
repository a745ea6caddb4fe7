#pragma once
// The stock a G-code program is cut from when no cycle spec says (`simulate`, `control`): --stock, else a
// solid block around the program.

#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/stock.hpp"

namespace feedplan::cli {

//! A solid block around every feed move, grown by four tool radii, from 5 mm below the lowest feed move up
//! to z = 0 — what a program with no stock given is assumed to cut (the worst case: full material).
geometry::Stock default_stock(const geometry::Program& program, double tool_radius_mm);

//! The note a command prints when it assumes default_stock().
inline constexpr const char* kDefaultStockNote =
    "no --stock given: assuming a solid block around the program's feed moves below z = 0 "
    "(every feed move below z = 0 cuts full material)";

}  // namespace feedplan::cli
