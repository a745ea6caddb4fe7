#pragma once
// The reader of Kistler DynoWare exports: a "DynoWare,Version ..." line, a header block of
// "key:,value" lines, the channel row (Time,Fx,Fy,Fz,...), the units row, then samples. Internal to
// the force_log module; read_force_log() picks the reader.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/force_log/force_log.hpp"

namespace feedplan::force_log::detail {

// Reads the export in `lines` (without terminators); `lines[start]` is the "DynoWare,Version ..."
// line. Time, Fx, Fy are required, Fz optional, other channels ignored; forces in kN become N.
// Throws InputError naming the line, the column, the value and what was expected.
ForceLog read_kistler_dynoware(const std::vector<std::string_view>& lines, std::size_t start,
                               const std::string& source_name);

}  // namespace feedplan::force_log::detail
