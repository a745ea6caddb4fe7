#include "feedplan/model/model_fit.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "feedplan/core/number_text.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "robust_linear_fit.hpp"

namespace feedplan::model {
namespace {

constexpr double kRankTolerance = 1e-9;      // σ_min/σ_max at or below which the design is rank-deficient
constexpr double kLeverageOne = 1.0 - 1e-9;  // h_ii at or above this: the sample alone fixes a coefficient
constexpr const char* kBetaNames[6] = {"β0", "β1", "β2", "β11", "β22", "β12"};

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
    case FitOptions::kHuber: return "Huber loss (scale " + six_digit_number_text(options.loss_scale_n) + " N)";
    case FitOptions::kCauchy: return "Cauchy loss (scale " + six_digit_number_text(options.loss_scale_n) + " N)";
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

//! Throws feedplan::InputError listing every problem with the options and the samples.
void check_input(const std::vector<FitSample>& samples, const FitOptions& options) {
  std::vector<InputProblem> problems = validate(options);
  check_samples(samples, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
}

//! The spread of both inputs over the samples.
struct InputSpreads {
  InputSpread chip;
  InputSpread length;
};

//! Step 1: centres, scales and fitted range of `model` from the data.
InputSpreads normalise_from_data(const std::vector<FitSample>& samples, const FitOptions& options,
                                 ResponseSurfaceModel& model) {
  std::vector<double> chips, lengths;
  for (const FitSample& s : samples) {
    chips.push_back(s.chip_mm);
    lengths.push_back(s.contact_length_mm);
  }
  const InputSpread chip = spread(chips, options.same_value_tolerance);
  const InputSpread length = spread(lengths, options.same_value_tolerance);
  normalisation(chip, model.chip_center_mm, model.chip_scale_mm);
  normalisation(length, model.contact_length_center_mm, model.contact_length_scale_mm);
  model.range = {chip.min, chip.max, length.min, length.max};
  return {chip, length};
}

//! The weighted least-squares problem over the coefficients the data can determine.
struct Design {
  std::array<bool, 6> active{true, true, true, true, true, true};  // false: held at 0
  std::string held_reason;                 // why some coefficients are held; empty when none are
  std::vector<int> columns;                // the estimated coefficients (BetaIndex), one per column of x
  std::vector<std::array<double, 6>> psi;  // regressors of each sample, 0 for held coefficients
  std::vector<double> y;                   // forces, N
  std::vector<double> w;                   // sample weights
  Eigen::MatrixXd x;                       // the design over the estimated coefficients, n × p
  Eigen::VectorXd sqrt_w;                  // √w
  Eigen::MatrixXd weighted_x;              // √W X

  int n() const { return static_cast<int>(y.size()); }
  int p() const { return static_cast<int>(columns.size()); }
};

//! Step 2, inputs that did not vary: marks their coefficients held in `design`. Returns why the fit cannot
//! go on (neither input varied, or one did and allow_reduced_model is off); empty when it can.
std::string hold_fixed_inputs(const InputSpreads& spreads, const FitOptions& options, int n, Design& design) {
  const InputSpread& chip = spreads.chip;
  const InputSpread& length = spreads.length;
  std::array<bool, 6>& active = design.active;
  if (!chip.varies && !length.varies) {
    return "neither t_m nor L varied (all " + std::to_string(n) + " samples at t_m = " +
           six_digit_number_text(chip.min) + " mm, L = " + six_digit_number_text(length.min) +
           " mm): the data say nothing about how the force depends on either";
  }
  if (!chip.varies || !length.varies) {
    const bool chip_fixed = !chip.varies;
    if (chip_fixed) {
      active[kBeta1] = active[kBeta11] = active[kBeta12] = false;
    } else {
      active[kBeta2] = active[kBeta22] = active[kBeta12] = false;
    }
    design.held_reason = std::string(chip_fixed ? "t_m" : "L") + " did not vary (all samples at " +
                         (chip_fixed ? "t_m = " + six_digit_number_text(chip.min)
                                     : "L = " + six_digit_number_text(length.min)) +
                         " mm)";
    if (!options.allow_reduced_model) {
      return design.held_reason + ", so " + list_names(active, false) +
             " cannot be estimated, and allow_reduced_model is off";
    }
  }
  for (int j = 0; j < 6; ++j) {
    if (active[j]) design.columns.push_back(j);
  }
  return "";
}

//! Step 2, sample count: why n samples cannot give the estimated coefficients and their uncertainty;
//! empty when they can.
std::string too_few_samples(const Design& design, int n) {
  const int p = design.p();
  if (n > p) return "";
  return std::to_string(n) + " samples for " + std::to_string(p) + " coefficients (" +
         list_names(design.active, true) + "): at least " + std::to_string(p + 1) + " are needed — " +
         std::to_string(p) + " to determine them and one more to estimate their uncertainty";
}

//! The regressors, forces and weights of the samples, the design x and the weighted design √W X.
void build_design(const std::vector<FitSample>& samples, const ResponseSurfaceModel& model, Design& design) {
  const int n = static_cast<int>(samples.size());
  const int p = design.p();
  design.psi.resize(samples.size());
  design.y.resize(samples.size());
  design.w.resize(samples.size());
  design.x.resize(n, p);
  for (int i = 0; i < n; ++i) {
    design.psi[i] = regressors(model, samples[i].chip_mm, samples[i].contact_length_mm);
    for (int j = 0; j < 6; ++j) {
      if (!design.active[j]) design.psi[i][j] = 0.0;
    }
    design.y[i] = samples[i].force_n;
    design.w[i] = samples[i].weight;
    for (int c = 0; c < p; ++c) design.x(i, c) = design.psi[i][design.columns[c]];
  }
  const Eigen::Map<const Eigen::VectorXd> w_vec(design.w.data(), n);
  design.sqrt_w = w_vec.cwiseSqrt();
  design.weighted_x = design.sqrt_w.asDiagonal() * design.x;
}

//! Step 2, rank: why the design does not determine the estimated coefficients; empty when it does.
std::string rank_deficiency(const Design& design, const InputSpreads& spreads) {
  const int p = design.p();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design.weighted_x);
  const Eigen::VectorXd sv = svd.singularValues();
  if (sv(p - 1) > kRankTolerance * sv(0)) return "";
  int rank = 0;
  for (int c = 0; c < p; ++c) rank += sv(c) > kRankTolerance * sv(0) ? 1 : 0;
  return "the samples do not determine the " + std::to_string(p) + " coefficients " +
         list_names(design.active, true) + " (the design has rank " + std::to_string(rank) + "): t_m takes " +
         std::to_string(spreads.chip.distinct) + " distinct values and L " + std::to_string(spreads.length.distinct) +
         "; a quadratic term needs 3 distinct values of its input, and the cross term needs t_m and L "
         "to vary independently, not along one line";
}

//! Step 2: the design over the coefficients the data determine, or nothing with result.message saying why
//! there is none.
std::optional<Design> identify_coefficients(const std::vector<FitSample>& samples, const InputSpreads& spreads,
                                            const FitOptions& options, FitResult& result) {
  Design design;
  result.message = hold_fixed_inputs(spreads, options, result.n, design);
  if (!result.message.empty()) return std::nullopt;
  result.message = too_few_samples(design, result.n);
  if (!result.message.empty()) return std::nullopt;
  build_design(samples, result.model, design);
  result.message = rank_deficiency(design, spreads);
  if (!result.message.empty()) return std::nullopt;
  return design;
}

//! The coefficients from step 3.
struct Estimate {
  std::array<double, 6> beta{};  // 0 for held coefficients
  bool converged = true;         // false: the robust fit stopped at max_iterations
  std::string ceres_report;      // "Ceres: …" for a robust loss, else empty
};

//! Step 3: weighted least squares, then the robust loss with Ceres.
Estimate estimate_coefficients(const Design& design, const FitOptions& options) {
  const int n = design.n();
  const int p = design.p();
  const Eigen::Map<const Eigen::VectorXd> y_vec(design.y.data(), n);
  const Eigen::VectorXd ols = design.weighted_x.householderQr().solve(design.sqrt_w.asDiagonal() * y_vec);
  Estimate estimate;
  for (int c = 0; c < p; ++c) estimate.beta[design.columns[c]] = ols(c);
  if (options.loss != FitOptions::kSquared) {
    const detail::RobustLinearFit robust =
        detail::robust_linear_fit(design.psi, design.y, design.w, options.loss, options.loss_scale_n, design.active,
                                  estimate.beta, options.max_iterations);
    estimate.beta = robust.beta;
    estimate.converged = robust.converged;
    estimate.ceres_report = "Ceres: " + robust.report;
  }
  return estimate;
}

//! The residuals at the final β and the loss's sums over them, shared by steps 4 and 5.
struct LossAtFit {
  Eigen::VectorXd residual;   // r_i = F_i − F̂_i, N
  Eigen::VectorXd psi_prime;  // ψ'(r_i)
  Eigen::VectorXd omega;      // Ω_i = w_i u(r_i)
  double weight_sum = 0.0;    // Σ w
  double sum_psi2 = 0.0;      // Σ w ψ(r)²
  double sum_psi_prime = 0.0; // Σ w ψ'(r)
  double sum_wr2 = 0.0;       // Σ w r²
  double sum_irls_r2 = 0.0;   // Σ Ω r²
  Eigen::MatrixXd omega_inverse;  // (XᵀΩX)⁻¹
};

//! (XᵀAX)⁻¹ for diagonal weights A, from the QR factor of √A X.
Eigen::MatrixXd inverse_normal_matrix(const Eigen::MatrixXd& x, const Eigen::VectorXd& a) {
  const int p = static_cast<int>(x.cols());
  const Eigen::MatrixXd ax = a.cwiseSqrt().asDiagonal() * x;
  const Eigen::MatrixXd r = ax.householderQr().matrixQR().topRows(p).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd r_inv = r.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
  return Eigen::MatrixXd(r_inv * r_inv.transpose());
}

//! The residuals at `beta` (stored in result.residual_n), the loss at them and the samples it down-weights
//! (result.downweighted_count).
LossAtFit evaluate_loss_at_fit(const Design& design, const std::array<double, 6>& beta, const FitOptions& options,
                               FitResult& result) {
  const int n = design.n();
  const int p = design.p();
  const std::vector<double>& w = design.w;
  const Eigen::Map<const Eigen::VectorXd> y_vec(design.y.data(), n);
  const Eigen::Map<const Eigen::VectorXd> w_vec(w.data(), n);
  Eigen::VectorXd beta_vec(p);
  for (int c = 0; c < p; ++c) beta_vec(c) = beta[design.columns[c]];
  LossAtFit loss;
  loss.residual = y_vec - design.x * beta_vec;
  const Eigen::VectorXd& residual = loss.residual;
  result.residual_n.assign(residual.data(), residual.data() + n);
  loss.weight_sum = w_vec.sum();
  loss.psi_prime.resize(n);
  loss.omega.resize(n);
  for (int i = 0; i < n; ++i) {
    const LossDerivatives d = loss_derivatives(options.loss, options.loss_scale_n, residual(i));
    loss.psi_prime(i) = d.psi_prime;
    loss.omega(i) = w[i] * d.irls_weight;
    loss.sum_psi2 += w[i] * d.psi * d.psi;
    loss.sum_psi_prime += w[i] * d.psi_prime;
    loss.sum_wr2 += w[i] * residual(i) * residual(i);
    loss.sum_irls_r2 += loss.omega(i) * residual(i) * residual(i);
    if (d.irls_weight < 0.5) ++result.downweighted_count;
  }
  loss.omega_inverse = inverse_normal_matrix(design.x, loss.omega);
  return loss;
}

//! Step 4: result.covariance and result.standard_error_n by Huber's sandwich, or the weighted-least-squares
//! covariance with the robust weights when m ≤ 0. Returns a note saying so in that case, else empty.
std::string estimate_uncertainty(const Design& design, const LossAtFit& loss, FitResult& result) {
  const int n = design.n();
  const int p = design.p();
  const std::vector<double>& w = design.w;
  const Eigen::Map<const Eigen::VectorXd> w_vec(w.data(), n);
  const double dof = static_cast<double>(n - p);
  const double m = loss.sum_psi_prime / loss.weight_sum;
  Eigen::MatrixXd cov;
  std::string covariance_note;
  if (m > 0.0) {
    double v = 0.0;
    for (int i = 0; i < n; ++i) v += w[i] * (loss.psi_prime(i) - m) * (loss.psi_prime(i) - m);
    v /= loss.weight_sum;
    const double kappa = 1.0 + (static_cast<double>(p) / n) * v / (m * m);
    cov = (kappa * kappa * (loss.sum_psi2 / dof) / (m * m)) * inverse_normal_matrix(design.x, w_vec);
  } else {
    cov = (loss.sum_irls_r2 / dof) * loss.omega_inverse;
    covariance_note = "most residuals lie beyond the loss scale, so the covariance is the weighted-least-squares "
                      "one with the robust weights";
  }
  for (int a = 0; a < p; ++a) {
    for (int b = 0; b < p; ++b) result.covariance(design.columns[a], design.columns[b]) = cov(a, b);
    result.standard_error_n[design.columns[a]] = std::sqrt(std::max(cov(a, a), 0.0));
  }
  return covariance_note;
}

//! Step 5: result.rmse_n, result.r_squared and result.loo_rmse_n. Returns how many samples alone determine a
//! coefficient and are left out of the leave-one-out RMSE.
int assess_quality(const Design& design, const LossAtFit& loss, FitResult& result) {
  const int n = design.n();
  const std::vector<double>& w = design.w;
  const Eigen::Map<const Eigen::VectorXd> y_vec(design.y.data(), n);
  const Eigen::Map<const Eigen::VectorXd> w_vec(w.data(), n);
  result.rmse_n = std::sqrt(loss.sum_wr2 / loss.weight_sum);
  const double mean_force = w_vec.dot(y_vec) / loss.weight_sum;
  const double total = (w_vec.array() * (y_vec.array() - mean_force).square()).sum();
  result.r_squared = total > 0.0 ? 1.0 - loss.sum_wr2 / total : (loss.sum_wr2 == 0.0 ? 1.0 : 0.0);

  double loo_sum = 0.0, loo_weight = 0.0;
  int unpredictable = 0;
  for (int i = 0; i < n; ++i) {
    const double h = loss.omega(i) * design.x.row(i).dot(loss.omega_inverse * design.x.row(i).transpose());
    if (h >= kLeverageOne) {
      ++unpredictable;
      continue;
    }
    const double e = loss.residual(i) / (1.0 - h);
    loo_sum += w[i] * e * e;
    loo_weight += w[i];
  }
  result.loo_rmse_n = std::sqrt(loo_sum / loo_weight);
  return unpredictable;
}

//! What the fit found besides the numbers in `result`.
struct FitNotes {
  std::string held_reason;      // why some coefficients are held; empty when none are
  std::string covariance_note;  // from step 4; empty for the sandwich covariance
  int unpredictable = 0;        // samples left out of the leave-one-out RMSE
};

//! result.status and result.message: a summary of the fit, after what was held and why, after why the
//! robust fit did not converge.
void report_outcome(const FitOptions& options, const Design& design, const Estimate& estimate,
                    const FitNotes& notes, FitResult& result) {
  const std::array<bool, 6>& active = design.active;
  std::string summary = "fitted " + list_names(active, true) + " to " + std::to_string(design.n()) +
                        " samples with " + loss_text(options) + ": RMSE " + rounded(result.rmse_n) + " N, R² " +
                        rounded(result.r_squared, "%.4f") + ", leave-one-out RMSE " + rounded(result.loo_rmse_n) + " N";
  if (result.downweighted_count > 0) {
    summary += "; the robust loss weighted " + std::to_string(result.downweighted_count) + " sample(s) below 1/2";
  }
  if (notes.unpredictable > 0) {
    summary += "; " + std::to_string(notes.unpredictable) +
               " sample(s) alone determine a coefficient and are left out of the leave-one-out RMSE";
  }
  if (!notes.covariance_note.empty()) summary += "; " + notes.covariance_note;
  if (!notes.held_reason.empty()) {
    summary = notes.held_reason + ", so " + list_names(active, false) + " are held at 0; " + summary;
  }
  if (!estimate.converged) {
    result.status = FitStatus::kNotConverged;
    result.message = "the robust fit did not converge within " + std::to_string(options.max_iterations) +
                     " iterations (" + estimate.ceres_report + "); the model is the last iterate. " + summary;
  } else if (!notes.held_reason.empty()) {
    result.status = FitStatus::kReducedModel;
    result.message = summary;
  } else {
    result.status = FitStatus::kOk;
    result.message = summary;
  }
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
  check_input(samples, options);
  FitResult result;
  result.status = FitStatus::kInsufficientData;
  result.n = static_cast<int>(samples.size());
  if (samples.empty()) {
    result.message = "no samples to fit";
    return result;
  }
  const InputSpreads spreads = normalise_from_data(samples, options, result.model);
  const std::optional<Design> design = identify_coefficients(samples, spreads, options, result);
  if (!design) return result;
  const Estimate estimate = estimate_coefficients(*design, options);
  result.model.beta = estimate.beta;
  result.estimated = design->active;
  const LossAtFit loss = evaluate_loss_at_fit(*design, estimate.beta, options, result);
  FitNotes notes;
  notes.held_reason = design->held_reason;
  notes.covariance_note = estimate_uncertainty(*design, loss, result);
  notes.unpredictable = assess_quality(*design, loss, result);
  report_outcome(options, *design, estimate, notes, result);
  return result;
}

double leave_group_out_rmse_n(const std::vector<FitSample>& samples, const std::vector<int>& group,
                                            const FitOptions& options) {
  if (group.size() != samples.size()) {
    throw InputError("group", "has " + std::to_string(group.size()) + " entries: must have one per sample (" +
                                  std::to_string(samples.size()) + ")");
  }
  std::vector<int> groups(group);
  std::sort(groups.begin(), groups.end());
  groups.erase(std::unique(groups.begin(), groups.end()), groups.end());
  double sum = 0.0;
  for (const int left_out : groups) {
    std::vector<FitSample> others;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (group[i] != left_out) others.push_back(samples[i]);
    }
    const FitResult fit = fit_model(others, options);
    const bool fitted = fit.status == FitStatus::kOk || fit.status == FitStatus::kReducedModel;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (group[i] != left_out) continue;
      const double predicted_n = fitted ? predict(fit.model, samples[i].chip_mm, samples[i].contact_length_mm).force_n : 0.0;
      const double error_n = predicted_n - samples[i].force_n;
      sum += error_n * error_n;
    }
  }
  return std::sqrt(sum / static_cast<double>(samples.size()));
}

}  // namespace feedplan::model
