#pragma once
// A set of angles on the circle as sorted disjoint open intervals in [0, 2π). The engagement
// kernels build every condition "tool-circle point inside a half-plane / disc / annulus" as such a
// set in closed form and combine them exactly (no sampling). Internal to geometry.

#include <boost/container/small_vector.hpp>

namespace feedplan::geometry::detail {

struct AngleInterval {
  double lo = 0.0;  //!< rad, in [0, 2π)
  double hi = 0.0;  //!< rad, in (lo, 2π]
};

using AngleIntervals = boost::container::small_vector<AngleInterval, 6>;

//! Tolerance on a cosine threshold: conditions within it of ±1 are tangencies and give the empty
//! or the full set (an angular error below 1.5e-7 rad).
inline constexpr double kCosTangencyTolerance = 1e-14;

class AngleSet {
 public:
  static AngleSet full();
  static AngleSet empty() { return {}; }

  //! {θ : cos(θ − center_rad) > threshold}: an arc about center_rad of half-width acos(threshold).
  static AngleSet cos_above(double center_rad, double threshold);

  //! Keeps only the angles also in `other`.
  void intersect_with(const AngleSet& other);

  bool is_empty() const { return intervals_.empty(); }
  double measure_rad() const;
  const AngleIntervals& intervals() const { return intervals_; }
  void push_raw(AngleInterval interval) { intervals_.push_back(interval); }

 private:
  AngleIntervals intervals_;
};

//! Wraps an angle into [0, 2π).
double wrap_two_pi(double angle_rad);

//! Removes from `base` (sorted, disjoint) the union of `cuts` (any order, may overlap; sorted in
//! place). Drops remaining pieces shorter than `min_length_rad`.
AngleIntervals subtract_union(const AngleIntervals& base, AngleIntervals& cuts, double min_length_rad);

}  // namespace feedplan::geometry::detail
