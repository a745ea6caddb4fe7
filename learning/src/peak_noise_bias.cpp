#include "feedplan/learning/peak_noise_bias.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "fixed_text.hpp"

namespace feedplan::learning {

namespace {

using detail::fixed;

// Rows [first, end) of a window on the log's clock.
struct RowRange {
  std::size_t first = 0, end = 0;
};

RowRange rows_of(const std::vector<double>& t_s, const force_log::RevolutionPeak& window) {
  const auto at = [&](double t) {
    return static_cast<std::size_t>(std::lower_bound(t_s.begin(), t_s.end(), t) - t_s.begin());
  };
  return {at(window.t_start_s), at(window.t_end_s)};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<long>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// One axis's noise over the air windows: its deviations from each window's median.
struct AxisNoise {
  std::vector<double> deviation;  // per row, in window order
  double lag_products = 0.0, lag_squares = 0.0;
};

void add_window(const std::vector<double>& f, RowRange r, AxisNoise& axis) {
  if (r.end <= r.first + 1) return;
  const double centre = median(std::vector<double>(f.begin() + static_cast<long>(r.first), f.begin() + static_cast<long>(r.end)));
  for (std::size_t i = r.first; i < r.end; ++i) {
    const double d = f[i] - centre;
    axis.deviation.push_back(d);
    axis.lag_squares += d * d;
    if (i > r.first) axis.lag_products += d * (f[i - 1] - centre);
  }
}

double robust_sigma(const AxisNoise& axis) {
  std::vector<double> absolute;
  absolute.reserve(axis.deviation.size());
  for (double d : axis.deviation) absolute.push_back(std::abs(d));
  return 1.4826 * median(std::move(absolute));
}

// Rows of a window that can carry its largest reading with noise of spread sigma_n added: a 2-D Gaussian
// error beyond kMaxNoiseSpreads spreads has probability e^(−kMaxNoiseSpreads²/2) (< 1e-7), so a row whose
// clean |F_xy| is more than twice that below the window's largest never carries it. Row offsets from
// r.first, ascending.
constexpr double kMaxNoiseSpreads = 5.7;

std::vector<std::size_t> rows_that_can_peak(const std::vector<double>& fx, const std::vector<double>& fy, RowRange r,
                                            double sigma_n) {
  double largest = 0.0;
  for (std::size_t k = r.first; k < r.end; ++k) largest = std::max(largest, std::hypot(fx[k], fy[k]));
  const double bar = largest - 2.0 * kMaxNoiseSpreads * sigma_n;
  std::vector<std::size_t> rows;
  for (std::size_t k = r.first; k < r.end; ++k) {
    if (std::hypot(fx[k], fy[k]) >= bar) rows.push_back(k - r.first);
  }
  return rows;
}

// The mean largest |F_xy| over one window with noise of spread sigma_n[l] (lag-1 correlation `lag1`)
// added, for every l: the same unit noise draws scaled to each spread (common random numbers, so the
// extrapolation across spreads sees the spread's effect, not the draws' scatter). The noise is drawn
// only at the rows that can carry the largest reading; an AR(1) sequence seen g rows later has
// correlation lag1^g, so drawing it there with that correlation is the same noise as drawing every row.
std::vector<double> noisy_largest_n(const std::vector<double>& fx, const std::vector<double>& fy, RowRange r,
                                    const std::vector<double>& sigma_n, double lag1, std::mt19937_64& random) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const std::vector<std::size_t> rows =
      rows_that_can_peak(fx, fy, r, *std::max_element(sigma_n.begin(), sigma_n.end()));
  std::vector<double> carry(rows.size(), 0.0), innovation(rows.size(), 1.0);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    carry[k] = std::pow(lag1, static_cast<double>(rows[k] - rows[k - 1]));
    innovation[k] = std::sqrt(1.0 - carry[k] * carry[k]);
  }
  std::vector<double> ux(rows.size()), uy(rows.size()), sum(sigma_n.size(), 0.0);
  for (int draw = 0; draw < kNoiseBiasDraws; ++draw) {
    for (std::size_t k = 0; k < rows.size(); ++k) {
      ux[k] = k == 0 ? normal(random) : carry[k] * ux[k - 1] + innovation[k] * normal(random);
      uy[k] = k == 0 ? normal(random) : carry[k] * uy[k - 1] + innovation[k] * normal(random);
    }
    for (std::size_t l = 0; l < sigma_n.size(); ++l) {
      double largest_squared = 0.0;  // of |F_xy|: one square root per draw
      for (std::size_t k = 0; k < rows.size(); ++k) {
        const std::size_t i = r.first + rows[k];
        const double x = fx[i] + sigma_n[l] * ux[k], y = fy[i] + sigma_n[l] * uy[k];
        largest_squared = std::max(largest_squared, x * x + y * y);
      }
      sum[l] += std::sqrt(largest_squared);
    }
  }
  for (double& v : sum) v /= kNoiseBiasDraws;
  return sum;
}

// The mean peak without noise from the means S at noise variance u σ² (u = 1 + λ): S = P + k u^p fitted by
// least squares (p on a grid, P and k linear for each), P the value at u = 0. A power of the variance: the
// excess grows with the noise as more rows enter the band of the top it reaches (a polynomial in λ cannot
// bend down to zero at λ = −1 and missed half the excess on pulses of known shape).
double extrapolated_to_no_noise(const std::vector<double>& u, const std::vector<double>& value) {
  double best_residual = std::numeric_limits<double>::infinity(), best = value.front();
  for (double p = 0.05; p <= 1.5 + 1e-9; p += 0.01) {
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      const double x = std::pow(u[k], p);
      sw += 1.0;
      sx += x;
      sy += value[k];
      sxx += x * x;
      sxy += x * value[k];
    }
    const double det = sw * sxx - sx * sx;
    if (!(det > 0.0)) continue;
    const double slope = (sw * sxy - sx * sy) / det;
    const double intercept = (sy - slope * sx) / sw;
    double residual = 0.0;
    for (std::size_t k = 0; k < u.size(); ++k) {
      const double r = value[k] - intercept - slope * std::pow(u[k], p);
      residual += r * r;
    }
    if (residual < best_residual) {
      best_residual = residual;
      best = intercept;
    }
  }
  return best;
}

}  // namespace

