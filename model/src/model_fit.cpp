#include "feedplan/model/model_fit.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "feedplan/core/number_text.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "robust_linear_fit.hpp"

namespace feedplan::model {
namespace {

constexpr double kRankTolerance = 1e-9;      // σ_min/σ_max at or below which the design is rank-deficient
constexpr double kLeverageOne = 1.0 - 1e-9;  // h_ii at or above this: the sample alone fixes a coefficient
constexpr const char* kBetaNames[6] = {"β0", "β1", "β2", "β11", "β22", "β12"};

std::string number(double value) { return six_digit_number_text(value); }

std::string rounded(double value, const char* format = "%.3g") {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

void check_samples(const std::vector<FitSample>& samples, std::vector<InputProblem>& problems) {
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const FitSample& s = samples[i];
    const std::string prefix = "samples[" + std::to_string(i) + "].";
    if (!std::isfinite(s.chip_mm) || s.chip_mm < 0.0) {
      problems.push_back({prefix + "chip_mm", "= " + shortest_number_text(s.chip_mm) + ": must be finite and ≥ 0"});
    }
    if (!std::isfinite(s.contact_length_mm) || s.contact_length_mm < 0.0) {
      problems.push_back({prefix + "contact_length_mm",
                          "= " + shortest_number_text(s.contact_length_mm) + ": must be finite and ≥ 0"});
    }
    if (!std::isfinite(s.force_n)) {
      problems.push_back({prefix + "force_n", "= " + shortest_number_text(s.force_n) + ": must be finite"});
    }
    if (!std::isfinite(s.weight) || s.weight <= 0.0) {
      problems.push_back({prefix + "weight", "= " + shortest_number_text(s.weight) + ": must be finite and > 0"});
    }
  }
}

//! The spread of one input over the samples.
struct InputSpread {
  double min = 0.0;
  double max = 0.0;
  bool varies = false;
  int distinct = 0;  // distinct values, those closer than the tolerance counted as one
};

InputSpread spread(const std::vector<double>& values, double tolerance) {
  InputSpread result;
  std::vector<double> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  result.min = sorted.front();
  result.max = sorted.back();
  const double gap = tolerance * std::max(std::abs(result.min), std::abs(result.max));
  result.varies = result.max - result.min > gap;
  result.distinct = 1;
  double level = sorted.front();
  for (double v : sorted) {
    if (v - level > gap) {
      ++result.distinct;
      level = v;
    }
  }
  return result;
}

//! Centre = mid-range, scale = half range; |centre| (1 when 0) for an input that did not vary.
void normalisation(const InputSpread& s, double& centre, double& scale) {
  centre = 0.5 * (s.min + s.max);
  scale = s.varies ? 0.5 * (s.max - s.min) : (centre != 0.0 ? std::abs(centre) : 1.0);
}

std::string loss_text(const FitOptions& options) {
  switch (options.loss) {
    case FitOptions::kSquared: return "squared loss";
    case FitOptions::kHuber: return "Huber loss (scale " + number(options.loss_scale_n) + " N)";
    case FitOptions::kCauchy: return "Cauchy loss (scale " + number(options.loss_scale_n) + " N)";
  }
  return "?";
}

//! ψ(r), ψ'(r) and the IRLS weight u(r) = ψ(r)/r of the loss (file comment of model_fit.hpp, step 4).
struct LossDerivatives {
  double psi = 0.0;
  double psi_prime = 0.0;
  double irls_weight = 1.0;
};

LossDerivatives loss_derivatives(FitOptions::Loss loss, double scale_n, double r) {
  switch (loss) {
    case FitOptions::kSquared: return {r, 1.0, 1.0};
    case FitOptions::kHuber:
      if (std::abs(r) <= scale_n) return {r, 1.0, 1.0};
      return {std::copysign(scale_n, r), 0.0, scale_n / std::abs(r)};
    case FitOptions::kCauchy: {
      const double q = (r / scale_n) * (r / scale_n);
      return {r / (1.0 + q), (1.0 - q) / ((1.0 + q) * (1.0 + q)), 1.0 / (1.0 + q)};
    }
  }
  return {};
}

std::string list_names(const std::array<bool, 6>& mask, bool wanted) {
  std::string text;
  for (int j = 0; j < 6; ++j) {
    if (mask[j] != wanted) continue;
    if (!text.empty()) text += ", ";
    text += kBetaNames[j];
  }
  return text;
}

}  // namespace

std::string to_string(FitStatus status) {
  switch (status) {
    case FitStatus::kOk: return "ok";
    case FitStatus::kReducedModel: return "reduced model";
    case FitStatus::kInsufficientData: return "insufficient data";
    case FitStatus::kNotConverged: return "not converged";
  }
  return "?";
}

std::vector<InputProblem> validate(const FitOptions& options) {
  std::vector<InputProblem> problems;
  if (options.loss != FitOptions::kSquared && options.loss != FitOptions::kHuber && options.loss != FitOptions::kCauchy) {
    problems.push_back({"options.loss", "= " + std::to_string(static_cast<int>(options.loss)) +
                                            ": must be kSquared, kHuber or kCauchy"});
  }
  if (!std::isfinite(options.loss_scale_n) || options.loss_scale_n <= 0.0) {
    problems.push_back({"options.loss_scale_n", "= " + shortest_number_text(options.loss_scale_n) +
                                                    ": must be finite and > 0 N"});
  }
  if (!(options.same_value_tolerance >= 0.0 && options.same_value_tolerance < 1.0)) {
    problems.push_back({"options.same_value_tolerance",
                        "= " + shortest_number_text(options.same_value_tolerance) + ": must be in [0, 1)"});
  }
  if (options.max_iterations < 1) {
    problems.push_back({"options.max_iterations", "= " + std::to_string(options.max_iterations) + ": must be ≥ 1"});
  }
  return problems;
}

FitResult fit_model(const std::vector<FitSample>& samples, const FitOptions& options) {
  std::vector<InputProblem> problems = validate(options);
  check_samples(samples, problems);
  if (!problems.empty()) throw InputError(std::move(problems));

  FitResult result;
  result.status = FitStatus::kInsufficientData;
  result.n = static_cast<int>(samples.size());
  if (samples.empty()) {
    result.message = "no samples to fit";
    return result;
  }

  // 1. Normalisation and range from the data.
  std::vector<double> chips, lengths;
  for (const FitSample& s : samples) {
    chips.push_back(s.chip_mm);
    lengths.push_back(s.contact_length_mm);
  }
  const InputSpread chip = spread(chips, options.same_value_tolerance);
  const InputSpread length = spread(lengths, options.same_value_tolerance);
  ResponseSurfaceModel& model = result.model;
  normalisation(chip, model.chip_center_mm, model.chip_scale_mm);
  normalisation(length, model.contact_length_center_mm, model.contact_length_scale_mm);
  model.range = {chip.min, chip.max, length.min, length.max};

  // 2. Identifiability: which coefficients the data can determine.
  std::array<bool, 6> active{true, true, true, true, true, true};
  std::string held_reason;
  if (!chip.varies && !length.varies) {
    result.message = "neither t_m nor L varied (all " + std::to_string(result.n) + " samples at t_m = " +
                     number(chip.min) + " mm, L = " + number(length.min) +
                     " mm): the data say nothing about how the force depends on either";
    return result;
  }
  if (!chip.varies || !length.varies) {
    const bool chip_fixed = !chip.varies;
    if (chip_fixed) {
      active[kBeta1] = active[kBeta11] = active[kBeta12] = false;
    } else {
      active[kBeta2] = active[kBeta22] = active[kBeta12] = false;
    }
    held_reason = std::string(chip_fixed ? "t_m" : "L") + " did not vary (all samples at " +
                  (chip_fixed ? "t_m = " + number(chip.min) : "L = " + number(length.min)) + " mm)";
    if (!options.allow_reduced_model) {
      result.message = held_reason + ", so " + list_names(active, false) +
                       " cannot be estimated, and allow_reduced_model is off";
      return result;
    }
  }
  std::vector<int> columns;
  for (int j = 0; j < 6; ++j) {
    if (active[j]) columns.push_back(j);
  }
  const int p = static_cast<int>(columns.size());
  const int n = result.n;
  if (n <= p) {
    result.message = std::to_string(n) + " samples for " + std::to_string(p) + " coefficients (" +
                     list_names(active, true) + "): at least " + std::to_string(p + 1) +
                     " are needed — " + std::to_string(p) + " to determine them and one more to estimate their uncertainty";
    return result;
  }

  std::vector<std::array<double, 6>> psi(samples.size());
  std::vector<double> y(samples.size()), w(samples.size());
  Eigen::MatrixXd x(n, p);  // the design over the estimated coefficients
  for (int i = 0; i < n; ++i) {
    psi[i] = regressors(model, samples[i].chip_mm, samples[i].contact_length_mm);
    for (int j = 0; j < 6; ++j) {
      if (!active[j]) psi[i][j] = 0.0;
    }
    y[i] = samples[i].force_n;
    w[i] = samples[i].weight;
    for (int c = 0; c < p; ++c) x(i, c) = psi[i][columns[c]];
  }
  const Eigen::Map<const Eigen::VectorXd> y_vec(y.data(), n);
  const Eigen::Map<const Eigen::VectorXd> w_vec(w.data(), n);
  const Eigen::VectorXd sqrt_w = w_vec.cwiseSqrt();
  const Eigen::MatrixXd weighted_x = sqrt_w.asDiagonal() * x;
  {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(weighted_x);
    const Eigen::VectorXd sv = svd.singularValues();
    if (!(sv(p - 1) > kRankTolerance * sv(0))) {
      int rank = 0;
      for (int c = 0; c < p; ++c) rank += sv(c) > kRankTolerance * sv(0) ? 1 : 0;
      result.message = "the samples do not determine the " + std::to_string(p) + " coefficients " +
                       list_names(active, true) + " (the design has rank " + std::to_string(rank) + "): t_m takes " +
                       std::to_string(chip.distinct) + " distinct values and L " + std::to_string(length.distinct) +
                       "; a quadratic term needs 3 distinct values of its input, and the cross term needs t_m and L "
                       "to vary independently, not along one line";
      return result;
    }
  }

  // 3. Estimate: weighted least squares, then the robust loss with Ceres.
  const Eigen::VectorXd ols = weighted_x.householderQr().solve(sqrt_w.asDiagonal() * y_vec);
  std::array<double, 6> beta{};
  for (int c = 0; c < p; ++c) beta[columns[c]] = ols(c);
  bool converged = true;
  std::string ceres_report;
  if (options.loss != FitOptions::kSquared) {
    const detail::RobustLinearFit robust = detail::robust_linear_fit(psi, y, w, options.loss, options.loss_scale_n,
                                                                      active, beta, options.max_iterations);
    beta = robust.beta;
    converged = robust.converged;
    ceres_report = "Ceres: " + robust.report;
  }
  model.beta = beta;
  result.estimated = active;

  // 4. Uncertainty and 5. quality, at the final β.
  Eigen::VectorXd beta_vec(p);
  for (int c = 0; c < p; ++c) beta_vec(c) = beta[columns[c]];
  const Eigen::VectorXd residual = y_vec - x * beta_vec;
  result.residual_n.assign(residual.data(), residual.data() + n);
  const double weight_sum = w_vec.sum();
  double sum_psi2 = 0.0, sum_psi_prime = 0.0, sum_wr2 = 0.0, sum_irls_r2 = 0.0;
  Eigen::VectorXd psi_prime(n), omega(n);
  for (int i = 0; i < n; ++i) {
    const LossDerivatives d = loss_derivatives(options.loss, options.loss_scale_n, residual(i));
    psi_prime(i) = d.psi_prime;
    omega(i) = w[i] * d.irls_weight;
    sum_psi2 += w[i] * d.psi * d.psi;
    sum_psi_prime += w[i] * d.psi_prime;
    sum_wr2 += w[i] * residual(i) * residual(i);
    sum_irls_r2 += omega(i) * residual(i) * residual(i);
    if (d.irls_weight < 0.5) ++result.downweighted_count;
  }
  const double dof = static_cast<double>(n - p);
  const double m = sum_psi_prime / weight_sum;

  // (XᵀAX)⁻¹ for diagonal weights A, from the QR factor of √A X.
  const auto inverse_normal_matrix = [&](const Eigen::VectorXd& a) {
    const Eigen::MatrixXd ax = a.cwiseSqrt().asDiagonal() * x;
    const Eigen::MatrixXd r = ax.householderQr().matrixQR().topRows(p).triangularView<Eigen::Upper>();
    const Eigen::MatrixXd r_inv = r.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
    return Eigen::MatrixXd(r_inv * r_inv.transpose());
  };
  const Eigen::MatrixXd omega_inverse = inverse_normal_matrix(omega);
  Eigen::MatrixXd cov;
  std::string covariance_note;
  if (m > 0.0) {
    double v = 0.0;
    for (int i = 0; i < n; ++i) v += w[i] * (psi_prime(i) - m) * (psi_prime(i) - m);
    v /= weight_sum;
    const double kappa = 1.0 + (static_cast<double>(p) / n) * v / (m * m);
    cov = (kappa * kappa * (sum_psi2 / dof) / (m * m)) * inverse_normal_matrix(w_vec);
  } else {
    cov = (sum_irls_r2 / dof) * omega_inverse;
    covariance_note = "most residuals lie beyond the loss scale, so the covariance is the weighted-least-squares "
                      "one with the robust weights";
  }
  for (int a = 0; a < p; ++a) {
    for (int b = 0; b < p; ++b) result.covariance(columns[a], columns[b]) = cov(a, b);
    result.standard_error_n[columns[a]] = std::sqrt(std::max(cov(a, a), 0.0));
  }

  result.rmse_n = std::sqrt(sum_wr2 / weight_sum);
  const double mean_force = w_vec.dot(y_vec) / weight_sum;
  const double total = (w_vec.array() * (y_vec.array() - mean_force).square()).sum();
  result.r_squared = total > 0.0 ? 1.0 - sum_wr2 / total : (sum_wr2 == 0.0 ? 1.0 : 0.0);

  double loo_sum = 0.0, loo_weight = 0.0;
  int unpredictable = 0;
  for (int i = 0; i < n; ++i) {
    const double h = omega(i) * x.row(i).dot(omega_inverse * x.row(i).transpose());
    if (h >= kLeverageOne) {
      ++unpredictable;
      continue;
    }
    const double e = residual(i) / (1.0 - h);
    loo_sum += w[i] * e * e;
    loo_weight += w[i];
  }
  result.loo_rmse_n = std::sqrt(loo_sum / loo_weight);

  // Status and message.
  std::string summary = "fitted " + list_names(active, true) + " to " + std::to_string(n) + " samples with " +
                        loss_text(options) + ": RMSE " + rounded(result.rmse_n) + " N, R² " +
                        rounded(result.r_squared, "%.4f") + ", leave-one-out RMSE " + rounded(result.loo_rmse_n) + " N";
  if (result.downweighted_count > 0) {
    summary += "; the robust loss weighted " + std::to_string(result.downweighted_count) + " sample(s) below 1/2";
  }
  if (unpredictable > 0) {
    summary += "; " + std::to_string(unpredictable) +
               " sample(s) alone determine a coefficient and are left out of the leave-one-out RMSE";
  }
  if (!covariance_note.empty()) summary += "; " + covariance_note;
  if (!held_reason.empty()) summary = held_reason + ", so " + list_names(active, false) + " are held at 0; " + summary;
  if (!converged) {
    result.status = FitStatus::kNotConverged;
    result.message = "the robust fit did not converge within " + std::to_string(options.max_iterations) +
                     " iterations (" + ceres_report + "); the model is the last iterate. " + summary;
  } else if (!held_reason.empty()) {
    result.status = FitStatus::kReducedModel;
    result.message = summary;
  } else {
    result.status = FitStatus::kOk;
    result.message = summary;
  }
  return result;
}

}  // namespace feedplan::model
