#pragma once
// Signals sampled at log rows or plan samples, read between samples and resampled onto a uniform time
// grid (bins) for the alignment's cross-correlations. Internal to learning.

#include <cstddef>
#include <vector>

namespace feedplan::learning::detail {

//! Value at `x` of the piecewise-linear function through (xs, ys), xs non-decreasing; `outside` beyond.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x, double outside);

//! Mean per bin [t0_s + b bin_s, t0_s + (b + 1) bin_s), b < bins, of the (time, value) pairs with a
//! finite value; NaN for bins without a value.
std::vector<double> bin_means(const std::vector<double>& t_s, const std::vector<double>& value, double t0_s,
                              double bin_s, std::size_t bins);

//! Centred running maximum over `width` bins (odd), of the finite values only: the peak envelope. NaN
//! stays NaN.
std::vector<double> moving_max(const std::vector<double>& x, int width);

}  // namespace feedplan::learning::detail
