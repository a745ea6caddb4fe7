#include "sensed_bin_rows.hpp"

#include <cassert>
#include <complex>
#include <numbers>

#include "bin_regressors.hpp"

namespace feedplan::model::detail {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

SensedBinning::SensedBinning(const MechanisticCuttingTest& test)
    : bins_(bin_count(test)), revolution_hz_(test.spindle_rpm / 60.0) {
  assert(test.spindle_rpm > 0.0);
  const int m = bins_ * kPhaseStepsPerBin;
  const int harmonics = m / 2 + 1;
  transform_.resize(harmonics, m);
  for (int k = 0; k < harmonics; ++k) {
    for (int j = 0; j < m; ++j) transform_(k, j) = std::polar(1.0 / m, -kTwoPi * ((k * j) % m) / m);
  }
  bin_average_.resize(bins_, harmonics);
  for (int k = 0; k < harmonics; ++k) {
    const double weight = k == 0 || 2 * k == m ? 1.0 : 2.0;
    std::complex<double> substeps = 0.0;
    for (int s = 0; s < kPhaseStepsPerBin; ++s) substeps += std::polar(1.0, kTwoPi * k * s / m);
    substeps *= weight / kPhaseStepsPerBin;
    for (int b = 0; b < bins_; ++b) bin_average_(b, k) = substeps * std::polar(1.0, kTwoPi * ((k * b * kPhaseStepsPerBin) % m) / m);
  }
}

Eigen::MatrixXcd SensedBinning::spectrum(const MechanisticCuttingTest& test, double phase_rad,
                                         const MechanisticModel& model) const {
  return transform_ * substep_regressors(test, phase_rad, model).cast<std::complex<double>>();
}

Eigen::MatrixXd SensedBinning::rows(const Eigen::MatrixXcd& spectrum, const SensorResponse& sensor) const {
  Eigen::MatrixXcd read(spectrum.rows(), spectrum.cols());
  for (Eigen::Index k = 0; k < spectrum.rows(); ++k) {
    const SensorGain g = sensor_gain(sensor, static_cast<double>(k) * revolution_hz_);
    for (int c = 0; c < kIdentifiedCoefficients; ++c) {
      const std::complex<double> fx = spectrum(k, c), fy = spectrum(k, kIdentifiedCoefficients + c);
      read(k, c) = g.xy[0][0] * fx + g.xy[0][1] * fy;
      read(k, kIdentifiedCoefficients + c) = g.xy[1][0] * fx + g.xy[1][1] * fy;
    }
  }
  const Eigen::MatrixXd binned = (bin_average_ * read).real();  // bins × 8
  Eigen::MatrixXd a(2 * bins_, kIdentifiedCoefficients);
  a.topRows(bins_) = binned.leftCols(kIdentifiedCoefficients);
  a.bottomRows(bins_) = binned.rightCols(kIdentifiedCoefficients);
  return a;
}

}  // namespace feedplan::model::detail
