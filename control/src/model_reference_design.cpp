#include "feedplan/control/model_reference_design.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <vector>

#include "feedplan/core/number_text.hpp"

namespace feedplan::control {
namespace {

double largest_magnitude(const Polynomial& p) {
  double m = 0.0;
  for (double c : p.coefficients) m = std::max(m, std::abs(c));
  return m;
}

std::string roots_text(const std::vector<std::complex<double>>& rs) {
  std::string text;
  for (const auto& r : rs) {
    if (!text.empty()) text += ", ";
    text += six_digit_number_text(r.real());
    if (r.imag() != 0.0) text += (r.imag() > 0 ? " + " : " − ") + six_digit_number_text(std::abs(r.imag())) + "i";
  }
  return text;
}

//! B = B⁺ B⁻ split by the cancellation radius.
struct ZeroSplit {
  Polynomial cancelled;  // B⁺, monic
  Polynomial kept;       // B⁻, with B's leading coefficient
};

ZeroSplit split_zeros(const Polynomial& b, double cancellation_radius) {
  std::vector<std::complex<double>> cancelled, kept;
  if (degree(b) >= 1) {
    for (const std::complex<double>& z : roots(b)) (std::abs(z) < cancellation_radius ? cancelled : kept).push_back(z);
  }
  return {monic_from_roots(cancelled), scaled(monic_from_roots(kept), b.coefficients[0])};
}

//! R1 (monic, degree deg A_d − n) and S (degree n − 1) with A R1 + B⁻ S = A_d; false when the Sylvester
//! matrix is singular to 1e-12 of its largest singular value.
bool solve_diophantine(const Polynomial& a, const Polynomial& kept, const Polynomial& desired, Polynomial& r1, Polynomial& s) {
  const int n = degree(a);
  const int d = degree(desired) - n;
  const int size = n + d;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(size, size);
  Eigen::VectorXd rhs(size);
  for (int p = 0; p < size; ++p) {
    const int row = size - 1 - p;  // highest power first
    for (int i = 1; i <= d; ++i) m(row, i - 1) = coefficient(a, p - (d - i));
    for (int j = 0; j < n; ++j) m(row, d + j) = coefficient(kept, p - (n - 1 - j));
    rhs(row) = coefficient(desired, p) - coefficient(a, p - d);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  if (!(sv(size - 1) > 1e-12 * sv(0))) return false;
  const Eigen::VectorXd x = svd.solve(rhs);
  r1.coefficients = {1.0};
  for (int i = 0; i < d; ++i) r1.coefficients.push_back(x(i));
  s.coefficients.clear();
  for (int j = 0; j < n; ++j) s.coefficients.push_back(x(d + j));
  return true;
}

}  // namespace

ModelReferenceDesign design_model_reference(const DiscreteTransferFunction& plant, const DiscreteTransferFunction& reference,
                                            double cancellation_radius) {
  const int n = degree(plant.denominator);
  assert(n >= 1 && degree(reference.denominator) == n);
  assert(plant.denominator.coefficients[0] == 1.0 && reference.denominator.coefficients[0] == 1.0);
  assert(degree(plant.numerator) <= n - 1 && degree(reference.numerator) <= n - 1);
  assert(cancellation_radius > 0.0 && cancellation_radius <= 1.0);
  ModelReferenceDesign design;

  const std::vector<std::complex<double>> reference_poles = roots(reference.denominator);
  for (const auto& p : reference_poles) {
    if (!(std::abs(p) < 1.0)) {
      design.status = ModelReferenceStatus::kUnstableReference;
      design.message = "the reference model's poles " + roots_text(reference_poles) + " are not all inside the unit circle";
      return design;
    }
  }
  // Pad B to degree n − 1 so that its leading coefficient is the one the relative degree rests on.
  Polynomial b = plant.numerator;
  while (degree(b) < n - 1) b.coefficients.insert(b.coefficients.begin(), 0.0);
  if (b.coefficients.empty() || !(std::abs(b.coefficients[0]) > 1e-12 * largest_magnitude(b))) {
    design.status = ModelReferenceStatus::kDegenerateZeros;
    design.message = "the plant's numerator has a (nearly) vanishing leading coefficient: its relative degree is above one";
    return design;
  }
  const ZeroSplit split = split_zeros(b, cancellation_radius);
  design.cancelled_zeros = split.cancelled;
  design.kept_zeros = split.kept;
  const double kept_at_one = evaluate(split.kept, 1.0);
  if (!(std::abs(kept_at_one) > 1e-12 * largest_magnitude(split.kept))) {
    design.status = ModelReferenceStatus::kZeroAtOne;
    design.message = "a kept zero of the plant sits at z = 1 (zeros " + roots_text(roots(b)) + ")";
    return design;
  }
  Polynomial shift{{1.0}};
  for (int i = 0; i < degree(split.kept); ++i) shift.coefficients.push_back(0.0);
  const Polynomial desired = multiply(shift, reference.denominator);
  design.closed_loop_polynomial = multiply(split.cancelled, desired);

  Polynomial r1, s;
  if (!solve_diophantine(plant.denominator, split.kept, desired, r1, s)) {
    design.status = ModelReferenceStatus::kNotCoprime;
    design.message = "the plant's poles and its kept zeros (" + roots_text(roots(b)) + ") (nearly) coincide";
    return design;
  }
  design.controller.r = multiply(split.cancelled, r1);
  design.controller.s = s;
  design.controller.t = scaled(reference.numerator, 1.0 / kept_at_one);
  design.status = ModelReferenceStatus::kDesigned;
  return design;
}

double model_reference_command(const ModelReferenceController& c, std::span<const double> reference_n,
                               std::span<const double> force_n, std::span<const double> past_commands) {
  const int top = degree(c.r);  // n − 1
  assert(top >= 0 && reference_n.size() >= static_cast<std::size_t>(top + 1) &&
         force_n.size() >= static_cast<std::size_t>(top + 1) && past_commands.size() >= static_cast<std::size_t>(top));
  double command = 0.0;
  for (int i = 0; i <= top; ++i) {
    const auto k = static_cast<std::size_t>(i);
    command += coefficient(c.t, top - i) * reference_n[k] - coefficient(c.s, top - i) * force_n[k];
    if (i >= 1) command -= coefficient(c.r, top - i) * past_commands[k - 1];
  }
  return command;
}

}  // namespace feedplan::control
