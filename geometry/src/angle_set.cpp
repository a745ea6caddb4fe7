#include "angle_set.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/core/angle.hpp"

namespace feedplan::geometry::detail {

double wrap_two_pi(double angle_rad) {
  // The kernels' angles are within a few turns of [0, 2π): avoid fmod for them.
  if (angle_rad >= 0.0 && angle_rad < kTwoPi) return angle_rad;
  if (angle_rad >= -kTwoPi && angle_rad < 0.0) {
    const double a = angle_rad + kTwoPi;
    return a < kTwoPi ? a : 0.0;
  }
  if (angle_rad >= kTwoPi && angle_rad < 2.0 * kTwoPi) return angle_rad - kTwoPi;
  double a = std::fmod(angle_rad, kTwoPi);
  if (a < 0.0) a += kTwoPi;
  if (a >= kTwoPi) a -= kTwoPi;
  return a;
}

AngleSet AngleSet::full() {
  AngleSet set;
  set.intervals_.push_back({0.0, kTwoPi});
  return set;
}

AngleSet AngleSet::cos_above(double center_rad, double threshold) {
  if (threshold <= -1.0 + kCosTangencyTolerance) return full();
  if (threshold >= 1.0 - kCosTangencyTolerance || std::isnan(threshold)) return {};
  const double half_width = std::acos(threshold);
  const double lo = wrap_two_pi(center_rad - half_width);
  const double hi = lo + 2.0 * half_width;
  AngleSet set;
  if (hi <= kTwoPi) {
    set.intervals_.push_back({lo, hi});
  } else {
    set.intervals_.push_back({0.0, hi - kTwoPi});
    set.intervals_.push_back({lo, kTwoPi});
  }
  return set;
}

void AngleSet::intersect_with(const AngleSet& other) {
  AngleIntervals result;
  std::size_t i = 0;
  std::size_t j = 0;
  const auto& a = intervals_;
  const auto& b = other.intervals_;
  while (i < a.size() && j < b.size()) {
    const double lo = std::max(a[i].lo, b[j].lo);
    const double hi = std::min(a[i].hi, b[j].hi);
    if (hi > lo) result.push_back({lo, hi});
    if (a[i].hi < b[j].hi) ++i; else ++j;
  }
  intervals_ = std::move(result);
}

double AngleSet::measure_rad() const {
  double total = 0.0;
  for (const auto& interval : intervals_) total += interval.hi - interval.lo;
  return total;
}

AngleIntervals subtract_union(const AngleIntervals& base, AngleIntervals& cuts, double min_length_rad) {
  std::sort(cuts.begin(), cuts.end(), [](const AngleInterval& p, const AngleInterval& q) { return p.lo < q.lo; });
  AngleIntervals result;
  std::size_t k = 0;
  for (const auto& piece : base) {
    double lo = piece.lo;
    const double hi = piece.hi;
    // Skip cuts that end before this piece starts; they cannot affect later pieces either.
    while (k < cuts.size() && cuts[k].hi <= lo) ++k;
    std::size_t m = k;
    while (m < cuts.size() && cuts[m].lo < hi) {
      if (cuts[m].lo > lo && cuts[m].lo - lo >= min_length_rad) result.push_back({lo, cuts[m].lo});
      lo = std::max(lo, cuts[m].hi);
      if (lo >= hi) break;
      ++m;
    }
    if (hi - lo >= min_length_rad) result.push_back({lo, hi});
  }
  return result;
}

}  // namespace feedplan::geometry::detail

