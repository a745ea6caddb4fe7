#include "peak_matching.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/sensed_peak.hpp"
#include "bin_regressors.hpp"
#include "identified_coefficients.hpp"

namespace feedplan::model::detail {
namespace {

//! A test's peak counts as known to no better than this fraction of it (noise-free synthetic tests have
//! identical peaks and a zero standard error).
constexpr double kPeakResolutionRel = 1e-3;

//! A test's mean peak and its standard error, N.
struct MeasuredPeak {
  std::size_t test = 0;
  double mean_n = 0.0;
  double standard_error_n = 0.0;
};

std::vector<MeasuredPeak> measured_peaks(const std::vector<MechanisticCuttingTest>& tests) {
  std::vector<MeasuredPeak> peaks;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const std::vector<double>& p = tests[i].revolution_peaks_n;
    if (p.size() < 2) continue;
    double mean = 0.0;
    for (double v : p) mean += v;
    mean /= static_cast<double>(p.size());
    double ss = 0.0;
    for (double v : p) ss += (v - mean) * (v - mean);
    const double sd = std::sqrt(ss / static_cast<double>(p.size() - 1));
    peaks.push_back({i, mean, std::hypot(sd / std::sqrt(static_cast<double>(p.size())), kPeakResolutionRel * mean)});
  }
  return peaks;
}

//! g = ∂peak/∂K of one test at `model`'s coefficients (the peak is then g·K).
Eigen::Vector4d test_peak_gradient(const MechanisticCuttingTest& test, const MechanisticModel& model,
                                   const std::optional<SensorResponse>& sensor) {
  const EngagedSection section{0.0, test.axial_depth_mm, std::span<const ImmersionArc>(&test.arc, 1)};
  const std::span<const EngagedSection> sections(&section, 1);
  std::array<double, 6> row_x{}, row_y{};
  if (sensor) {
    const SensedPeak peak = predicted_sensed_peak(model, sections, test.cutter, test.feed_per_tooth_mm, *sensor,
                                                  test.spindle_rpm);
    row_x = peak.regressors[0];
    row_y = peak.regressors[1];
  } else {
    const MechanisticPeak peak = predicted_peak(model, sections, test.cutter, test.feed_per_tooth_mm);
    const ForceRegressors r = regressors(model, sections, test.cutter, test.feed_per_tooth_mm, peak.spindle_angle_rad);
    row_x = r.rows[0];
    row_y = r.rows[1];
  }
  const std::array<double, 4> g = detail::peak_gradient(row_x, row_y, model);
  return Eigen::Vector4d(g[0], g[1], g[2], g[3]);
}

//! The weighted least-squares solution of m x ≈ r with m's columns scaled to unit norm, and (mᵀm)⁻¹.
Eigen::Vector4d solve_scaled(const Eigen::MatrixXd& m, const Eigen::VectorXd& r, Eigen::Matrix4d& inverse_normal) {
  Eigen::Vector4d scale = m.colwise().norm().transpose();
  for (int c = 0; c < 4; ++c) {
    if (scale(c) == 0.0) scale(c) = 1.0;
  }
  const Eigen::MatrixXd scaled = m * scale.cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  Eigen::Matrix4d inner = Eigen::Matrix4d::Zero();
  for (int k = 0; k < 4; ++k) {
    if (sv(k) > 0.0) inner += svd.matrixV().col(k) * svd.matrixV().col(k).transpose() / (sv(k) * sv(k));
  }
  inverse_normal = scale.cwiseInverse().asDiagonal() * inner * scale.cwiseInverse().asDiagonal();
  return scale.cwiseInverse().asDiagonal() * svd.solve(r);
}

}  // namespace

bool has_peaks(const std::vector<MechanisticCuttingTest>& tests) {
  return std::any_of(tests.begin(), tests.end(), [](const MechanisticCuttingTest& t) { return t.revolution_peaks_n.size() >= 2; });
}

PeakMatching match_peaks(const std::vector<MechanisticCuttingTest>& tests, const Eigen::MatrixXd& a,
                         const Eigen::VectorXd& y, const MechanisticModel& model,
                         const std::optional<SensorResponse>& sensor, const Eigen::Vector4d& start) {
  const std::vector<MeasuredPeak> peaks = measured_peaks(tests);
  const Eigen::Index bins = a.rows();
  const double bins_variance_n2 =
      std::max((a * start - y).squaredNorm() / static_cast<double>(std::max<Eigen::Index>(bins - 4, 1)), 1e-12);
  const double bins_weight = 1.0 / std::sqrt(bins_variance_n2);
  const auto n = static_cast<Eigen::Index>(peaks.size());

  PeakMatching result;
  result.tests_matched = static_cast<int>(n);
  Eigen::Vector4d k = start;
  Eigen::Matrix4d inverse_normal = Eigen::Matrix4d::Zero();
  double scatter_n2 = 0.0;
  MechanisticModel current = model;
  Eigen::MatrixXd m(bins + n, 4);
  Eigen::VectorXd r(bins + n);
  m.topRows(bins) = bins_weight * a;
  r.head(bins) = bins_weight * y;
  Eigen::MatrixXd g(n, 4);
  for (int step = 0; step < kPeakMatchingSteps; ++step) {
    set_identified_coefficients(current, k);
    for (Eigen::Index i = 0; i < n; ++i) g.row(i) = test_peak_gradient(tests[peaks[i].test], current, sensor).transpose();
    // τ² by moments from the residuals of the previous step (0 before the first: the peaks are trusted
    // first): what the peaks scatter about the model beyond their standard errors, over the degrees of freedom
    // the coefficients leave. With no more peaks than coefficients they can all be met: 0.
    if (step > 0 && n > 4) {
      double excess_n2 = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) {
        const double residual_n = peaks[i].mean_n - g.row(i).dot(k);
        excess_n2 += residual_n * residual_n - peaks[i].standard_error_n * peaks[i].standard_error_n;
      }
      scatter_n2 = std::max(0.0, excess_n2 / static_cast<double>(n - 4));
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      const double w = 1.0 / std::sqrt(peaks[i].standard_error_n * peaks[i].standard_error_n + scatter_n2);
      m.row(bins + i) = w * g.row(i);
      r(bins + i) = w * peaks[i].mean_n;
    }
    k = solve_scaled(m, r, inverse_normal);
  }
  set_identified_coefficients(current, k);
  double ss = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double residual_n = peaks[i].mean_n - test_peak_gradient(tests[peaks[i].test], current, sensor).dot(k);
    ss += residual_n * residual_n;
  }
  result.coefficients = k;
  result.peak_rms_residual_n = n > 0 ? std::sqrt(ss / static_cast<double>(n)) : 0.0;
  result.peak_scatter_n = std::sqrt(scatter_n2);
  result.bins_rms_residual_n = std::sqrt((a * k - y).squaredNorm() / static_cast<double>(std::max<Eigen::Index>(bins, 1)));
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) result.covariance[i][j] = inverse_normal(i, j);
  }
  return result;
}

}  // namespace feedplan::model::detail
