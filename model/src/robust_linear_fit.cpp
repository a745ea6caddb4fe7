#include "robust_linear_fit.hpp"

#include <ceres/ceres.h>

#include <cassert>
#include <memory>

namespace feedplan::model::detail {
namespace {

//! r = ψᵀβ − y for one sample; linear, so the Jacobian is ψ itself.
class LinearResidual final : public ceres::SizedCostFunction<1, 6> {
 public:
  LinearResidual(const std::array<double, 6>& psi, double force_n) : psi_(psi), force_n_(force_n) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const double* beta = parameters[0];
    double predicted = 0.0;
    for (int j = 0; j < 6; ++j) predicted += psi_[j] * beta[j];
    residuals[0] = predicted - force_n_;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      for (int j = 0; j < 6; ++j) jacobians[0][j] = psi_[j];
    }
    return true;
  }

 private:
  std::array<double, 6> psi_;
  double force_n_;
};

}  // namespace

RobustLinearFit robust_linear_fit(const std::vector<std::array<double, 6>>& regressors,
                                  const std::vector<double>& forces_n, const std::vector<double>& weights,
                                  FitOptions::Loss loss, double scale_n, const std::array<bool, 6>& active,
                                  const std::array<double, 6>& initial, int max_iterations) {
  assert(loss == FitOptions::kHuber || loss == FitOptions::kCauchy);
  assert(regressors.size() == forces_n.size() && regressors.size() == weights.size());
  RobustLinearFit fit;
  fit.beta = initial;

  // One base loss shared by every sample's ScaledLoss; the ScaledLoss objects do not own it.
  std::unique_ptr<ceres::LossFunction> base_loss;
  if (loss == FitOptions::kHuber) {
    base_loss = std::make_unique<ceres::HuberLoss>(scale_n);
  } else {
    base_loss = std::make_unique<ceres::CauchyLoss>(scale_n);
  }
  ceres::Problem problem;
  for (std::size_t i = 0; i < regressors.size(); ++i) {
    problem.AddResidualBlock(new LinearResidual(regressors[i], forces_n[i]),
                             new ceres::ScaledLoss(base_loss.get(), weights[i], ceres::DO_NOT_TAKE_OWNERSHIP),
                             fit.beta.data());
  }
  std::vector<int> held;
  for (int j = 0; j < 6; ++j) {
    if (!active[j]) held.push_back(j);
  }
  if (!held.empty()) problem.SetManifold(fit.beta.data(), new ceres::SubsetManifold(6, held));

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = max_iterations;
  options.function_tolerance = 1e-10;
  options.gradient_tolerance = 1e-10;
  options.parameter_tolerance = 1e-10;
  options.logging_type = ceres::SILENT;
  options.minimizer_progress_to_stdout = false;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  fit.converged = summary.termination_type == ceres::CONVERGENCE;
  fit.iterations = static_cast<int>(summary.iterations.size()) - 1;  // entry 0 is the start
  fit.report = summary.message;
  return fit;
}

}  // namespace feedplan::model::detail