PeakNoise peak_noise(const std::vector<double>& t_s, const std::vector<double>& fx_n, const std::vector<double>& fy_n,
                     const std::vector<force_log::RevolutionPeak>& air,
                     const std::vector<force_log::RevolutionPeak>& periods) {
  PeakNoise out;
  AxisNoise x, y;
  for (const auto& window : air) {
    const RowRange r = rows_of(t_s, window);
    add_window(fx_n, r, x);
    add_window(fy_n, r, y);
  }
  out.air_rows = x.deviation.size();
  if (out.air_rows < kMinNoiseRows || periods.empty()) {
    out.message = "peak noise not estimated: " + std::to_string(out.air_rows) + " rows out of the cut (" +
                  std::to_string(kMinNoiseRows) + " needed) and " + std::to_string(periods.size()) + " tooth periods in it";
    return out;
  }
  out.sigma_n = 0.5 * (robust_sigma(x) + robust_sigma(y));
  const double squares = x.lag_squares + y.lag_squares;
  out.lag1 = squares > 0.0 ? std::clamp((x.lag_products + y.lag_products) / squares, 0.0, 0.99) : 0.0;
  // SIMEX: the mean peak reading with the noise variance raised to u σ², u = 1 (as read), 2, 3, 4,
  // extrapolated back to u = 0 (no noise).
  std::mt19937_64 random(20261127u);
  const std::vector<double> u = {1.0, 2.0, 3.0, 4.0};
  std::vector<double> mean_peak(u.size(), 0.0);
  std::vector<double> added_sigma_n;  // the noise added to reach u σ²
  for (std::size_t l = 1; l < u.size(); ++l) added_sigma_n.push_back(out.sigma_n * std::sqrt(u[l] - 1.0));
  std::size_t windows = 0;
  const std::size_t step = std::max<std::size_t>(1, periods.size() / kNoiseBiasWindows);
  for (std::size_t k = 0; k < periods.size(); k += step) {
    const RowRange r = rows_of(t_s, periods[k]);
    if (r.end <= r.first) continue;
    ++windows;
    double read = 0.0;
    for (std::size_t i = r.first; i < r.end; ++i) read = std::max(read, std::hypot(fx_n[i], fy_n[i]));
    mean_peak[0] += read;
    const std::vector<double> noisy = noisy_largest_n(fx_n, fy_n, r, added_sigma_n, out.lag1, random);
    for (std::size_t l = 1; l < u.size(); ++l) mean_peak[l] += noisy[l - 1];
  }
  if (windows > 0) {
    for (double& v : mean_peak) v /= static_cast<double>(windows);
    out.peak_excess_n = std::max(0.0, mean_peak[0] - extrapolated_to_no_noise(u, mean_peak));
  }
  out.message = "noise " + fixed(out.sigma_n, 2) + " N per axis (lag-1 correlation " + fixed(out.lag1, 2) + ", " +
                std::to_string(out.air_rows) + " rows out of the cut) raises a tooth period's peak reading by about " +
                fixed(out.peak_excess_n, 1) + " N";
  return out;
}

}  // namespace feedplan::learning
