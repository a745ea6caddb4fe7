// The local straight-line smoothing learning averages single peak readings with. Oracles: a straight
// line passes unchanged (a least-squares line through points on a line is that line), and white noise of
// variance σ² comes out at σ² / (2h + 1) in the middle of a window of h points either side (the fitted
// line's value at the window's centre is the window's mean).

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "../../learning/src/local_linear_smoothing.hpp"

namespace feedplan::learning::detail {
namespace {

TEST(LocalLinearSmoothing, AStraightLinePassesUnchangedAlsoAtTheEndsAndOnUnevenSpacing) {
  std::vector<double> x, y;
  for (int k = 0; k < 20; ++k) {
    x.push_back(0.1 * k + 0.03 * (k % 3));
    y.push_back(4.0 - 2.5 * x.back());
  }
  const std::vector<double> like(x.size(), 1.0);
  const std::vector<double> out = local_linear_smoothed(x, y, {like}, 3, 0.1);
  for (std::size_t k = 0; k < y.size(); ++k) EXPECT_NEAR(out[k], y[k], 1e-12) << k;
}

TEST(LocalLinearSmoothing, WhiteNoiseComesOutAtItsVarianceOverTheWindowsLength) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 2.0);
  const std::size_t n = 60000;
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = static_cast<double>(k);
    y[k] = 10.0 + noise(random);
  }
  const std::vector<double> out = local_linear_smoothed(x, y, {std::vector<double>(n, 1.0)}, 3, 0.1);
  double sum = 0.0, sum_sq = 0.0;
  for (std::size_t k = 3; k + 3 < n; ++k) {
    sum += out[k];
    sum_sq += out[k] * out[k];
  }
  const double count = static_cast<double>(n - 6);
  const double variance = sum_sq / count - (sum / count) * (sum / count);
  EXPECT_NEAR(sum / count, 10.0, 0.01);
  // σ² / 7 = 0.571; the estimate's relative standard error over 60 000 correlated values is about 2 %.
  EXPECT_NEAR(variance, 4.0 / 7.0, 0.04);
}

TEST(LocalLinearSmoothing, TheWindowStopsAtPointsThatAreNotAlike) {
  // Two stretches, `like` 1 and then 1.5 (50 % apart): each a constant of its own, kept as it is.
  std::vector<double> x, y, like;
  for (int k = 0; k < 12; ++k) {
    x.push_back(k);
    y.push_back(k < 6 ? 1.0 : 3.0);
    like.push_back(k < 6 ? 1.0 : 1.5);
  }
  const std::vector<double> apart = local_linear_smoothed(x, y, {like}, 3, 0.1);
  for (std::size_t k = 0; k < y.size(); ++k) EXPECT_NEAR(apart[k], y[k], 1e-12) << k;
  // Alike within a tolerance of 60 %: the step is smoothed into a ramp next to it.
  const std::vector<double> together = local_linear_smoothed(x, y, {like}, 3, 0.6);
  EXPECT_GT(together[5], 1.1);
  EXPECT_LT(together[6], 2.9);
}

TEST(LocalLinearSmoothing, NoWindowLeavesTheValuesAsGiven) {
  const std::vector<double> x{0.0, 1.0, 2.0, 3.0}, y{1.0, 5.0, 2.0, 8.0};
  EXPECT_EQ(local_linear_smoothed(x, y, {std::vector<double>(4, 1.0)}, 0, 0.1), y);
}

}  // namespace
}  // namespace feedplan::learning::detail
