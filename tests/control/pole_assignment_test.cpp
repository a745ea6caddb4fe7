// Seed 002's pole assignment (Eqs. 19–30). The oracle builds Φ(K) of Eq. 28 from the plant's canonical
// form (Eq. 20) and the gains the module returns, and takes its eigenvalues with Eigen — not the
// characteristic polynomial the module solves.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <complex>
#include <vector>

#include "feedplan/control/arma_model.hpp"
#include "feedplan/control/pole_assignment.hpp"

namespace feedplan::control {
namespace {

constexpr double kPeriodS = 0.1;

// Eq. 28 with Eq. 20's Φ, Γ, C_m = [0 1], the servo compensator of Eq. 22 (C*_d = 1, B*_d = T).
Eigen::Matrix4d closed_loop_matrix(const ArmaModel& m, const RobustServoGains& g, double period_s) {
  Eigen::Matrix2d phi;
  phi << 0.0, -m.phi2, 1.0, -m.phi1;
  const Eigen::Vector2d gamma(m.theta1, m.theta0);
  const Eigen::RowVector2d c(0.0, 1.0);
  Eigen::Matrix4d cl = Eigen::Matrix4d::Zero();
  cl.topLeftCorner<2, 2>() = phi + gamma * g.gamma3 * c;
  cl.block<2, 1>(0, 2) = gamma * g.k;
  cl.block<2, 1>(0, 3) = gamma * g.gamma4;
  cl.block<1, 2>(2, 0) = period_s * c;
  cl(2, 2) = 1.0;
  cl.block<1, 2>(3, 0) = g.gamma1 * c;
  cl(3, 2) = g.gamma2;
  cl(3, 3) = g.gamma0;
  return cl;
}

std::vector<double> sorted_real_eigenvalues(const Eigen::Matrix4d& m) {
  const Eigen::Vector4cd ev = Eigen::EigenSolver<Eigen::Matrix4d>(m).eigenvalues();
  std::vector<double> re;
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(ev(i).imag(), 0.0, 1e-6) << ev(i);
    re.push_back(ev(i).real());
  }
  std::sort(re.begin(), re.end());
  return re;
}

// Three plants: seed 002's feed drive with its first cut's gain (a zero outside the unit circle, φ2 = 0), a
// second-order plant with a minimum-phase zero, and one with complex poles. The eigenvalues agree with
// the requested poles to 1e-6 — distinct poles of a well-conditioned 4×4 move by about the rounding error
// times the condition of their eigenvectors, far below that.
TEST(PoleAssignment, ClosedLoopEigenvaluesAreTheRequestedPoles) {
  const std::vector<ArmaModel> plants{
      {-0.246597, 0.0, 0.339189, 0.707204},
      {-1.2, 0.35, 0.5, 0.3},
      {-1.0, 0.5, 2.0, -0.5},
  };
  const std::vector<std::array<double, 4>> pole_sets{kKimKimPoles, {0.1, -0.2, 0.5, 0.9}};
  for (const ArmaModel& plant : plants) {
    for (const auto& poles : pole_sets) {
      const PoleAssignment a = assign_poles(plant, poles, kPeriodS);
      ASSERT_EQ(a.status, PoleAssignmentStatus::kAssigned) << a.message;
      const std::vector<double> got = sorted_real_eigenvalues(closed_loop_matrix(plant, a.gains, kPeriodS));
      std::vector<double> want(poles.begin(), poles.end());
      std::sort(want.begin(), want.end());
      for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(got[i], want[i], 1e-6) << "plant phi1 = " << plant.phi1;
    }
  }
}

// Closed on the ARMA plant through Eqs. 22–24 themselves (η and ε stepped as printed, not the module's
// input–output form), the loop reaches the reference with no steady error — the servo compensator's
// integral action — and with seed 002's poles (slowest 0.75) within 1e-6 N after 100 samples: 0.75^100 ≈ 3e-13.
TEST(PoleAssignment, ServoEquationsReachTheReferenceWithoutSteadyError) {
  const ArmaModel plant{-1.2, 0.35, 0.5, 0.3};
  const PoleAssignment a = assign_poles(plant, kKimKimPoles, kPeriodS);
  ASSERT_EQ(a.status, PoleAssignmentStatus::kAssigned);
  const RobustServoGains& g = a.gains;
  ArmaPlant arma(plant, 100.0);
  const double reference = 500.0;
  double eta = 0.0, epsilon = 0.0, f = arma.force_n();
  for (int t = 0; t < 100; ++t) {
    const double v = g.k * eta + g.gamma3 * f + g.gamma4 * epsilon;
    const double next_epsilon = g.gamma0 * epsilon + g.gamma1 * f + g.gamma2 * eta;
    eta += kPeriodS * (f - reference);
    epsilon = next_epsilon;
    f = arma.step(v);
  }
  EXPECT_NEAR(f, reference, 1e-6);
}

// A plant whose zero z = −θ1/θ0 = 1 sits at the servo compensator's mode: no gains place the poles
// (seed 002's condition 4), and the assignment says so instead of returning gains.
TEST(PoleAssignment, ZeroAtTheCommandModeIsRefused) {
  const PoleAssignment a = assign_poles(ArmaModel{-1.2, 0.35, 0.5, -0.5}, kKimKimPoles, kPeriodS);
  EXPECT_EQ(a.status, PoleAssignmentStatus::kNotCoprime);
  EXPECT_NE(a.message.find("zero"), std::string::npos) << a.message;
}

}  // namespace
}  // namespace feedplan::control
