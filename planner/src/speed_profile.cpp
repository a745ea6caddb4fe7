#include "feedplan/planner/speed_profile.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace feedplan::planner {

std::vector<double> greatest_speeds(const std::vector<double>& s, const std::vector<double>& cap, double accel) {
  assert(s.size() == cap.size());
  assert(accel > 0.0);
  const std::size_t n = s.size();
  std::vector<double> u(n);
  for (std::size_t i = 0; i < n; ++i) {
    assert(cap[i] >= 0.0);
    u[i] = cap[i] * cap[i];
  }
  for (std::size_t i = 0; i + 1 < n; ++i) {
    assert(s[i + 1] >= s[i]);
    u[i + 1] = std::min(u[i + 1], u[i] + 2.0 * accel * (s[i + 1] - s[i]));
  }
  for (std::size_t i = n; i-- > 1;) u[i - 1] = std::min(u[i - 1], u[i] + 2.0 * accel * (s[i] - s[i - 1]));
  for (double& value : u) value = std::sqrt(value);
  return u;
}

double interval_time(double ds, double v0, double v1, double cap, double accel) {
  if (ds <= 0.0) return 0.0;
  assert(accel > 0.0);
  // Peak speed of the triangle through v0 and v1 over ds, limited by the cap.
  const double peak = std::min(cap, std::sqrt(0.5 * (v0 * v0 + v1 * v1) + accel * ds));
  if (!(peak > 0.0)) return std::numeric_limits<double>::infinity();
  const double up_s = std::max(0.0, (peak * peak - v0 * v0) / (2.0 * accel));
  const double down_s = std::max(0.0, (peak * peak - v1 * v1) / (2.0 * accel));
  const double cruise_s = std::max(0.0, ds - up_s - down_s);
  return std::max(0.0, peak - v0) / accel + std::max(0.0, peak - v1) / accel + cruise_s / peak;
}

}  // namespace feedplan::planner
