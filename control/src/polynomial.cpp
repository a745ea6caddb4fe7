#include "feedplan/control/polynomial.hpp"

#include <Eigen/Dense>
#include <cassert>
#include <cmath>
#include <cstddef>

namespace feedplan::control {

int degree(const Polynomial& p) { return static_cast<int>(p.coefficients.size()) - 1; }

double coefficient(const Polynomial& p, int power) {
  const int d = degree(p);
  if (power < 0 || power > d) return 0.0;
  return p.coefficients[static_cast<std::size_t>(d - power)];
}

double evaluate(const Polynomial& p, double z) {
  double value = 0.0;
  for (double c : p.coefficients) value = value * z + c;
  return value;
}

Polynomial multiply(const Polynomial& a, const Polynomial& b) {
  if (a.coefficients.empty() || b.coefficients.empty()) return {};
  Polynomial product{std::vector<double>(a.coefficients.size() + b.coefficients.size() - 1, 0.0)};
  for (std::size_t i = 0; i < a.coefficients.size(); ++i) {
    for (std::size_t j = 0; j < b.coefficients.size(); ++j) product.coefficients[i + j] += a.coefficients[i] * b.coefficients[j];
  }
  return product;
}

Polynomial scaled(const Polynomial& p, double factor) {
  Polynomial result = p;
  for (double& c : result.coefficients) c *= factor;
  return result;
}

Polynomial monic_from_roots(const std::vector<std::complex<double>>& roots) {
  std::vector<std::complex<double>> c{1.0};
  for (const std::complex<double>& r : roots) {
    c.push_back(0.0);
    for (std::size_t j = c.size() - 1; j >= 1; --j) c[j] -= r * c[j - 1];
  }
  Polynomial p;
  for (const std::complex<double>& value : c) {
    assert(std::abs(value.imag()) <= 1e-9 * (1.0 + std::abs(value.real())));
    p.coefficients.push_back(value.real());
  }
  return p;
}

std::vector<std::complex<double>> roots(const Polynomial& p) {
  const int d = degree(p);
  assert(d >= 1 && p.coefficients[0] != 0.0);
  if (d == 1) return {-p.coefficients[1] / p.coefficients[0]};
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(d, d);
  for (int j = 0; j < d; ++j) companion(0, j) = -p.coefficients[static_cast<std::size_t>(j + 1)] / p.coefficients[0];
  for (int i = 1; i < d; ++i) companion(i, i - 1) = 1.0;
  const Eigen::VectorXcd eigenvalues = Eigen::EigenSolver<Eigen::MatrixXd>(companion, false).eigenvalues();
  return {eigenvalues.data(), eigenvalues.data() + eigenvalues.size()};
}

}  // namespace feedplan::control
