#include "feedplan/force_log/logged_spindle_speed.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

namespace feedplan::force_log {

double logged_spindle_rpm(const ForceLog& log) {
  std::vector<double> rpm;
  for (const auto& row : log.rows) {
    if (std::isfinite(row.spindle_rpm) && row.spindle_rpm > 0.0) rpm.push_back(row.spindle_rpm);
  }
  if (!rpm.empty()) {
    std::nth_element(rpm.begin(), rpm.begin() + static_cast<long>(rpm.size() / 2), rpm.end());
    return rpm[rpm.size() / 2];
  }
  try {
    const double value = std::stod(log.metadata_value("spindle_rpm"));
    if (std::isfinite(value) && value > 0.0) return value;
  } catch (const std::exception&) {
  }
  return 0.0;
}

}  // namespace feedplan::force_log
