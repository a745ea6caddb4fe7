#include "local_linear_smoothing.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace feedplan::learning::detail {

double local_linear_at(const std::vector<double>& x, const std::vector<double>& y, std::size_t lo, std::size_t hi,
                       std::size_t k) {
  assert(x.size() == y.size() && lo <= k && k <= hi && hi < y.size());
  const double count = static_cast<double>(hi - lo + 1);
  double x_mean = 0.0;
  double y_mean = 0.0;
  for (std::size_t j = lo; j <= hi; ++j) {
    x_mean += x[j];
    y_mean += y[j];
  }
  x_mean /= count;
  y_mean /= count;
  double sxx = 0.0;
  double sxy = 0.0;
  for (std::size_t j = lo; j <= hi; ++j) {
    sxx += (x[j] - x_mean) * (x[j] - x_mean);
    sxy += (x[j] - x_mean) * (y[j] - y_mean);
  }
  return sxx > 0.0 ? y_mean + sxy / sxx * (x[k] - x_mean) : y_mean;
}

std::vector<double> local_linear_smoothed(const std::vector<double>& x, const std::vector<double>& y,
                                          const std::vector<std::vector<double>>& like, int half_width,
                                          double like_tolerance) {
  assert(x.size() == y.size());
  if (half_width <= 0) return y;
  const std::size_t n = y.size();
  const auto h = static_cast<std::size_t>(half_width);
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const auto alike = [&](std::size_t j) {
      return std::all_of(like.begin(), like.end(), [&](const std::vector<double>& v) {
        assert(v.size() == n);
        return std::abs(v[j] - v[k]) <= like_tolerance * std::abs(v[k]);
      });
    };
    std::size_t lo = k;
    std::size_t hi = k;
    while (lo > 0 && k - lo < h && alike(lo - 1)) --lo;
    while (hi + 1 < n && hi - k < h && alike(hi + 1)) ++hi;
    out[k] = local_linear_at(x, y, lo, hi, k);
  }
  return out;
}

}  // namespace feedplan::learning::detail
