#pragma once
// The columns of the feedplan force-log CSV: their names, the decimals the writer gives them and
// the ForceLogRow field each one holds. Internal to the force_log module.

#include <array>

#include "feedplan/force_log/force_log.hpp"

namespace feedplan::force_log::detail {

// The columns of our format, in the order the writer puts them.
enum Column { kT, kX, kY, kZ, kFx, kFy, kFz, kFeed, kRpm, kIx, kIy, kIz, kColumnCount };
inline const std::array<const char*, kColumnCount> kColumnNames = {
    "t_s", "x_mm", "y_mm", "z_mm", "fx_n", "fy_n", "fz_n", "feed_mm_per_min", "spindle_rpm", "ix_a", "iy_a", "iz_a"};
inline constexpr std::array<int, kColumnCount> kDecimals = {6, 4, 4, 4, 3, 3, 3, 2, 1, 5, 5, 5};

// The field of `row` that holds `column` (const or not, as `row` is).
template <typename Row>
auto& cell_of(Row& row, int column) {
  switch (column) {
    case kT: return row.t_s;
    case kX: return row.x_mm;
    case kY: return row.y_mm;
    case kZ: return row.z_mm;
    case kFx: return row.fx_n;
    case kFy: return row.fy_n;
    case kFz: return row.fz_n;
    case kFeed: return row.feed_mm_per_min;
    case kRpm: return row.spindle_rpm;
    case kIx: return row.ix_a;
    case kIy: return row.iy_a;
    default: return row.iz_a;
  }
}

}  // namespace feedplan::force_log::detail
