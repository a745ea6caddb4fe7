#include "feedplan/learning/batch_refit.hpp"

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "feedplan/core/number_text.hpp"
#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using model::FitOptions;

constexpr double kExcitedVarianceRatio = 0.5;  // posterior/prior variance at or below which data dominate
constexpr const char* kBetaNames[6] = {"β0", "β1", "β2", "β11", "β22", "β12"};

std::string text(double value) { return shortest_number_text(value); }

std::string rounded(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

std::string loss_text(const BatchRefitOptions& options) {
  switch (options.loss) {
    case FitOptions::kSquared: return "squared loss";
    case FitOptions::kHuber: return "Huber loss (scale " + text(options.loss_scale_n) + " N)";
    case FitOptions::kCauchy: return "Cauchy loss (scale " + text(options.loss_scale_n) + " N)";
  }
  return "?";
}

//! u(r) = ρ'(r)/r, the loss's IRLS weight (step 3 of the file comment of batch_refit.hpp).
double irls_weight(FitOptions::Loss loss, double scale_n, double r) {
  switch (loss) {
    case FitOptions::kSquared: return 1.0;
    case FitOptions::kHuber: return std::abs(r) <= scale_n ? 1.0 : scale_n / std::abs(r);
    case FitOptions::kCauchy: return 1.0 / (1.0 + (r / scale_n) * (r / scale_n));
  }
  return 1.0;
}

//! r = ψᵀβ − F for one sample; linear, so the Jacobian is ψ itself.
class DataResidual final : public ceres::SizedCostFunction<1, 6> {
 public:
  DataResidual(const std::array<double, 6>& psi, double force_n) : psi_(psi), force_n_(force_n) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    double predicted = 0.0;
    for (int j = 0; j < 6; ++j) predicted += psi_[j] * parameters[0][j];
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

//! f_j = s_j (β_j − β_prior_j), s_j = √prior_weight / σ_j: ½ Σ f² is the prior term of step 2.
class PriorResidual final : public ceres::SizedCostFunction<6, 6> {
 public:
  PriorResidual(const std::array<double, 6>& prior, const std::array<double, 6>& scale)
      : prior_(prior), scale_(scale) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    for (int j = 0; j < 6; ++j) residuals[j] = scale_[j] * (parameters[0][j] - prior_[j]);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      for (int k = 0; k < 36; ++k) jacobians[0][k] = 0.0;
      for (int j = 0; j < 6; ++j) jacobians[0][j * 6 + j] = scale_[j];
    }
    return true;
  }

 private:
  std::array<double, 6> prior_;
  std::array<double, 6> scale_;
};

//! The data: regressors, forces and the weights w_i / σ_e².
struct Data {
  std::vector<std::array<double, 6>> psi;
  std::vector<double> force_n;
  std::vector<double> weight;  // w_i / σ_e², N⁻²
};

//! Minimises step 2's objective with a robust loss by Ceres from `beta` (overwritten with the last iterate).
bool robust_minimum(const Data& data, const std::array<double, 6>& prior, const std::array<double, 6>& prior_scale,
                    FitOptions::Loss loss, double scale_n, int max_iterations, std::array<double, 6>& beta,
                    std::string& report) {
  std::unique_ptr<ceres::LossFunction> base_loss;
  if (loss == FitOptions::kHuber) {
    base_loss = std::make_unique<ceres::HuberLoss>(scale_n);
  } else {
    base_loss = std::make_unique<ceres::CauchyLoss>(scale_n);
  }
  ceres::Problem problem;
  for (std::size_t i = 0; i < data.psi.size(); ++i) {
    problem.AddResidualBlock(new DataResidual(data.psi[i], data.force_n[i]),
                             new ceres::ScaledLoss(base_loss.get(), data.weight[i], ceres::DO_NOT_TAKE_OWNERSHIP),
                             beta.data());
  }
  problem.AddResidualBlock(new PriorResidual(prior, prior_scale), nullptr, beta.data());

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
  report = summary.message;
  return summary.termination_type == ceres::CONVERGENCE;
}

std::string list_names(const std::array<bool, 6>& mask, bool wanted) {
  std::string names;
  for (int j = 0; j < 6; ++j) {
    if (mask[j] != wanted) continue;
    if (!names.empty()) names += ", ";
    names += kBetaNames[j];
  }
  return names;
}

//! 1. Prior spread: σ_j into result.prior_sigma_n; returns √prior_weight / σ_j.
std::array<double, 6> prior_scale_of(const std::array<double, 6>& beta_prior, const BatchRefitOptions& options,
                                     BatchRefitResult& result) {
  std::array<double, 6> prior_scale{};  // √prior_weight / σ_j
  for (int j = 0; j < 6; ++j) {
    const double variance = options.prior_covariance_n2 ? options.prior_covariance_n2->variance(j) : 0.0;
    double sigma = std::sqrt(variance);
    if (!(sigma > 0.0)) {
      sigma = options.prior_sigma_fraction *
              std::max(std::abs(beta_prior[j]), options.prior_floor_fraction * std::abs(beta_prior[model::kBeta0]));
      if (!(sigma > 0.0)) sigma = 1.0;
    }
    result.prior_sigma_n[j] = sigma;
    prior_scale[j] = std::sqrt(options.prior_weight) / sigma;
  }
  return prior_scale;
}

