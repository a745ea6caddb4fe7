#include "feedplan/planner/controller_model.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "feedplan/planner/speed_profile.hpp"

namespace feedplan::planner {
namespace {

using Vec3 = std::array<double, 3>;

// Unit tangent in space at `fraction` of a move (direction of travel).
Vec3 unit_tangent(const geometry::Move& move, double fraction) {
  Vec3 t{};
  if (move.kind == geometry::MoveKind::kArc) {
    const double xy_angle = geometry::tangent_angle_rad(move, fraction);
    const double xy_length = geometry::xy_length_mm(move);
    const double dz = move.end.z_mm - move.start.z_mm;
    const double norm = std::hypot(xy_length, dz);
    t = {std::cos(xy_angle) * xy_length / norm, std::sin(xy_angle) * xy_length / norm, dz / norm};
  } else {
    t = {move.end.x_mm - move.start.x_mm, move.end.y_mm - move.start.y_mm, move.end.z_mm - move.start.z_mm};
    const double norm = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (double& c : t) c /= norm;
  }
  return t;
}

double turn_angle_rad(const Vec3& a, const Vec3& b) {
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const Vec3 cross{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  return std::atan2(std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]), dot);
}

}  // namespace

std::vector<bool> controller_stops(const geometry::ToolPath& path, const geometry::EngagementProfile& engagement) {
  const auto& samples = engagement.samples;
  std::vector<bool> stops(samples.size(), false);
  if (samples.empty()) return stops;
  stops.front() = true;
  stops.back() = true;
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {
    const int m1 = samples[i].move_index;
    const int m0 = samples[i - 1].move_index;
    if (m0 == m1) continue;
    const geometry::Move& before = path.moves[static_cast<std::size_t>(m0)];
    const geometry::Move& after = path.moves[static_cast<std::size_t>(m1)];
    const bool rapid_before = before.kind == geometry::MoveKind::kRapid;
    const bool rapid_after = after.kind == geometry::MoveKind::kRapid;
    if (rapid_before != rapid_after) {
      stops[i] = true;
      continue;
    }
    if (turn_angle_rad(unit_tangent(before, 1.0), unit_tangent(after, 0.0)) > kTangentJunctionToleranceRad) {
      stops[i] = true;
    }
  }
  return stops;
}

std::vector<double> centripetal_caps_mm_per_s(const geometry::ToolPath& path,
                                              const geometry::EngagementProfile& engagement, double accel_mm_per_s2) {
  const auto& samples = engagement.samples;
  std::vector<double> caps(samples.empty() ? 0 : samples.size() - 1, std::numeric_limits<double>::infinity());
  for (std::size_t j = 0; j + 1 < samples.size(); ++j) {
    const geometry::Move& move = path.moves[static_cast<std::size_t>(samples[j].move_index)];
    if (move.kind == geometry::MoveKind::kArc) caps[j] = std::sqrt(accel_mm_per_s2 * geometry::arc_radius_mm(move));
  }
  return caps;
}

ControllerRun run_controller(const std::vector<double>& s_mm, const std::vector<double>& interval_cap_mm_per_s,
                             const std::vector<bool>& stops, const std::vector<bool>& interval_cutting,
                             double accel_mm_per_s2) {
  const std::size_t n = s_mm.size();
  assert(stops.size() == n);
  assert(n == 0 || interval_cap_mm_per_s.size() == n - 1);
  assert(interval_cutting.size() == interval_cap_mm_per_s.size());
  ControllerRun run;
  if (n == 0) return run;
  std::vector<double> node_cap(n, std::numeric_limits<double>::infinity());
  for (std::size_t j = 0; j + 1 < n; ++j) {
    node_cap[j] = std::min(node_cap[j], interval_cap_mm_per_s[j]);
    node_cap[j + 1] = std::min(node_cap[j + 1], interval_cap_mm_per_s[j]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (stops[i]) node_cap[i] = 0.0;
  }
  run.speed_mm_per_s = greatest_speeds(s_mm, node_cap, accel_mm_per_s2);
  run.time_s.assign(n, 0.0);
  for (std::size_t j = 0; j + 1 < n; ++j) {
    const double dt = interval_time(s_mm[j + 1] - s_mm[j], run.speed_mm_per_s[j], run.speed_mm_per_s[j + 1],
                                    interval_cap_mm_per_s[j], accel_mm_per_s2);
    run.time_s[j + 1] = run.time_s[j] + dt;
    (interval_cutting[j] ? run.cutting_time_s : run.air_time_s) += dt;
  }
  run.cycle_time_s = run.time_s.back();
  return run;
}

}  // namespace feedplan::planner
