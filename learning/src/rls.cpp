#include "feedplan/learning/rls.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"
#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning {
namespace {

using Matrix6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

std::string text(double value) { return shortest_number_text(value); }

void throw_if_any(std::vector<InputProblem> problems) {
  if (!problems.empty()) throw InputError(std::move(problems));
}

model::Covariance initial_covariance(const RlsOptions& options) {
  model::Covariance p;
  for (int j = 0; j < 6; ++j) p(j, j) = options.initial_variance_n2;
  return p;
}

void extend_range(model::FittedRange& range, const LearningSample& s) {
  range.chip_min_mm = std::min(range.chip_min_mm, s.chip_mm);
  range.chip_max_mm = std::max(range.chip_max_mm, s.chip_mm);
  range.contact_length_min_mm = std::min(range.contact_length_min_mm, s.contact_length_mm);
  range.contact_length_max_mm = std::max(range.contact_length_max_mm, s.contact_length_mm);
}

}  // namespace

std::vector<InputProblem> validate(const RlsOptions& options) {
  std::vector<InputProblem> problems;
  if (!(options.forgetting_factor > 0.0 && options.forgetting_factor <= 1.0)) {
    problems.push_back({"rls.forgetting_factor", "= " + text(options.forgetting_factor) + ": must be in (0, 1]"});
  }
  if (!(std::isfinite(options.dead_zone_n) && options.dead_zone_n >= 0.0)) {
    problems.push_back({"rls.dead_zone_n", "= " + text(options.dead_zone_n) + ": must be finite and ≥ 0 N"});
  }
  if (!(std::isfinite(options.noise_sigma_n) && options.noise_sigma_n > 0.0)) {
    problems.push_back({"rls.noise_sigma_n", "= " + text(options.noise_sigma_n) + ": must be finite and > 0 N"});
  }
  const bool variance_ok = std::isfinite(options.initial_variance_n2) && options.initial_variance_n2 > 0.0;
  if (!variance_ok) {
    problems.push_back({"rls.initial_variance_n2",
                        "= " + text(options.initial_variance_n2) + ": must be finite and > 0 N²"});
  }
  const double trace0 = 6.0 * options.initial_variance_n2;
  if (!(std::isfinite(options.reset_trace_min_n2) && options.reset_trace_min_n2 >= 0.0)) {
    problems.push_back({"rls.reset_trace_min_n2",
                        "= " + text(options.reset_trace_min_n2) + ": must be finite and ≥ 0 N²"});
  } else if (variance_ok && !(options.reset_trace_min_n2 < trace0)) {
    problems.push_back({"rls.reset_trace_min_n2", "= " + text(options.reset_trace_min_n2) +
                                                      ": must be below trace(P0) = 6 × rls.initial_variance_n2 = " +
                                                      text(trace0) + " N², or P would be reset after every update"});
  }
  if (std::isnan(options.reset_trace_max_n2)) {
    problems.push_back({"rls.reset_trace_max_n2", "= nan: must be a number of N² (+inf: never reset high)"});
  } else if (variance_ok && !(options.reset_trace_max_n2 > trace0)) {
    problems.push_back({"rls.reset_trace_max_n2", "= " + text(options.reset_trace_max_n2) +
                                                      ": must be above trace(P0) = 6 × rls.initial_variance_n2 = " +
                                                      text(trace0) + " N²"});
  }
  return problems;
}

RecursiveLeastSquares::RecursiveLeastSquares(const model::ResponseSurfaceModel& start, const RlsOptions& options)
    : model_(start), options_(options) {
  std::vector<InputProblem> problems = validate(options);
  for (InputProblem& p : model::validate(start)) problems.push_back(std::move(p));
  throw_if_any(std::move(problems));
  covariance_ = initial_covariance(options_);
}

RlsStep RecursiveLeastSquares::add(const LearningSample& sample) {
  std::vector<InputProblem> problems;
  validate(sample, "sample.", problems);
  throw_if_any(std::move(problems));

  extend_range(model_.range, sample);
  const std::array<double, 6> regressors = model::regressors(model_, sample.chip_mm, sample.contact_length_mm);
  const Eigen::Map<const Vector6> psi(regressors.data());
  Eigen::Map<Vector6> theta(model_.beta.data());
  Eigen::Map<Matrix6> p(covariance_.entries().data());

  RlsStep step;
  step.error_n = sample.force_n - psi.dot(theta);  // step 1
  if (options_.dead_zone_n > 0.0 && std::abs(step.error_n) <= options_.dead_zone_n) {
    ++skipped_in_dead_zone_;
    return step;
  }

  // Step 2: the weighted, exponentially forgetting form of Eq. 5.
  const double lambda = options_.forgetting_factor;
  const double noise_variance = options_.noise_sigma_n * options_.noise_sigma_n / sample.weight;
  const Vector6 p_psi = p * psi;
  const Vector6 gain = p_psi / (lambda * noise_variance + psi.dot(p_psi));
  theta += gain * step.error_n;
  p = (p - gain * p_psi.transpose()) / lambda;  // ψᵀP = (Pψ)ᵀ for symmetric P
  p = (0.5 * (p + p.transpose())).eval();
  step.updated = true;
  ++updates_;

  // Step 3: covariance resetting.
  const double trace = p.trace();
  if (!(trace >= options_.reset_trace_min_n2 && trace <= options_.reset_trace_max_n2)) {
    covariance_ = initial_covariance(options_);
    step.reset = true;
    ++resets_;
  }
  return step;
}

RlsResult rls_update(const model::ResponseSurfaceModel& start, const std::vector<LearningSample>& samples,
                     const RlsOptions& options) {
  std::vector<InputProblem> problems = validate(options);
  validate(start, samples, problems);
  throw_if_any(std::move(problems));

  RecursiveLeastSquares rls(start, options);
  for (const LearningSample& s : samples) rls.add(s);

  RlsResult result;
  result.model = rls.model();
  result.n = static_cast<int>(samples.size());
  result.updates = rls.updates();
  result.skipped_in_dead_zone = rls.skipped_in_dead_zone();
  result.resets = rls.resets();
  result.rms_error_before_n = weighted_rms_error(start, samples);
  result.rms_error_after_n = weighted_rms_error(result.model, samples);
  result.covariance = rls.covariance();
  return result;
}

}  // namespace feedplan::learning
