#pragma once
// The reader of feedplan's own force-log CSV ("# key: value" metadata, a header row of column
// names, one row per sample). Internal to the force_log module; read_force_log() picks the reader.

#include <string>
#include <string_view>
#include <vector>

#include "feedplan/force_log/force_log.hpp"

namespace feedplan::force_log::detail {

// Reads the log in `lines` (without terminators). Throws InputError naming the line, the column,
// the value and what was expected for every problem (at most kMaxProblems).
ForceLog read_feedplan_csv(const std::vector<std::string_view>& lines, const std::string& source_name);

}  // namespace feedplan::force_log::detail
