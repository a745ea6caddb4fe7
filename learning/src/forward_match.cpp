#include "forward_match.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "log_rows.hpp"

namespace feedplan::learning::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The row's place on the path at or after segment `k_min`: the local minima of the distance over the
// segments within reach, taken in path order; among those within a short stretch after the first one
// the nearest sets the bar, and the first minimum within `tie_mm` of it wins. So a crossing of the path
// far ahead (the next trochoid loop) never takes the match, and at a reversal (down and back up the same
// line) the leg the row is really on beats the one it only grazes.
// Distances are compared squared; `minima` is the caller's buffer (one allocation for all rows).
std::optional<Projection> match_row(const PathIndex& path, double x, double y, double z, int k_min, double reach_mm,
                                    double window_mm, double tie_mm, std::vector<Projection>& minima) {
  const std::span<const int> cell = path.candidates(x, y);
  auto it = std::lower_bound(cell.begin(), cell.end(), k_min);
  minima.clear();
  const bool use_z = std::isfinite(z);
  const double reach2 = reach_mm * reach_mm;
  double window_end = 1e300;
  int previous_k = -2;
  Projection previous{1e300, 0.0};
  bool previous_falling = true;  // the distance fell into the previous segment (or it starts a run)
  auto close_run_at_previous = [&]() {
    if (previous_k >= 0 && previous_falling) minima.push_back(previous);
  };
  for (; it != cell.end(); ++it) {
    const int k = *it;
    if (path.s_of_segment_start(k) > window_end) break;
    const Projection p = path.project_squared(k, x, y, z, use_z);
    if (p.distance_mm > reach2) continue;
    if (k != previous_k + 1) {  // a new run of segments within reach
      close_run_at_previous();
      previous_falling = true;
    } else {
      if (p.distance_mm > previous.distance_mm) {
        if (previous_falling) minima.push_back(previous);
        previous_falling = false;
      } else {
        previous_falling = true;
      }
    }
    previous_k = k;
    previous = p;
    if (window_end > 1e299) window_end = path.s_of_segment_start(k) + window_mm;
  }
  close_run_at_previous();
  if (minima.empty()) return std::nullopt;
  double best = 1e300;
  for (auto& m : minima) {
    m.distance_mm = std::sqrt(m.distance_mm);
    best = std::min(best, m.distance_mm);
  }
  for (const auto& m : minima) {
    if (m.distance_mm <= best + tie_mm) return m;
  }
  return minima.front();
}

// Each row's place by match_row, at or after the furthest place so far (less a tolerance for position
// noise); first, last: the first and last matched rows.
PositionMatch match_rows_forward(const force_log::ForceLog& log, const PathIndex& path, double scale,
                                 double reach_mm) {
  PositionMatch m;
  const std::size_t n = log.rows.size();
  m.s_mm.assign(n, kNaN);
  m.first = n;
  // Backward tolerance for position noise; the stretch after the first candidate searched for a nearer one.
  const double back_mm = std::min(0.1, reach_mm);
  const double window_mm = 2.0 + 4.0 * reach_mm;
  const double tie_mm = 0.1 * reach_mm;
  double anchor_mm = -1e300;
  std::vector<Projection> minima;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& row = log.rows[i];
    if (!finite_xy(row)) continue;
    const int k_min = anchor_mm > -1e299 ? path.segment_at(anchor_mm - back_mm) : 0;
    const auto match =
        match_row(path, scale * row.x_mm, scale * row.y_mm, scale * row.z_mm, k_min, reach_mm, window_mm, tie_mm, minima);
    if (!match) continue;
    m.s_mm[i] = match->s_mm;
    anchor_mm = std::max(anchor_mm, match->s_mm);
    if (m.first == n) m.first = i;
    m.last = i;
  }
  return m;
}

// Rows before the machine reaches the part of the path in material are the machine arriving — from
// its home, through the program's own approach moves, which a forward match cannot follow back up a
// plunge — and are neither matched nor off the path, when that first arrival lies before the cut
// starts; the same for rows after the cut when the last match lies after it. Otherwise rows before
// the first match or after the last one left the path. Needs a matched row.
void count_rows_around_cut(const force_log::ForceLog& log, double reach_mm, const CutSpan& cut, PositionMatch& m) {
  const std::size_t n = log.rows.size();
  const double near_mm = 2.0 * reach_mm + 1.0;
  std::size_t cut_first = m.first;
  while (cut_first <= m.last && !(std::isfinite(m.s_mm[cut_first]) && m.s_mm[cut_first] >= cut.first_mm - near_mm)) {
    ++cut_first;
  }
  std::size_t cut_last = m.last;
  while (cut_last > cut_first && !(std::isfinite(m.s_mm[cut_last]) && m.s_mm[cut_last] <= cut.last_mm + near_mm)) {
    --cut_last;
  }
  const bool arrives_before_cut = m.s_mm[m.first] <= cut.first_mm + near_mm;
  const bool leaves_after_cut = m.s_mm[m.last] >= cut.last_mm - near_mm;
  m.span_rows = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite_xy(log.rows[i])) continue;
    const bool before = i < (arrives_before_cut ? cut_first : m.first);
    const bool after = i > (leaves_after_cut ? cut_last : m.last);
    if ((before && arrives_before_cut) || (after && leaves_after_cut)) {
      if (!std::isfinite(m.s_mm[i])) ++(before ? m.leading : m.trailing);  // off the path, not on its approach
      continue;
    }
    ++m.span_rows;
    if (std::isfinite(m.s_mm[i])) continue;
    if (m.off_path == 0) m.first_off_path = i;
    ++m.off_path;
  }
}

}  // namespace

CutSpan cut_span(const planner::PlanResult& plan) {
  CutSpan span{plan.samples.empty() ? 0.0 : plan.samples.front().s_mm, plan.samples.empty() ? 0.0 : plan.samples.back().s_mm};
  const auto first = std::find_if(plan.samples.begin(), plan.samples.end(), [](const auto& p) { return p.engaged; });
  if (first == plan.samples.end()) return span;
  const auto last = std::find_if(plan.samples.rbegin(), plan.samples.rend(), [](const auto& p) { return p.engaged; });
  return {first->s_mm, last->s_mm};
}

PositionMatch match_positions(const force_log::ForceLog& log, const PathIndex& path, double scale, double reach_mm,
                              const CutSpan& cut) {
  PositionMatch m = match_rows_forward(log, path, scale, reach_mm);
  const std::size_t n = log.rows.size();
  if (m.first == n) {
    for (std::size_t i = 0; i < n; ++i) m.leading += finite_xy(log.rows[i]) ? 1 : 0;
    return m;
  }
  count_rows_around_cut(log, reach_mm, cut, m);
  return m;
}

}  // namespace feedplan::learning::detail
