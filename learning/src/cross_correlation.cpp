#include "cross_correlation.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include <Eigen/Core>

namespace feedplan::learning::detail {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Correlations this close to the maximum belong to its flat top (rounding in the sums).
constexpr double kFlatTop = 1e-9;

// The Pearson coefficient from the sums of n pairs; NaN with fewer than 3 pairs or a constant signal.
double pearson(double n, double sx, double sy, double sxx, double syy, double sxy) {
  if (n < 3) return kNaN;
  const double cov = sxy - sx * sy / n;
  const double vx = sxx - sx * sx / n;
  const double vy = syy - sy * sy / n;
  if (vx <= 0.0 || vy <= 0.0) return kNaN;
  return cov / std::sqrt(vx * vy);
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double a) { return std::isfinite(a); });
}

// Prefix sums: out[k] = Σ_{i<k} f(v[i]).
template <class F>
std::vector<double> prefix(const std::vector<double>& v, F f) {
  std::vector<double> out(v.size() + 1, 0.0);
  for (std::size_t i = 0; i < v.size(); ++i) out[i + 1] = out[i] + f(v[i]);
  return out;
}

// correlation_by_lag for signals without gaps and a finite y_outside: every x pairs with something, so
// the sums of x are fixed, those of y come from prefix sums, and only Σ x·y needs a pass per lag (a
// vectorised dot product over the overlap).
std::vector<double> correlation_by_lag_dense(const std::vector<double>& x, const std::vector<double>& y,
                                             long lag_min, long lag_max, double y_outside) {
  std::vector<double> r(static_cast<std::size_t>(lag_max - lag_min + 1), kNaN);
  const long nx = static_cast<long>(x.size()), ny = static_cast<long>(y.size());
  const std::vector<double> px = prefix(x, [](double a) { return a; });
  const std::vector<double> py = prefix(y, [](double a) { return a; });
  const std::vector<double> pyy = prefix(y, [](double a) { return a * a; });
  double sxx = 0.0;
  for (const double a : x) sxx += a * a;
  const double sx = px.back();
  for (long lag = lag_min; lag <= lag_max; ++lag) {
    // x[i] meets y[i − lag] for i in [i0, i1); the other x meet y_outside.
    const long i0 = std::clamp(lag, 0L, nx), i1 = std::clamp(ny + lag, i0, nx);
    const long inside = i1 - i0;
    const auto u0 = static_cast<std::size_t>(i0), u1 = static_cast<std::size_t>(i1);
    const auto j0 = static_cast<std::size_t>(i0 - lag), j1 = static_cast<std::size_t>(i1 - lag);
    const double outside = static_cast<double>(nx - inside);
    const double x_outside_sum = sx - (px[u1] - px[u0]);
    const double sy = py[j1] - py[j0] + outside * y_outside;
    const double syy = pyy[j1] - pyy[j0] + outside * y_outside * y_outside;
    double sxy = y_outside * x_outside_sum;
    if (inside > 0) {
      sxy += Eigen::Map<const Eigen::VectorXd>(x.data() + u0, inside).dot(Eigen::Map<const Eigen::VectorXd>(y.data() + j0, inside));
    }
    r[static_cast<std::size_t>(lag - lag_min)] = pearson(static_cast<double>(nx), sx, sy, sxx, syy, sxy);
  }
  return r;
}

// r[lag − lag_min]: the Pearson coefficient of x[i] with y[i − lag] (the rule of correlate()); NaN with
// fewer than 3 pairs or a constant signal.
std::vector<double> correlation_by_lag(const std::vector<double>& x, const std::vector<double>& y, long lag_min,
                                       long lag_max, double y_outside) {
  if (std::isfinite(y_outside) && all_finite(x) && all_finite(y)) {
    return correlation_by_lag_dense(x, y, lag_min, lag_max, y_outside);
  }
  std::vector<double> r(static_cast<std::size_t>(lag_max - lag_min + 1), kNaN);
  const long nx = static_cast<long>(x.size()), ny = static_cast<long>(y.size());
  for (long lag = lag_min; lag <= lag_max; ++lag) {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    long n = 0;
    for (long i = 0; i < nx; ++i) {
      const double xi = x[static_cast<std::size_t>(i)];
      if (!std::isfinite(xi)) continue;
      const long j = i - lag;
      const double yj = (j >= 0 && j < ny) ? y[static_cast<std::size_t>(j)] : y_outside;
      if (!std::isfinite(yj)) continue;
      sx += xi;
      sy += yj;
      sxx += xi * xi;
      syy += yj * yj;
      sxy += xi * yj;
      ++n;
    }
    r[static_cast<std::size_t>(lag - lag_min)] = pearson(static_cast<double>(n), sx, sy, sxx, syy, sxy);
  }
  return r;
}

// The maximum of r (index k for lag lag_min + k): the middle of its flat top, refined by a parabola
// through its neighbours when the top is one lag wide.
CorrelationPeak peak_of(const std::vector<double>& r, long lag_min) {
  CorrelationPeak peak;
  std::size_t best = r.size();
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (std::isfinite(r[k]) && (best == r.size() || r[k] > r[best])) best = k;
  }
  if (best == r.size()) return peak;
  peak.found = true;
  peak.correlation = r[best];
  // A flat top (contact signals of different length): its middle.
  std::size_t lo = best, hi = best;
  while (lo > 0 && r[lo - 1] >= r[best] - kFlatTop) --lo;
  while (hi + 1 < r.size() && r[hi + 1] >= r[best] - kFlatTop) ++hi;
  peak.lag_bins = static_cast<double>(lag_min) + 0.5 * static_cast<double>(lo + hi);
  peak.at_edge = lo == 0 || hi + 1 == r.size();
  if (lo == hi && !peak.at_edge && std::isfinite(r[best - 1]) && std::isfinite(r[best + 1])) {
    const double a = r[best - 1], b = r[best], c = r[best + 1];
    const double denominator = a - 2.0 * b + c;
    if (denominator < 0.0) peak.lag_bins += std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
  }
  return peak;
}

}  // namespace

CorrelationPeak correlate(const std::vector<double>& x, const std::vector<double>& y, long lag_min, long lag_max,
                          double y_outside) {
  return peak_of(correlation_by_lag(x, y, lag_min, lag_max, y_outside), lag_min);
}

}  // namespace feedplan::learning::detail
