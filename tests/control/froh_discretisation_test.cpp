// Seed 004's discrete models (Eqs. 4–5) against truths computed here, apart from the module's state-space
// route and matrix exponential:
//   - the zero-order hold (β = 0) against the closed-form ZOH transfer function of K/((τ1 s + 1)(τ2 s + 1))
//     by partial fractions, ZOH{1/(τ s + 1)} = (1 − p)/(z − p), p = e^{−T/τ};
//   - any β against Eq. 5 itself, (z − β)/z · Z[h_0 G] + β (z − 1)/(T z) · Z[h_0 G/s], with Z[h_0 G/s]
//     by partial fractions of G/s²;
//   - the sampled responses of the discrete model (its difference equation) to a step and to a seeded
//     random command sequence against classical Runge–Kutta on the continuous plant driven by the β-FROH's
//     reconstructed feed (milling_runge_kutta.hpp), also for equal time constants, where partial fractions
//     do not apply.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "feedplan/control/froh_discretisation.hpp"
#include "feedplan/control/milling_plant.hpp"
#include "milling_runge_kutta.hpp"

namespace feedplan::control {
namespace {

using Coefficients = std::vector<double>;  // highest power first

Coefficients times(const Coefficients& a, const Coefficients& b) {
  Coefficients c(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

Coefficients plus(Coefficients a, Coefficients b) {
  if (a.size() < b.size()) std::swap(a, b);
  for (std::size_t i = 0; i < b.size(); ++i) a[a.size() - b.size() + i] += b[i];
  return a;
}

Coefficients scaled_by(Coefficients a, double f) {
  for (double& c : a) c *= f;
  return a;
}

// The numerator and denominator of Eq. 5 in closed form for K/((τ1 s + 1)(τ2 s + 1)), τ1 ≠ τ2.
struct ClosedForm {
  Coefficients numerator, denominator;
};

ClosedForm equation_5(double k, double tau1, double tau2, double beta, double period) {
  const double p1 = std::exp(-period / tau1), p2 = std::exp(-period / tau2);
  const Coefficients d = times({1.0, -p1}, {1.0, -p2});
  const Coefficients zoh = scaled_by(plus(scaled_by({tau1 * (1.0 - p1), -tau1 * (1.0 - p1) * p2}, 1.0),
                                          scaled_by({tau2 * (1.0 - p2), -tau2 * (1.0 - p2) * p1}, -1.0)),
                                     k / (tau1 - tau2));
  if (beta == 0.0) return {zoh, d};
  const Coefficients ramp = times(plus({-(tau1 + tau2), tau1 + tau2}, {period}), d);  // (T − (τ1+τ2)(z−1)) D(z)
  const Coefficients lags = scaled_by(plus(scaled_by({1.0, -p2}, tau1 * tau1), scaled_by({1.0, -p1}, -tau2 * tau2)),
                                      1.0 / (tau1 - tau2));
  const Coefficients second = scaled_by(plus(ramp, times(times({1.0, -1.0}, {1.0, -1.0}), lags)), beta * k / period);
  return {plus(times({1.0, -beta}, zoh), second), times({1.0, 0.0}, d)};
}

// Compares coefficient by coefficient (padded at the high end), relative to the largest of `want`.
void expect_same_polynomial(const Polynomial& got, Coefficients want, double relative, const std::string& what) {
  Coefficients g = got.coefficients;
  while (g.size() < want.size()) g.insert(g.begin(), 0.0);
  while (want.size() < g.size()) want.insert(want.begin(), 0.0);
  double scale = 0.0;
  for (double c : want) scale = std::max(scale, std::abs(c));
  for (std::size_t i = 0; i < g.size(); ++i) EXPECT_NEAR(g[i], want[i], relative * scale) << what << ", coefficient " << i;
}

struct Plant {
  double depth_mm;
  double tau_m_s;
  double tau_c_s;
};

MillingPlantParameters parameters_of(const Plant& plant) {
  MillingPlantParameters p;
  p.feed_drive_time_constant_s = plant.tau_m_s;
  p.cutting_time_constant_s = plant.tau_c_s;
  return p;
}

// The paper's plant (τ_m = 0.1 ms, τ_c chosen: one tooth period) and one with a slow drive (τ_m = 30 ms),
// where the drive's pole is not at the origin. Tolerance 1e-9 of the largest coefficient: both sides are
// closed forms of double-precision exponentials; the matrix exponential's Padé approximant is accurate to a
// few units of rounding times the norm of A T (≈ 840 for τ_m = 0.1 ms), about 1e-13.
TEST(FrohDiscretisation, ZeroOrderHoldIsTheClosedFormAndEq5HoldsForEveryBeta) {
  const double t = spindle_period_s(MillingPlantParameters{});
  for (const Plant& plant : {Plant{3.0, 1e-4, 60.0 / (715.0 * 4.0)}, Plant{2.0, 0.03, 0.021}}) {
    const MillingPlantParameters p = parameters_of(plant);
    const double k = process_gain_n_s_per_mm(p, plant.depth_mm);
    for (double beta : {0.0, -1.0, -0.4, 0.3, 1.0}) {
      const DiscreteTransferFunction tf = froh_transfer_function(milling_system(p, plant.depth_mm), beta, t);
      const ClosedForm want = equation_5(k, plant.tau_m_s, plant.tau_c_s, beta, t);
      const std::string what = "τ_m = " + std::to_string(plant.tau_m_s) + ", β = " + std::to_string(beta);
      EXPECT_EQ(degree(tf.numerator), beta == 0.0 ? 1 : 2) << what;
      expect_same_polynomial(tf.numerator, want.numerator, 1e-9, what + " numerator");
      expect_same_polynomial(tf.denominator, want.denominator, 1e-9, what + " denominator");
    }
  }
}

// y_k of D(q) y = B(q) u from rest, u_k = 0 before k = 0.
std::vector<double> difference_equation_response(const DiscreteTransferFunction& tf, const std::vector<double>& u) {
  const int n = degree(tf.denominator), m = degree(tf.numerator);
  std::vector<double> y(u.size() + 1, 0.0);
  for (int k = 0; k <= static_cast<int>(u.size()); ++k) {
    double value = 0.0;
    for (int i = 1; i <= n; ++i) {
      if (k - i >= 0) value -= tf.denominator.coefficients[static_cast<std::size_t>(i)] * y[static_cast<std::size_t>(k - i)];
    }
    for (int i = 0; i <= m; ++i) {
      const int j = k - (n - m) - i;
      if (j >= 0 && j < static_cast<int>(u.size())) value += tf.numerator.coefficients[static_cast<std::size_t>(i)] * u[static_cast<std::size_t>(j)];
    }
    y[static_cast<std::size_t>(k)] = value;
  }
  return y;
}

// Step (10 mm/s from k = 0) and a random staircase (uniform 0–20 mm/s, std::mt19937 seed 4), 20 periods,
// for β ∈ {−1, −0.5, 0, 0.5, 1} on three plants: the paper's, a slow drive, and equal time constants
// (τ_m = τ_c, a double pole). Runge–Kutta with 8000 steps per period (h = 10.5 µs, h/τ_m ≈ 0.1 on the
// paper's plant): its error is of order (h/τ)⁵ per step on the fastest mode, far below the tolerance of
// 1e-9 of the force's scale (K_p × 10 mm/s, about 1 kN; about 5e-13 is seen).
TEST(FrohDiscretisation, SampledResponsesMatchRungeKuttaOnTheFrohReconstructedFeed) {
  const double t = spindle_period_s(MillingPlantParameters{});
  std::mt19937 random(4);
  std::uniform_real_distribution<double> feed(0.0, 20.0);
  std::vector<double> staircase;
  for (int k = 0; k < 20; ++k) staircase.push_back(feed(random));
  const std::vector<double> step(20, 10.0);
  double worst = 0.0;
  for (const Plant& plant : {Plant{3.0, 1e-4, 60.0 / (715.0 * 4.0)}, Plant{2.0, 0.03, 0.021}, Plant{2.0, 0.021, 0.021}}) {
    const MillingPlantParameters p = parameters_of(plant);
    const double k = process_gain_n_s_per_mm(p, plant.depth_mm);
    const test::PlantOde ode{k, plant.tau_m_s, plant.tau_c_s};
    for (double beta : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
      const DiscreteTransferFunction tf = froh_transfer_function(milling_system(p, plant.depth_mm), beta, t);
      for (const std::vector<double>* input : std::vector<const std::vector<double>*>{&step, &staircase}) {
        const std::vector<double> y = difference_equation_response(tf, *input);
        test::ContinuousTruth truth;
        double previous = 0.0;
        for (std::size_t i = 0; i < input->size(); ++i) {
          const double force = truth.step(ode, test::ReferenceOde{}, (*input)[i], previous, beta, 0.0, t, 8000);
          previous = (*input)[i];
          EXPECT_NEAR(y[i + 1], force, 1e-9 * k * 10.0) << "τ_m = " << plant.tau_m_s << ", β = " << beta << ", k = " << i + 1;
          worst = std::max(worst, std::abs(y[i + 1] - force) / (k * 10.0));
        }
      }
    }
  }
  std::printf("discrete model vs Runge–Kutta: largest difference %.2e of K_p × 10 mm/s (random staircase seed 4)\n", worst);
}

}  // namespace
}  // namespace feedplan::control