//! No samples: the prior unchanged, with its own covariance.
void return_prior_unchanged(const BatchRefitOptions& options, BatchRefitResult& result) {
  result.status = BatchRefitStatus::kNotEnoughSamples;
  result.message = "no samples to refit: the prior model is returned unchanged";
  for (int j = 0; j < 6; ++j) {
    const double variance = result.prior_sigma_n[j] * result.prior_sigma_n[j] / options.prior_weight;
    result.covariance(j, j) = variance;
    result.standard_error_n[j] = std::sqrt(variance);
  }
}

//! The samples as regression data, widening `range` to hold them.
Data regression_data(const model::ResponseSurfaceModel& prior, const std::vector<LearningSample>& samples,
                     const BatchRefitOptions& options, model::FittedRange& range) {
  Data data;
  const double noise_variance = options.noise_sigma_n * options.noise_sigma_n;
  for (const LearningSample& s : samples) {
    data.psi.push_back(model::regressors(prior, s.chip_mm, s.contact_length_mm));
    data.force_n.push_back(s.force_n);
    data.weight.push_back(s.weight / noise_variance);
    range.chip_min_mm = std::min(range.chip_min_mm, s.chip_mm);
    range.chip_max_mm = std::max(range.chip_max_mm, s.chip_mm);
    range.contact_length_min_mm = std::min(range.contact_length_min_mm, s.contact_length_mm);
    range.contact_length_max_mm = std::max(range.contact_length_max_mm, s.contact_length_mm);
  }
  return data;
}

//! (Ψᵀ diag(a) Ψ + Λ), a_i the data weights times `factor(i)`.
template <class Factor>
Matrix6 information(const Data& data, const Vector6& prior_information, const Factor& factor) {
  Matrix6 h = prior_information.asDiagonal();
  for (std::size_t i = 0; i < data.psi.size(); ++i) {
    const Eigen::Map<const Vector6> psi(data.psi[i].data());
    h += (data.weight[i] * factor(i)) * psi * psi.transpose();
  }
  return h;
}

//! The estimate of step 2 and how the robust fit ended.
struct Estimate {
  std::array<double, 6> beta{};
  bool converged = true;
  std::string report;  // Ceres' message on the last robust fit
};

//! 2. Estimate: the closed form for squared loss, the start of the robust fits.
Estimate estimate(const Data& data, const std::array<double, 6>& beta_prior, const std::array<double, 6>& prior_scale,
                  const Vector6& prior_information, const BatchRefitOptions& options) {
  const Eigen::Map<const Vector6> beta_prior_vec(beta_prior.data());
  Vector6 rhs = prior_information.cwiseProduct(beta_prior_vec);
  for (std::size_t i = 0; i < data.psi.size(); ++i) {
    rhs += data.weight[i] * data.force_n[i] * Eigen::Map<const Vector6>(data.psi[i].data());
  }
  const Vector6 closed_form = information(data, prior_information, [](std::size_t) { return 1.0; }).ldlt().solve(rhs);
  Estimate e;
  std::array<double, 6>& beta = e.beta;
  Eigen::Map<Vector6>(beta.data()) = closed_form;
  if (options.loss == FitOptions::kCauchy) {
    robust_minimum(data, beta_prior, prior_scale, FitOptions::kHuber, options.loss_scale_n, options.max_iterations,
                   beta, e.report);
  }
  if (options.loss != FitOptions::kSquared) {
    e.converged = robust_minimum(data, beta_prior, prior_scale, options.loss, options.loss_scale_n,
                                 options.max_iterations, beta, e.report);
  }
  return e;
}

//! 3. Covariance and 4. excitation, at the final β.
void set_covariance_and_excitation(const Data& data, const std::array<double, 6>& beta, const Vector6& prior_information,
                                   const BatchRefitOptions& options, BatchRefitResult& result) {
  const Eigen::Map<const Vector6> beta_vec(beta.data());
  std::vector<double> robust_weight(data.psi.size());
  for (std::size_t i = 0; i < data.psi.size(); ++i) {
    const double r = data.force_n[i] - Eigen::Map<const Vector6>(data.psi[i].data()).dot(beta_vec);
    robust_weight[i] = irls_weight(options.loss, options.loss_scale_n, r);
    if (robust_weight[i] < 0.5) ++result.downweighted_count;
  }
  const Matrix6 covariance = information(data, prior_information, [&](std::size_t i) { return robust_weight[i]; }).inverse();
  Eigen::Map<Matrix6>(result.covariance.entries().data()) = 0.5 * (covariance + covariance.transpose());
  for (int j = 0; j < 6; ++j) {
    result.standard_error_n[j] = std::sqrt(std::max(covariance(j, j), 0.0));
    result.excited[j] = covariance(j, j) <= kExcitedVarianceRatio / prior_information(j);
  }
}

