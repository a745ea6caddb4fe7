// The cross-correlation the alignment finds delays with, against the Pearson coefficient computed from
// its definition (two passes: means, then centred sums) at every lag, on signals with and without gaps.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "../../learning/src/cross_correlation.hpp"

namespace feedplan::learning::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Pearson's r of the pairs (x[i], y[i − lag]), y outside its range taking y_outside, pairs with a NaN left out.
double pearson_by_definition(const std::vector<double>& x, const std::vector<double>& y, long lag, double y_outside) {
  std::vector<double> a, b;
  for (long i = 0; i < static_cast<long>(x.size()); ++i) {
    const long j = i - lag;
    const double yj = j >= 0 && j < static_cast<long>(y.size()) ? y[static_cast<std::size_t>(j)] : y_outside;
    if (std::isfinite(x[static_cast<std::size_t>(i)]) && std::isfinite(yj)) {
      a.push_back(x[static_cast<std::size_t>(i)]);
      b.push_back(yj);
    }
  }
  double ma = 0, mb = 0;
  for (std::size_t k = 0; k < a.size(); ++k) ma += a[k] / a.size(), mb += b[k] / b.size();
  double cab = 0, caa = 0, cbb = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    cab += (a[k] - ma) * (b[k] - mb);
    caa += (a[k] - ma) * (a[k] - ma);
    cbb += (b[k] - mb) * (b[k] - mb);
  }
  return cab / std::sqrt(caa * cbb);
}

// y[i] is x[i + 37] plus noise: the peak is at lag 37 and has the definition's coefficient.
void expect_peak_as_defined(const std::vector<double>& x, const std::vector<double>& y, double y_outside) {
  const CorrelationPeak peak = correlate(x, y, -60, 60, y_outside);
  ASSERT_TRUE(peak.found);
  EXPECT_NEAR(peak.lag_bins, 37.0, 0.5);
  const long best = std::lround(peak.lag_bins);
  EXPECT_NEAR(peak.correlation, pearson_by_definition(x, y, best, y_outside), 1e-9);
  // Every lag: the coefficient at the rounded peak is the largest of the definition's.
  for (long lag = -60; lag <= 60; ++lag) {
    EXPECT_LE(pearson_by_definition(x, y, lag, y_outside), peak.correlation + 1e-9) << "lag " << lag;
  }
}

std::vector<double> bursts(std::mt19937& rng, std::size_t n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> v(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) v[i] = (i / 97) % 3 == 1 ? 300.0 + 40.0 * u(rng) : 5.0 * u(rng);
  return v;
}

std::vector<double> delayed(const std::vector<double>& x, long bins, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 10.0);
  std::vector<double> y(x.size());
  for (long i = 0; i < static_cast<long>(x.size()); ++i) {
    const long j = i + bins;
    y[static_cast<std::size_t>(i)] = (j < static_cast<long>(x.size()) ? x[static_cast<std::size_t>(j)] : 0.0) + noise(rng);
  }
  return y;
}

TEST(CrossCorrelation, SignalsWithoutGapsPeakWhereTheDefinitionDoes) {
  std::mt19937 rng(11);
  const std::vector<double> x = bursts(rng, 3000);
  expect_peak_as_defined(x, delayed(x, 37, rng), 0.0);
  expect_peak_as_defined(x, delayed(x, 37, rng), 12.5);
}

TEST(CrossCorrelation, SignalsWithGapsPeakWhereTheDefinitionDoes) {
  std::mt19937 rng(12);
  std::vector<double> x = bursts(rng, 3000);
  std::vector<double> y = delayed(x, 37, rng);
  for (std::size_t i = 500; i < 520; ++i) x[i] = kNaN;
  for (std::size_t i = 1500; i < 1510; ++i) y[i] = kNaN;
  expect_peak_as_defined(x, y, 0.0);
  expect_peak_as_defined(x, y, kNaN);
}

}  // namespace
}  // namespace feedplan::learning::detail
