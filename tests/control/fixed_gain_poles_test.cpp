// The conventional ACC's closed-loop poles (seed 000/001 Eqs. 1–3, c1 = c2 = 0), computed apart from the
// module's code, against what its simulation does.
//
// The oracle. The plant's sampled matrices Φ, Γ come from integrating ẋ = A x + B u over one period with
// classical Runge–Kutta (2000 steps — the module uses the matrix exponential), the integral controller
// u_k = u_{k−1} − K_c Δt F_k (+ const) closes the loop on the state (f, ḟ, F, u_{k−1}), and Eigen's
// eigensolver gives the poles. The simulated error then follows the dominant pair once the faster modes
// have died out: fitting e_{k+1} = a e_k + b e_{k−1} to the simulated tail by least squares and solving
// z² − a z − b = 0 recovers that pair — its modulus is the decay (or growth) per period, its angle the
// oscillation.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <vector>

#include "feedplan/control/integral_force_controller.hpp"
#include "feedplan/control/turning_process.hpp"

namespace feedplan::control {
namespace {

constexpr double kPeriodS = 0.1;

struct SampledPlant {
  Eigen::Matrix3d phi;
  Eigen::Vector3d gamma;
};

// Φ and Γ by Runge–Kutta on the augmented system d/dt (x, u) = ([A B; 0 0]) (x, u).
SampledPlant sampled_by_runge_kutta(const TurningProcessParameters& p, double depth_mm) {
  const double wn = p.servo_natural_frequency_rad_per_s, zeta = p.servo_damping_ratio;
  const double kp = p.specific_cutting_force_n_per_mm2 * depth_mm / p.spindle_rpm;
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a(0, 1) = 1.0;
  a(1, 0) = -wn * wn;
  a(1, 1) = -2.0 * zeta * wn;
  a(1, 3) = p.servo_dc_gain * wn * wn;
  a(2, 0) = kp / p.process_time_constant_s;
  a(2, 2) = -1.0 / p.process_time_constant_s;
  Eigen::Matrix4d e = Eigen::Matrix4d::Identity();
  const int n = 2000;
  const double h = kPeriodS / n;
  for (int i = 0; i < n; ++i) {
    const Eigen::Matrix4d k1 = a * e, k2 = a * (e + 0.5 * h * k1), k3 = a * (e + 0.5 * h * k2), k4 = a * (e + h * k3);
    e += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return {e.topLeftCorner<3, 3>(), e.block<3, 1>(0, 3)};
}

// The dominant closed-loop pole (largest modulus, upper half plane) for the controller gain K_c.
std::complex<double> dominant_pole(const SampledPlant& plant, double controller_gain) {
  const double g = controller_gain * kPeriodS;
  const Eigen::RowVector3d c(0.0, 0.0, 1.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m.topLeftCorner<3, 3>() = plant.phi - plant.gamma * g * c;
  m.block<3, 1>(0, 3) = plant.gamma;
  m.block<1, 3>(3, 0) = -g * c;
  m(3, 3) = 1.0;
  const Eigen::Vector4cd poles = Eigen::EigenSolver<Eigen::Matrix4d>(m).eigenvalues();
  std::complex<double> best = poles(0);
  for (int i = 1; i < 4; ++i) {
    if (std::abs(poles(i)) > std::abs(best) + 1e-12 || (std::abs(std::abs(poles(i)) - std::abs(best)) <= 1e-12 && poles(i).imag() > best.imag())) {
      best = poles(i);
    }
  }
  return best.imag() < 0.0 ? std::conj(best) : best;
}

// The pair a second-order recurrence fits to e[first … last).
std::complex<double> fitted_pair(const std::vector<double>& e, std::size_t first, std::size_t last) {
  const Eigen::Index rows = static_cast<Eigen::Index>(last - first - 2);
  Eigen::MatrixXd x(rows, 2);
  Eigen::VectorXd y(rows);
  for (Eigen::Index r = 0; r < rows; ++r) {
    const std::size_t k = first + 1 + static_cast<std::size_t>(r);
    x(r, 0) = e[k];
    x(r, 1) = e[k - 1];
    y(r) = e[k + 1];
  }
  const Eigen::Vector2d ab = x.colPivHouseholderQr().solve(y);
  const std::complex<double> disc = std::sqrt(std::complex<double>(ab(0) * ab(0) + 4.0 * ab(1)));
  const std::complex<double> root = 0.5 * (ab(0) + disc);
  return root.imag() < 0.0 ? std::conj(root) : root;
}

// The force error of the module's plant and controller at a constant depth, started 0.1 % off the
// reference; the override's top is out of reach and the runs are short enough that the feed never reaches
// 0 (at 4 mm the error grows ×1.12 per sample from 1 N to about 240 N in 50 samples, the feed swings
// ±15 mm/min around 62.5), so the loop stays linear.
std::vector<double> simulated_error(double depth_mm, double controller_gain, int steps) {
  const TurningProcessParameters plant_parameters;
  const double reference = 1000.0;
  const double feed = reference / process_gain_n_per_mm_per_min(plant_parameters, depth_mm);
  IntegralControllerParameters p;
  p.reference_force_n = reference;
  p.controller_gain_mm_per_min_per_n_s = controller_gain;
  p.programmed_feed_mm_per_min = 1e6;
  p.override_range.max_ratio = 1.0;
  p.initial_feed_mm_per_min = 0.999 * feed;
  IntegralForceController controller(p);
  TurningProcess plant(plant_parameters, kPeriodS, depth_mm, 0.999 * feed);
  std::vector<double> error;
  double force = plant.force_n();
  for (int k = 0; k < steps; ++k) {
    force = plant.step(controller.step(force, kPeriodS) * p.programmed_feed_mm_per_min);
    error.push_back(force - reference);
  }
  return error;
}

// The gain tuned at 1 mm for a loop gain of 8 /s (K_p = 4 N per mm/min per mm of depth).
constexpr double kFixedGain = 8.0 / 4.0;

// At 4 mm the loop gain is 32 /s: the oracle's dominant pair lies outside the unit circle, and the
// simulation grows at that rate with that oscillation. Tolerance 1e-4 on modulus and angle: after 15 samples
// the faster modes have shrunk far below the growing dominant pair, and the fit sees little else.
TEST(FixedGainPoles, GrowthAtTheLargeDepthMatchesTheCharacteristicRoots) {
  const SampledPlant plant = sampled_by_runge_kutta(TurningProcessParameters{}, 4.0);
  const std::complex<double> oracle = dominant_pole(plant, kFixedGain);
  ASSERT_GT(std::abs(oracle), 1.0) << oracle;
  const std::vector<double> error = simulated_error(4.0, kFixedGain, 50);
  const std::complex<double> simulated = fitted_pair(error, 15, 50);
  EXPECT_NEAR(std::abs(simulated), std::abs(oracle), 1e-4);
  EXPECT_NEAR(std::arg(simulated), std::arg(oracle), 1e-4);
  std::printf("fixed gain at 4 mm: dominant pole |z| = %.4f (growth ×%.2f per s), %.3f rad per sample (period %.2f s)\n",
              std::abs(oracle), std::pow(std::abs(oracle), 1.0 / kPeriodS), std::arg(oracle),
              2.0 * 3.141592653589793 / std::arg(oracle) * kPeriodS);
}

// At 1 and 2 mm the same gain is stable, and the simulation decays as the oracle's pair says.
TEST(FixedGainPoles, DecayAtTheSmallDepthsMatchesTheCharacteristicRoots) {
  for (double depth_mm : {1.0, 2.0}) {
    const SampledPlant plant = sampled_by_runge_kutta(TurningProcessParameters{}, depth_mm);
    const std::complex<double> oracle = dominant_pole(plant, kFixedGain);
    ASSERT_LT(std::abs(oracle), 1.0) << depth_mm << " mm: " << oracle;
    const std::vector<double> error = simulated_error(depth_mm, kFixedGain, 40);
    const std::complex<double> simulated = fitted_pair(error, 10, 40);
    EXPECT_NEAR(std::abs(simulated), std::abs(oracle), 1e-3) << depth_mm << " mm";
    EXPECT_NEAR(std::arg(simulated), std::arg(oracle), 1e-3) << depth_mm << " mm";
  }
}

// Where the fixed loop turns unstable: the loop gain K_c K_p at which the oracle's dominant pole crosses
// the unit circle lies between 21 and 24 /s — the bound the variable-gain tests lean on (≈ 23 /s).
TEST(FixedGainPoles, StabilityLimitOfTheLoopGain) {
  const SampledPlant plant = sampled_by_runge_kutta(TurningProcessParameters{}, 1.0);
  const double kp = 4.0;
  EXPECT_LT(std::abs(dominant_pole(plant, 21.0 / kp)), 1.0);
  EXPECT_GT(std::abs(dominant_pole(plant, 24.0 / kp)), 1.0);
}

}  // namespace
}  // namespace feedplan::control
