#pragma once
// A noisy quantity along the path smoothed by a local straight line: at each point the least-squares
// line through it and its neighbours, evaluated there. A straight trend passes unchanged; white noise of
// variance σ² comes out at σ² / (2 h + 1) in the middle of a window of h points either side.
// Internal to learning.

#include <cstddef>
#include <vector>

namespace feedplan::learning::detail {

//! The least-squares line through (x[j], y[j]) for j in [lo, hi] evaluated at x[k] (lo ≤ k ≤ hi < size;
//! the mean of y where the x do not spread).
double local_linear_at(const std::vector<double>& x, const std::vector<double>& y, std::size_t lo, std::size_t hi,
                       std::size_t k);

//! y smoothed at each x (x increasing; x, y and each of `like` equally long). The window of point k takes
//! up to `half_width` neighbours either side, each side stopping before the first j with
//! |like[m][j] − like[m][k]| > like_tolerance · |like[m][k]| for some m: only points alike in every one
//! of `like` are averaged (at an end of the data, or of the alike stretch, the window is cut on that side
//! and the line still fitted). half_width ≤ 0: y as given.
std::vector<double> local_linear_smoothed(const std::vector<double>& x, const std::vector<double>& y,
                                          const std::vector<std::vector<double>>& like, int half_width,
                                          double like_tolerance);

}  // namespace feedplan::learning::detail
