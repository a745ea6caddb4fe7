#include "revolution_signals.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace feedplan::model_db::detail {

RevolutionSignals revolution_signals(const force_log::ForceLog& log, const std::vector<force_log::RevolutionPeak>& peaks) {
  RevolutionSignals signals;
  const auto& rows = log.rows;
  auto first_at = [&](double t) {
    return static_cast<std::size_t>(
        std::lower_bound(rows.begin(), rows.end(), t, [](const force_log::ForceLogRow& r, double v) { return r.t_s < v; }) -
        rows.begin());
  };
  for (const auto& peak : peaks) {
    const std::size_t i0 = first_at(peak.t_start_s);
    const std::size_t i1 = first_at(peak.t_end_s);
    double feed_sum = 0.0, rpm_sum = 0.0;
    int feed_count = 0, rpm_count = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      if (std::isfinite(rows[i].feed_mm_per_min)) {
        feed_sum += rows[i].feed_mm_per_min;
        ++feed_count;
      }
      if (std::isfinite(rows[i].spindle_rpm)) {
        rpm_sum += rows[i].spindle_rpm;
        ++rpm_count;
      }
    }
    signals.feed_column_mm_per_min.push_back(feed_count > 0 ? feed_sum / feed_count : std::nan(""));
    signals.spindle_rpm.push_back(rpm_count > 0 ? rpm_sum / rpm_count : std::nan(""));
    double feed_positions = std::nan("");
    if (log.has_positions && i1 >= i0 + 2) {
      const force_log::ForceLogRow& a = rows[i0];
      const force_log::ForceLogRow& b = rows[i1 - 1];
      const double distance_mm = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
      if (std::isfinite(distance_mm) && b.t_s > a.t_s) feed_positions = distance_mm / (b.t_s - a.t_s) * 60.0;
    }
    signals.feed_positions_mm_per_min.push_back(feed_positions);
  }
  return signals;
}

}  // namespace feedplan::model_db::detail
