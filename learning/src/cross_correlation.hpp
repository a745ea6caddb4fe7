#pragma once
// Pearson cross-correlation of two binned signals over a range of lags, and the lag of its maximum:
// how the alignment finds the program's start (time profile) and the force delay. Internal to learning.

#include <vector>

namespace feedplan::learning::detail {

//! The best lag found by correlate().
struct CorrelationPeak {
  double lag_bins = 0.0;     // interpolated lag of the maximum
  double correlation = 0.0;  // Pearson coefficient there
  bool at_edge = false;      // the maximum lies on the edge of the searched range
  bool found = false;
};

// Pearson correlation of x[i] with y[i − lag] for lag in [lag_min, lag_max]; y outside its range takes
// `y_outside` (NaN: the pair is left out). Pairs with a NaN are left out. The maximum is refined by a
// parabola through its neighbours.
CorrelationPeak correlate(const std::vector<double>& x, const std::vector<double>& y, long lag_min, long lag_max,
                          double y_outside);

}  // namespace feedplan::learning::detail