//! Status and message: the errors before and after, which coefficients the data determine, and
//! whether the robust fit converged.
void set_status_and_message(const Estimate& fit, const BatchRefitOptions& options, BatchRefitResult& result) {
  std::string summary = "refitted β to " + std::to_string(result.n) + " samples with " + loss_text(options) +
                        ": weighted RMS error " + rounded(result.rms_error_before_n) + " N with the prior, " +
                        rounded(result.rms_error_after_n) + " N refitted";
  const std::string excited = list_names(result.excited, true);
  const std::string unexcited = list_names(result.excited, false);
  summary += excited.empty() ? "; the data excite no coefficient more than the prior"
                             : "; the data determine " + excited;
  if (!unexcited.empty()) summary += "; " + unexcited + " stay set by the prior";
  if (result.downweighted_count > 0) {
    summary += "; the robust loss weighted " + std::to_string(result.downweighted_count) + " sample(s) below 1/2";
  }
  if (fit.converged) {
    result.status = BatchRefitStatus::kOk;
    result.message = summary;
  } else {
    result.status = BatchRefitStatus::kNoConvergence;
    result.message = "the robust refit did not converge within " + std::to_string(options.max_iterations) +
                     " iterations (Ceres: " + fit.report + "); the model is the last iterate. " + summary;
  }
}

}  // namespace

std::string to_string(BatchRefitStatus status) {
  switch (status) {
    case BatchRefitStatus::kOk: return "ok";
    case BatchRefitStatus::kNotEnoughSamples: return "not enough samples";
    case BatchRefitStatus::kNoConvergence: return "no convergence";
  }
  return "?";
}

std::vector<InputProblem> validate(const BatchRefitOptions& options) {
  std::vector<InputProblem> problems;
  if (options.loss != FitOptions::kSquared && options.loss != FitOptions::kHuber && options.loss != FitOptions::kCauchy) {
    problems.push_back({"refit.loss", "= " + std::to_string(static_cast<int>(options.loss)) +
                                          ": must be kSquared, kHuber or kCauchy"});
  }
  const auto positive = [&problems](const char* field, double value, const char* unit) {
    if (!(std::isfinite(value) && value > 0.0)) {
      problems.push_back({field, "= " + text(value) + ": must be finite and > 0" + unit});
    }
  };
  positive("refit.loss_scale_n", options.loss_scale_n, " N");
  positive("refit.noise_sigma_n", options.noise_sigma_n, " N");
  positive("refit.prior_weight", options.prior_weight, "");
  positive("refit.prior_sigma_fraction", options.prior_sigma_fraction, "");
  if (!(std::isfinite(options.prior_floor_fraction) && options.prior_floor_fraction >= 0.0)) {
    problems.push_back({"refit.prior_floor_fraction",
                        "= " + text(options.prior_floor_fraction) + ": must be finite and ≥ 0"});
  }
  if (options.prior_covariance_n2) {
    for (int j = 0; j < 6; ++j) {
      const double v = options.prior_covariance_n2->variance(j);
      if (!(std::isfinite(v) && v >= 0.0)) {
        problems.push_back({"refit.prior_covariance_n2[" + std::to_string(j * 6 + j) + "]",
                            "= " + text(v) + ": a variance (of " + kBetaNames[j] + ") must be finite and ≥ 0 N²"});
      }
    }
  }
  if (options.max_iterations < 1) {
    problems.push_back({"refit.max_iterations", "= " + std::to_string(options.max_iterations) + ": must be ≥ 1"});
  }
  return problems;
}

BatchRefitResult batch_refit(const model::ResponseSurfaceModel& prior, const std::vector<LearningSample>& samples,
                             const BatchRefitOptions& options) {
  std::vector<InputProblem> problems = validate(options);
  validate(prior, samples, problems);
  if (!problems.empty()) throw InputError(std::move(problems));

  BatchRefitResult result;
  result.model = prior;
  result.n = static_cast<int>(samples.size());

  const std::array<double, 6>& beta_prior = prior.beta;
  const std::array<double, 6> prior_scale = prior_scale_of(beta_prior, options, result);
  if (samples.empty()) {
    return_prior_unchanged(options, result);
    return result;
  }
  const Data data = regression_data(prior, samples, options, result.model.range);
  Vector6 prior_information;  // diagonal of Λ
  for (int j = 0; j < 6; ++j) prior_information(j) = prior_scale[j] * prior_scale[j];

  const Estimate fit = estimate(data, beta_prior, prior_scale, prior_information, options);
  result.model.beta = fit.beta;
  set_covariance_and_excitation(data, fit.beta, prior_information, options, result);

  result.rms_error_before_n = weighted_rms_error(prior, samples);
  result.rms_error_after_n = weighted_rms_error(result.model, samples);
  set_status_and_message(fit, options, result);
  return result;
}

}  // namespace feedplan::learning
