#pragma once
// The covariance of the response-surface coefficients β (seed 003 Eq. 1), 6×6 in BetaIndex order, N²:
// what a fit reports about how well the data determine the model, what RLS carries from step to step, and
// what a cautious plan turns into a force uncertainty σ² = ψᵀ C ψ (seed 003 Eq. 4's regressors ψ).

#include <array>
#include <cstddef>

namespace feedplan::model {

class Covariance {
 public:
  static constexpr std::size_t kSize = 6;  //!< coefficients, in BetaIndex order

  Covariance() = default;  //!< all zero: nothing known about the spread (or a model without a fit)

  //! A covariance from its 36 entries, row-major (as stored and exchanged).
  static Covariance from_entries(const std::array<double, kSize * kSize>& entries) {
    Covariance c;
    c.entries_ = entries;
    return c;
  }

  //! C(row, column), N².
  double operator()(std::size_t row, std::size_t column) const { return entries_[row * kSize + column]; }
  double& operator()(std::size_t row, std::size_t column) { return entries_[row * kSize + column]; }

  //! The variance of coefficient j, C(j, j), N².
  double variance(std::size_t j) const { return (*this)(j, j); }

  //! ψᵀ C ψ, summed row by row, N² (the variance of Σ βᵢ ψᵢ).
  double quadratic_form(const std::array<double, kSize>& psi) const {
    double sum = 0.0;
    for (std::size_t i = 0; i < kSize; ++i) {
      for (std::size_t j = 0; j < kSize; ++j) sum += psi[i] * (*this)(i, j) * psi[j];
    }
    return sum;
  }

  //! The 36 entries, row-major: entry k is C(k / 6, k % 6). For storage, exchange, messages naming
  //! "covariance[k]", and Eigen::Map.
  const std::array<double, kSize * kSize>& entries() const { return entries_; }
  std::array<double, kSize * kSize>& entries() { return entries_; }

  bool operator==(const Covariance&) const = default;

 private:
  std::array<double, kSize * kSize> entries_{};
};

}  // namespace feedplan::model
