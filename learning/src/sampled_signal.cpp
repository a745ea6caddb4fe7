#include "sampled_signal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace feedplan::learning::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x, double outside) {
  if (xs.empty() || !(x >= xs.front()) || !(x <= xs.back())) return outside;
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  if (it == xs.end()) return ys.back();
  const std::size_t j = static_cast<std::size_t>(it - xs.begin());
  if (j == 0) return ys.front();
  const double x0 = xs[j - 1], x1 = xs[j];
  const double w = x1 > x0 ? (x - x0) / (x1 - x0) : 1.0;
  return ys[j - 1] + w * (ys[j] - ys[j - 1]);
}

// Mean per bin of (time, value) pairs; NaN for bins without a value.
std::vector<double> bin_means(const std::vector<double>& t_s, const std::vector<double>& value, double t0_s,
                              double bin_s, std::size_t bins) {
  std::vector<double> sum(bins, 0.0);
  std::vector<int> count(bins, 0);
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    if (!std::isfinite(value[i])) continue;
    const double f = (t_s[i] - t0_s) / bin_s;
    if (!(f >= 0.0)) continue;
    const std::size_t b = static_cast<std::size_t>(f);
    if (b >= bins) continue;
    sum[b] += value[i];
    ++count[b];
  }
  std::vector<double> mean(bins, kNaN);
  for (std::size_t b = 0; b < bins; ++b) {
    if (count[b] > 0) mean[b] = sum[b] / count[b];
  }
  return mean;
}

// Centred running maximum over `width` bins (odd), of the finite values only: the peak envelope.
std::vector<double> moving_max(const std::vector<double>& x, int width) {
  if (width <= 1) return x;
  const std::size_t half = static_cast<std::size_t>(width / 2);
  const std::size_t n = x.size();
  std::vector<double> out(n, kNaN);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) continue;
    double most = x[i];
    for (std::size_t j = i >= half ? i - half : 0; j < std::min(n, i + half + 1); ++j) {
      if (std::isfinite(x[j])) most = std::max(most, x[j]);
    }
    out[i] = most;
  }
  return out;
}

}  // namespace feedplan::learning::detail
