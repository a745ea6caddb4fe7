#pragma once
// A force log's samples must be in time order. Internal to the force_log module.

#include <cstddef>
#include <vector>

#include "feedplan/force_log/force_log.hpp"
#include "log_problems.hpp"

namespace feedplan::force_log::detail {

// Reports rows whose time does not increase; `lines[i]` is the 1-based line of `rows[i]`. Rows
// without a time (NaN) are skipped.
void check_time_order(Problems& problems, const std::vector<ForceLogRow>& rows, const std::vector<std::size_t>& lines);

}  // namespace feedplan::force_log::detail
