#include "sensor_refinement.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "bin_regressors.hpp"
#include "runout_refinement.hpp"

namespace feedplan::model::detail {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr int kSensorParameters = 5;  // f_0, ζ_0, f_1, ζ_1, θ

SensorResponse sensor_of(const double* p) {
  SensorResponse s;
  s.modes[0] = {p[0], p[1]};
  s.modes[1] = {p[2], p[3]};
  s.mode_angle_deg = p[4];
  return s;
}

//! One test's bin residuals; parameter blocks K (4), the sensor (5), Ω₀ (1), then the runout of teeth
//! 1 … N−1 and the helix (1, deg) when refined. The spectrum depends on Ω₀, runout and helix only, not on K
//! or the sensor: it is kept for the last of those, so that the derivatives in K and the sensor cost no
//! kernel evaluation.
struct SensedBinResidual {
  const MechanisticCuttingTest* test;
  const SensedBinning* binning;
  Eigen::VectorXd y;
  bool runout = false;
  bool helix = false;
  double size_exponent = 0.0;
  double size_reference_chip_mm = 0.1;
  mutable std::vector<double> cached_key;
  mutable Eigen::MatrixXcd cached_spectrum;

  bool operator()(double const* const* p, double* residual) const {
    const int flutes = test->cutter.flutes;
    std::vector<double> key{p[2][0]};
    MechanisticModel model;
    model.size_exponent = size_exponent;
    model.size_reference_chip_mm = size_reference_chip_mm;
    int block = 3;
    if (runout) {
      model.runout_mm.assign(static_cast<std::size_t>(flutes), 0.0);
      for (int j = 1; j < flutes; ++j) model.runout_mm[static_cast<std::size_t>(j)] = p[block][j - 1];
      key.insert(key.end(), model.runout_mm.begin(), model.runout_mm.end());
      ++block;
    }
    if (helix) {
      model.helix_deg = p[block][0];
      key.push_back(p[block][0]);
    }
    if (key != cached_key) {
      cached_spectrum = binning->spectrum(*test, p[2][0], model);
      cached_key = std::move(key);
    }
    const Eigen::MatrixXd a = binning->rows(cached_spectrum, sensor_of(p[1]));
    const Eigen::Map<const Eigen::Vector4d> k(p[0]);
    Eigen::Map<Eigen::VectorXd>(residual, y.size()) = a * k - y;
    return true;
  }
};

ceres::Solver::Summary solve(ceres::Problem& problem) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 100;
  options.function_tolerance = 1e-10;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary;
}

}  // namespace

SensorRefinement refine_sensor(const std::vector<MechanisticCuttingTest>& tests,
                               const std::vector<SensedBinning>& binnings, const SensorRefinementStart& start,
                               double min_hz, double max_hz) {
  const int flutes = tests.front().cutter.flutes;
  std::array<double, 4> k = start.coefficients;
  double sensor[kSensorParameters] = {start.sensor.modes[0].natural_frequency_hz, start.sensor.modes[0].damping_ratio,
                                      start.sensor.modes[1].natural_frequency_hz, start.sensor.modes[1].damping_ratio,
                                      start.sensor.mode_angle_deg};
  std::vector<double> phases = start.phase_rad;
  const bool runout = !start.runout_mm.empty();
  std::vector<double> runout_rest;
  if (runout) {
    for (int j = 1; j < flutes; ++j) {
      runout_rest.push_back(start.runout_mm[static_cast<std::size_t>(j)] - start.runout_mm[0]);
    }
  }
  double helix_deg = start.helix_deg.value_or(tests.front().cutter.helix_deg);

  ceres::Problem problem;
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = 1e-4;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    auto* residual = new SensedBinResidual{&tests[i], &binnings[i], measured(tests[i]), runout, start.helix_deg.has_value(),
                                           start.size_exponent, start.size_reference_chip_mm, {}, {}};
    auto* cost = new ceres::DynamicNumericDiffCostFunction<SensedBinResidual, ceres::CENTRAL>(residual, ceres::TAKE_OWNERSHIP, diff);
    std::vector<double*> blocks{k.data(), sensor, &phases[i]};
    cost->AddParameterBlock(kIdentifiedCoefficients);
    cost->AddParameterBlock(kSensorParameters);
    cost->AddParameterBlock(1);
    if (runout) {
      cost->AddParameterBlock(flutes - 1);
      blocks.push_back(runout_rest.data());
    }
    if (start.helix_deg) {
      cost->AddParameterBlock(1);
      blocks.push_back(&helix_deg);
    }
    cost->SetNumResiduals(2 * bin_count(tests[i]));
    problem.AddResidualBlock(cost, nullptr, blocks);
  }
  for (int m = 0; m < 2; ++m) {
    problem.SetParameterLowerBound(sensor, 2 * m, min_hz);
    problem.SetParameterUpperBound(sensor, 2 * m, max_hz);
    problem.SetParameterLowerBound(sensor, 2 * m + 1, kMinRefinedDamping);
    problem.SetParameterUpperBound(sensor, 2 * m + 1, kMaxRefinedDamping);
  }
  problem.SetParameterLowerBound(sensor, 4, -90.0);
  problem.SetParameterUpperBound(sensor, 4, 90.0);
  if (start.helix_deg) {
    problem.SetParameterLowerBound(&helix_deg, 0, tests.front().cutter.helix_deg - kMaxHelixChangeDeg);
    problem.SetParameterUpperBound(&helix_deg, 0, tests.front().cutter.helix_deg + kMaxHelixChangeDeg);
  }
  const ceres::Solver::Summary summary = solve(problem);

  SensorRefinement result;
  result.sensor = sensor_of(sensor);
  // θ − 90° with the modes swapped is the same sensor (sensor_response.hpp): report θ in (−45°, 45°].
  while (result.sensor.mode_angle_deg > 45.0) {
    result.sensor.mode_angle_deg -= 90.0;
    std::swap(result.sensor.modes[0], result.sensor.modes[1]);
  }
  while (result.sensor.mode_angle_deg <= -45.0) {
    result.sensor.mode_angle_deg += 90.0;
    std::swap(result.sensor.modes[0], result.sensor.modes[1]);
  }
  result.coefficients = k;
  for (double& phase : phases) phase -= kTwoPi * std::floor(phase / kTwoPi);
  result.phase_rad = phases;
  if (runout) {
    result.runout_mm.assign(static_cast<std::size_t>(flutes), 0.0);
    for (int j = 1; j < flutes; ++j) result.runout_mm[static_cast<std::size_t>(j)] = runout_rest[static_cast<std::size_t>(j - 1)];
  }
  if (start.helix_deg) result.helix_deg = helix_deg;
  result.converged = summary.IsSolutionUsable();
  result.message = summary.BriefReport();
  return result;
}

}  // namespace feedplan::model::detail
