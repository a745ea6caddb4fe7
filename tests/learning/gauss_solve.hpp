#pragma once
// The learning tests' own 6×6 linear solver (not Eigen's, which the code under test uses): the oracle
// for least-squares normal equations.

#include <array>
#include <cmath>
#include <utility>

namespace feedplan::learning::testing {

using Matrix = std::array<std::array<double, 6>, 6>;
using Vector = std::array<double, 6>;

//! x with a x = b by Gaussian elimination with partial pivoting.
inline Vector solve(Matrix a, Vector b) {
  for (int c = 0; c < 6; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 6; ++r) {
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    }
    std::swap(a[c], a[pivot]);
    std::swap(b[c], b[pivot]);
    for (int r = c + 1; r < 6; ++r) {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < 6; ++k) a[r][k] -= f * a[c][k];
      b[r] -= f * b[c];
    }
  }
  Vector x{};
  for (int r = 5; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < 6; ++k) s -= a[r][k] * x[k];
    x[r] = s / a[r][r];
  }
  return x;
}

}  // namespace feedplan::learning::testing
