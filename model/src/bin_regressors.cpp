#include "bin_regressors.hpp"

#include <numbers>
#include <span>

#include "feedplan/model/mechanistic_force.hpp"

namespace feedplan::model::detail {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kColumn[kIdentifiedCoefficients] = {kKtc, kKrc, kKte, kKre};

//! The four XY regressor columns of one test at each of `spindle_rad` (one kernel set-up for them all,
//! mechanistic_force.hpp): rows 0 … 1 are Fx, Fy.
std::vector<XyRegressors> xy_regressors(const MechanisticCuttingTest& test, const MechanisticModel& model,
                                        std::span<const double> spindle_rad) {
  const EngagedSection section{0.0, test.axial_depth_mm, std::span<const ImmersionArc>(&test.arc, 1)};
  const std::vector<ForceRegressors> rows = regressors_at_angles(model, std::span<const EngagedSection>(&section, 1),
                                                                 test.cutter, test.feed_per_tooth_mm, spindle_rad);
  std::vector<XyRegressors> out(rows.size());
  for (std::size_t j = 0; j < rows.size(); ++j) {
    for (int axis = 0; axis < 2; ++axis) {
      for (int c = 0; c < kIdentifiedCoefficients; ++c) out[j][axis][c] = rows[j].rows[axis][kColumn[c]];
    }
  }
  return out;
}

//! The sub-step midpoints Ω₀ + 2π (k + ½) / steps, k = 0 … steps − 1.
std::vector<double> substep_angles(double phase_rad, int steps) {
  std::vector<double> angles(static_cast<std::size_t>(steps));
  for (int k = 0; k < steps; ++k) angles[static_cast<std::size_t>(k)] = phase_rad + kTwoPi * (k + 0.5) / steps;
  return angles;
}

}  // namespace

int bin_count(const MechanisticCuttingTest& test) { return static_cast<int>(test.synchronous_fx_n.size()); }

//! The regressors at the sub-step midpoints Ω_k = 2π (k + ½) / (bins · kPhaseStepsPerBin), k over a revolution.
std::vector<XyRegressors> regressor_table(const MechanisticCuttingTest& test) {
  const MechanisticModel plain;
  return xy_regressors(test, plain, substep_angles(0.0, bin_count(test) * kPhaseStepsPerBin));
}

//! The bin-averaged regressors (rows 0 … bins − 1: Fx, then bins … 2·bins − 1: Fy) at the phase offset of
//! `offset` sub-steps, read from the table.
Eigen::MatrixXd table_rows(const std::vector<XyRegressors>& table, int bins, int offset) {
  const int steps = bins * kPhaseStepsPerBin;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * bins, kIdentifiedCoefficients);
  for (int b = 0; b < bins; ++b) {
    for (int s = 0; s < kPhaseStepsPerBin; ++s) {
      const auto& r = table[static_cast<std::size_t>((offset + b * kPhaseStepsPerBin + s) % steps)];
      for (int c = 0; c < kIdentifiedCoefficients; ++c) {
        a(b, c) += r[0][c] / kPhaseStepsPerBin;
        a(bins + b, c) += r[1][c] / kPhaseStepsPerBin;
      }
    }
  }
  return a;
}

//! The bin-averaged regressors at any phase Ω₀, evaluated directly (same sub-steps as the table), with
//! the size effect and runout of `model`.
Eigen::MatrixXd phase_rows(const MechanisticCuttingTest& test, double phase_rad, const MechanisticModel& model) {
  const int bins = bin_count(test);
  const int steps = bins * kPhaseStepsPerBin;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * bins, kIdentifiedCoefficients);
  const std::vector<XyRegressors> substeps = xy_regressors(test, model, substep_angles(phase_rad, steps));
  for (int b = 0; b < bins; ++b) {
    for (int s = 0; s < kPhaseStepsPerBin; ++s) {
      const auto& r = substeps[static_cast<std::size_t>(b * kPhaseStepsPerBin + s)];
      for (int c = 0; c < kIdentifiedCoefficients; ++c) {
        a(b, c) += r[0][c] / kPhaseStepsPerBin;
        a(bins + b, c) += r[1][c] / kPhaseStepsPerBin;
      }
    }
  }
  return a;
}

Eigen::MatrixXd substep_regressors(const MechanisticCuttingTest& test, double phase_rad, const MechanisticModel& model) {
  const int steps = bin_count(test) * kPhaseStepsPerBin;
  Eigen::MatrixXd samples(steps, 2 * kIdentifiedCoefficients);
  const std::vector<XyRegressors> substeps = xy_regressors(test, model, substep_angles(phase_rad, steps));
  for (int j = 0; j < steps; ++j) {
    const auto& r = substeps[static_cast<std::size_t>(j)];
    for (int c = 0; c < kIdentifiedCoefficients; ++c) {
      samples(j, c) = r[0][c];
      samples(j, kIdentifiedCoefficients + c) = r[1][c];
    }
  }
  return samples;
}

Eigen::VectorXd measured(const MechanisticCuttingTest& test) {
  const int bins = bin_count(test);
  Eigen::VectorXd y(2 * bins);
  for (int b = 0; b < bins; ++b) {
    y(b) = test.synchronous_fx_n[static_cast<std::size_t>(b)];
    y(bins + b) = test.synchronous_fy_n[static_cast<std::size_t>(b)];
  }
  return y;
}

}  // namespace feedplan::model::detail
