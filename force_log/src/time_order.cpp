#include "time_order.hpp"

#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"

namespace feedplan::force_log::detail {

void check_time_order(Problems& problems, const std::vector<ForceLogRow>& rows, const std::vector<std::size_t>& lines) {
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (std::isnan(rows[i].t_s) || std::isnan(rows[i - 1].t_s) || rows[i].t_s > rows[i - 1].t_s) continue;
    problems.add(lines[i], "t_s",
                 "= " + shortest_number_text(rows[i].t_s) + ": must be after " + shortest_number_text(rows[i - 1].t_s) +
                     " on line " + std::to_string(lines[i - 1]) + " — time must increase from row to row");
  }
}

}  // namespace feedplan::force_log::detail
