#pragma once
// Matching the cutting tests' measured per-revolution peaks (mechanistic identification, private to the model
// module; docs/method.md §5.7). The bins of the synchronous averages fix how the force is shaped over the
// revolution; what a plan holds is the peak the sensor reads in each revolution, and the mean of those peaks
// is not the peak of the mean: noise, the revolution-to-revolution scatter of a real cut and a dynamometer
// that rings all raise it. So the coefficients are fitted to both, as one weighted least-squares problem:
//
//   minimise  Σ_bins (y − A K)² / σ_b²  +  Σ_tests (P_i − peak_i(K))² / (s_i² + τ²)
//
// with σ_b² the bins' residual variance, P_i a test's mean per-revolution peak, s_i its standard error
// (the peaks' standard deviation / √n) and τ² the scatter of the peaks about the model beyond it (what the
// model cannot reproduce from test to test; estimated from the peak residuals, by moments, at every step).
// The peak is homogeneous of degree one in K for fixed runout, helix and size effect, peak_i(K) = g_i·K with
// g_i = ∂peak_i/∂K at the peak's angle, so the problem is solved by Gauss–Newton, each step a linear
// least-squares solve with g_i at the current K. With as many tests as coefficients or fewer the peaks are
// met (τ → 0) and the bins decide what they leave free.

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model/sensor_response.hpp"

namespace feedplan::model::detail {

//! Gauss–Newton steps of the peak matching.
inline constexpr int kPeakMatchingSteps = 8;

//! The outcome of matching the peaks.
struct PeakMatching {
  Eigen::Vector4d coefficients;                //!< K_tc, K_rc, K_te, K_re
  std::array<std::array<double, 4>, 4> covariance{};  //!< (AᵀA/σ_b² + Σ w_i g_i g_iᵀ)⁻¹
  int tests_matched = 0;                       //!< tests with at least 2 peaks
  double peak_rms_residual_n = 0.0;            //!< RMS of P_i − peak_i(K) over them, N
  double peak_scatter_n = 0.0;                 //!< τ, N
  double bins_rms_residual_n = 0.0;            //!< RMS of the bins' residual at the matched K, N
};

//! Whether any test has at least 2 revolution peaks to match.
bool has_peaks(const std::vector<MechanisticCuttingTest>& tests);

//! The coefficients matching the bins `a` K ≈ `y` (every test's rows at its phase, with `model`'s runout,
//! helix and size effect, read through `sensor` when given) and the tests' mean peaks, from `start`; the peaks
//! of the kernel's force, or of the sensor's reading when `sensor` is given. Needs has_peaks(tests).
PeakMatching match_peaks(const std::vector<MechanisticCuttingTest>& tests, const Eigen::MatrixXd& a,
                         const Eigen::VectorXd& y, const MechanisticModel& model,
                         const std::optional<SensorResponse>& sensor, const Eigen::Vector4d& start);

}  // namespace feedplan::model::detail
