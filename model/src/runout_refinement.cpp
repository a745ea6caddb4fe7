#include "runout_refinement.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "bin_regressors.hpp"
#include "size_effect_search.hpp"

namespace feedplan::model::detail {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

MechanisticModel with_runout(const double* runout_rest_mm, int flutes, const RunoutSizeEffect& size) {
  MechanisticModel model;
  model.size_exponent = size.exponent;
  model.size_reference_chip_mm = size.reference_chip_mm;
  model.runout_mm.assign(static_cast<std::size_t>(flutes), 0.0);
  for (int j = 1; j < flutes; ++j) model.runout_mm[static_cast<std::size_t>(j)] = runout_rest_mm[j - 1];
  return model;
}

//! One test's bin residuals A(Ω₀, runout, β, m) · K − y; parameter blocks K (4), runout of teeth 1 … N−1, Ω₀ (1),
//! with identify_helix the helix angle β (1, deg, shared by all tests), then with size.refine the size
//! effect's exponent m (1, shared). All blocks are differenced by Ceres, K too although the residual is
//! linear in it: a cost function with A as K's Jacobian and only the other blocks differenced (13 bin
//! evaluations per Jacobian instead of 21) reached a worse minimum on steel-resonant's tests (RMS residual
//! 58.6 N against 20.9 N, the runout 2.5 µm instead of the machine's 12), so the cheaper Jacobian waits for
//! the reason.
struct BinResidual {
  const MechanisticCuttingTest* test;
  Eigen::VectorXd y;
  bool identify_helix = false;
  RunoutSizeEffect size;
  bool operator()(double const* const* p, double* residual) const {
    MechanisticModel runout = with_runout(p[1], test->cutter.flutes, size);
    int block = 3;
    if (identify_helix) runout.helix_deg = p[block++][0];
    if (size.refine) runout.size_exponent = p[block][0];
    const Eigen::MatrixXd a = phase_rows(*test, p[2][0], runout);
    const Eigen::Map<const Eigen::Vector4d> k(p[0]);
    Eigen::Map<Eigen::VectorXd>(residual, y.size()) = a * k - y;
    return true;
  }
};

//! Adds one test's residuals; `helix_deg` and `size_exponent` are the shared blocks to refine, or null to hold
//! them (the helix at the cutter's, the exponent at `size`'s).
void add_test(ceres::Problem& problem, const MechanisticCuttingTest& test, double* k, double* runout_rest, double* phase,
              double* helix_deg, RunoutSizeEffect size, double* size_exponent) {
  ceres::NumericDiffOptions diff;
  diff.relative_step_size = 1e-4;
  size.refine = size_exponent != nullptr;
  auto* cost = new ceres::DynamicNumericDiffCostFunction<BinResidual, ceres::CENTRAL>(
      new BinResidual{&test, measured(test), helix_deg != nullptr, size}, ceres::TAKE_OWNERSHIP, diff);
  cost->AddParameterBlock(kIdentifiedCoefficients);
  cost->AddParameterBlock(test.cutter.flutes - 1);
  cost->AddParameterBlock(1);
  if (helix_deg != nullptr) cost->AddParameterBlock(1);
  if (size_exponent != nullptr) cost->AddParameterBlock(1);
  cost->SetNumResiduals(2 * bin_count(test));
  std::vector<double*> blocks{k, runout_rest, phase};
  if (helix_deg != nullptr) blocks.push_back(helix_deg);
  if (size_exponent != nullptr) blocks.push_back(size_exponent);
  problem.AddResidualBlock(cost, nullptr, blocks);
  if (size_exponent != nullptr) {
    // The range the search covers (size_effect_search.hpp); the model needs m ≥ 0.
    problem.SetParameterLowerBound(size_exponent, 0, 0.0);
    problem.SetParameterUpperBound(size_exponent, 0, kMaxSizeExponent);
  }
  if (helix_deg != nullptr) {
    // The kernel needs |β| < 90°; a flute beyond ±kMaxHelixChangeDeg of the catalogue is not a tolerance.
    problem.SetParameterLowerBound(helix_deg, 0, test.cutter.helix_deg - kMaxHelixChangeDeg);
    problem.SetParameterUpperBound(helix_deg, 0, test.cutter.helix_deg + kMaxHelixChangeDeg);
  }
}

ceres::Solver::Summary solve(ceres::Problem& problem) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 50;
  options.function_tolerance = 1e-10;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary;
}

//! The tooth-period shift of a test's phase that fits the runout and coefficients best.
double best_shift(const MechanisticCuttingTest& test, double phase, const double* k, const double* runout_rest,
                  const RunoutSizeEffect& size) {
  const int flutes = test.cutter.flutes;
  const MechanisticModel model = with_runout(runout_rest, flutes, size);
  const Eigen::Map<const Eigen::Vector4d> coefficients(k);
  const Eigen::VectorXd y = measured(test);
  double best = phase, best_cost = std::numeric_limits<double>::infinity();
  for (int m = 0; m < flutes; ++m) {
    const double shifted = phase + m * kTwoPi / flutes;
    const double cost = (phase_rows(test, shifted, model) * coefficients - y).squaredNorm();
    if (cost < best_cost) {
      best_cost = cost;
      best = shifted;
    }
  }
  return best;
}

}  // namespace

RunoutRefinement refine_runout(const std::vector<MechanisticCuttingTest>& tests, const std::vector<double>& phases_rad,
                               const std::array<double, 4>& coefficients, bool identify_helix,
                               const RunoutSizeEffect& size) {
  const int flutes = tests.front().cutter.flutes;
  std::array<double, 4> k = coefficients;
  std::vector<double> runout_rest(static_cast<std::size_t>(flutes - 1), 0.0);
  std::vector<double> phases = phases_rad;
  double helix_deg = tests.front().cutter.helix_deg;
  double size_exponent = size.exponent;

  {
    ceres::Problem first;
    add_test(first, tests.front(), k.data(), runout_rest.data(), &phases.front(), nullptr, size, nullptr);
    solve(first);
  }
  for (std::size_t i = 1; i < tests.size(); ++i) {
    phases[i] = best_shift(tests[i], phases[i], k.data(), runout_rest.data(), size);
  }

  ceres::Problem problem;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    add_test(problem, tests[i], k.data(), runout_rest.data(), &phases[i], identify_helix ? &helix_deg : nullptr, size,
             size.refine ? &size_exponent : nullptr);
  }
  const ceres::Solver::Summary summary = solve(problem);

  RunoutRefinement result;
  if (identify_helix) result.helix_deg = helix_deg;
  result.size_exponent = size_exponent;
  result.runout_mm = with_runout(runout_rest.data(), flutes, size).runout_mm;
  for (double& phase : phases) phase -= kTwoPi * std::floor(phase / kTwoPi);
  result.phase_rad = phases;
  result.converged = summary.IsSolutionUsable();
  result.message = summary.BriefReport();
  return result;
}

}  // namespace feedplan::model::detail
