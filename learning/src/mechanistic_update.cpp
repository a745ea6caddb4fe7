#include "feedplan/learning/mechanistic_update.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"
#include "feedplan/planner/sample_force_model.hpp"

namespace feedplan::learning {
namespace {

using Vector4 = Eigen::Vector4d;
using Matrix4 = Eigen::Matrix4d;

// Relative step of the central differences of the kernel's peak in each coefficient.
constexpr double kDifferenceStep = 1e-3;

Vector4 coefficients_of(const model::MechanisticModel& m) {
  return {m.ktc_n_per_mm2, m.krc_n_per_mm2, m.kte_n_per_mm, m.kre_n_per_mm};
}

model::MechanisticModel with_coefficients(model::MechanisticModel m, const Vector4& k) {
  m.ktc_n_per_mm2 = k(0);
  m.krc_n_per_mm2 = k(1);
  m.kte_n_per_mm = k(2);
  m.kre_n_per_mm = k(3);
  return m;
}

Matrix4 matrix_of(const MechanisticCovariance& c) {
  Matrix4 m;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) m(i, j) = c[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
  }
  return m;
}

MechanisticCovariance covariance_of(const Matrix4& m) {
  MechanisticCovariance c{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) c[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = m(i, j);
  }
  return c;
}

// The engagement sample nearest to s (the profile's samples are in path order).
const geometry::EngagementSample& nearest_sample(const geometry::EngagementProfile& profile, double s_mm) {
  const auto& samples = profile.samples;
  auto after = std::lower_bound(samples.begin(), samples.end(), s_mm,
                                [](const geometry::EngagementSample& e, double s) { return e.s_mm < s; });
  if (after == samples.end()) return samples.back();
  if (after != samples.begin() && s_mm - std::prev(after)->s_mm < after->s_mm - s_mm) return *std::prev(after);
  return *after;
}

// Evaluates the kernel's per-revolution peak at places of the plan for any coefficients.
class PeakAtPlace {
 public:
  PeakAtPlace(const planner::PlanSettings& settings, const geometry::EngagementProfile& profile,
              const geometry::Tool& tool)
      : settings_(settings), profile_(profile), tool_(tool) {}

  double peak_n(const model::MechanisticModel& model, const geometry::EngagementSample& place, double feed) const {
    const planner::SampleForceModel kernel(settings_.model, &model, profile_, tool_);
    return kernel.predicted_force_n(place, 0.0, feed, tool_.flutes, settings_.spindle_rpm);
  }

  // g = ∂peak/∂K at `model`, by central differences.
  Vector4 regressor(const model::MechanisticModel& model, const geometry::EngagementSample& place, double feed) const {
    const Vector4 k = coefficients_of(model);
    const double scale = k.cwiseAbs().maxCoeff();
    Vector4 g;
    for (int j = 0; j < 4; ++j) {
      const double h = kDifferenceStep * std::max(std::abs(k(j)), 1e-3 * scale);
      Vector4 up = k, down = k;
      up(j) += h;
      down(j) -= h;
      g(j) = (peak_n(with_coefficients(model, up), place, feed) - peak_n(with_coefficients(model, down), place, feed)) /
             (2.0 * h);
    }
    return g;
  }

 private:
  const planner::PlanSettings& settings_;
  const geometry::EngagementProfile& profile_;
  const geometry::Tool& tool_;
};

// The prior Σ₀ of the file comment.
Matrix4 prior_covariance(const Matrix4& stored, const Vector4& k, double fraction) {
  Matrix4 prior = stored;
  for (int j = 0; j < 4; ++j) prior(j, j) += (fraction * k(j)) * (fraction * k(j));
  return prior;
}

// RLS over the samples from k with P₀ (rls.hpp's steps 1–2; no resetting: few hundred revolutions per part).
Vector4 rls_coefficients(const std::vector<MechanisticSample>& samples, Vector4 k, Matrix4 p,
                         const MechanisticUpdateOptions& o) {
  const double noise2 = o.noise_sigma_n * o.noise_sigma_n;
  for (const MechanisticSample& s : samples) {
    const Vector4 psi(s.regressor.data());
    const double error = s.force_n - psi.dot(k);
    if (std::abs(error) <= o.dead_zone_n) continue;
    const Vector4 gain = p * psi / (o.forgetting_factor * noise2 + psi.dot(p * psi));
    k += gain * error;
    p = (p - gain * psi.transpose() * p) / o.forgetting_factor;
    p = 0.5 * (p + p.transpose()).eval();
  }
  return k;
}

std::string errors_line(const char* what, const PredictionErrors& e) {
  char text[256];
  std::snprintf(text, sizeof text, "%s: RMS %.2f %% (%.1f N), max %.2f %%, median %.2f %%, p95 %.2f %%, mean %+.2f %%",
                what, e.rms_percent, e.rms_n, e.max_abs_percent, e.median_abs_percent, e.p95_abs_percent, e.mean_percent);
  return text;
}

// The per-revolution samples of every usable log, with their regressors at the planned model.
void collect_samples(const planner::PlanResult& plan, const planner::PlanSettings& settings, const PeakAtPlace& kernel,
                     const geometry::EngagementProfile& profile, int flutes, const std::vector<NamedLog>& logs,
                     const MechanisticUpdateOptions& options, MechanisticUpdate& update) {
  MeasuredRevolutionOptions revolutions = options.revolutions;
  revolutions.transfer_to_model = false;  // the kernel predicts the peak itself, at the depth cut
  update.logs = log_evidence(plan, settings.model, flutes, settings.spindle_rpm, logs, options.alignment, revolutions,
                             update.messages);
  add_infeasible_message(plan, update.logs, settings.target_force_n, update.messages);
  for (const LogEvidence& evidence : update.logs) {
    for (const LearningSample& sample : evidence.revolutions.samples) {
      if (!(sample.feed_mm_per_min > 0.0)) continue;
      MechanisticSample m;
      m.s_mm = sample.s_peak_mm;
      m.feed_mm_per_min = sample.feed_mm_per_min;
      m.force_n = sample.force_n;
      const Vector4 g = kernel.regressor(*settings.mechanistic, nearest_sample(profile, m.s_mm), m.feed_mm_per_min);
      if (!(g.squaredNorm() > 0.0)) continue;  // the kernel sees no cut there
      for (int j = 0; j < 4; ++j) m.regressor[static_cast<std::size_t>(j)] = g(j);
      update.samples.push_back(m);
    }
  }
}

PredictionErrors errors_of(const std::vector<MechanisticSample>& samples, const Vector4& k) {
  std::vector<double> measured, predicted;
  for (const MechanisticSample& s : samples) {
    measured.push_back(s.force_n);
    predicted.push_back(Vector4(s.regressor.data()).dot(k));
  }
  return prediction_errors(measured, predicted);
}

// The batch refit of the file comment: Gauss–Newton with Cauchy IRLS weights; returns K, sets the covariance
// and the RMS error (both at the last regressors).
Vector4 batch_coefficients(const std::vector<MechanisticSample>& samples, const PeakAtPlace& kernel,
                           const planner::PlanSettings& settings, const geometry::EngagementProfile& profile,
                           const Vector4& k0, const Matrix4& prior, const MechanisticUpdateOptions& o,
                           Matrix4& covariance, double& rms_n) {
  const Matrix4 prior_information = prior.inverse();
  const double noise2 = o.noise_sigma_n * o.noise_sigma_n;
  std::vector<Vector4> g(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) g[i] = Vector4(samples[i].regressor.data());
  Vector4 k = k0;
  for (int step = 0; step < o.gauss_newton_steps; ++step) {
    if (step > 0) {
      const model::MechanisticModel at = with_coefficients(*settings.mechanistic, k);
      for (std::size_t i = 0; i < samples.size(); ++i) {
        g[i] = kernel.regressor(at, nearest_sample(profile, samples[i].s_mm), samples[i].feed_mm_per_min);
      }
    }
    Matrix4 information = prior_information;
    Vector4 rhs = prior_information * k0;
    double sum_squares = 0.0;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const double r = samples[i].force_n - g[i].dot(k);
      sum_squares += r * r;
      const double u = 1.0 / (1.0 + r * r / (o.loss_scale_n * o.loss_scale_n));
      information += (u / noise2) * g[i] * g[i].transpose();
      rhs += (u / noise2) * samples[i].force_n * g[i];
    }
    rms_n = std::sqrt(sum_squares / static_cast<double>(samples.size()));
    covariance = information.inverse();
    k = information.ldlt().solve(rhs);
  }
  double sum_squares = 0.0;
  for (std::size_t i = 0; i < samples.size(); ++i) sum_squares += std::pow(samples[i].force_n - g[i].dot(k), 2);
  rms_n = std::sqrt(sum_squares / static_cast<double>(samples.size()));
  return k;
}

}  // namespace

std::vector<InputProblem> validate(const MechanisticUpdateOptions& o) {
  ProblemList problems("");
  if (!(o.forgetting_factor > 0.0 && o.forgetting_factor <= 1.0)) {
    problems.add_value("forgetting_factor", shortest_number_text(o.forgetting_factor), "must be in (0, 1]");
  }
  if (!(o.dead_zone_n >= 0.0 && std::isfinite(o.dead_zone_n))) {
    problems.add_value("dead_zone_n", shortest_number_text(o.dead_zone_n), "must be finite and ≥ 0");
  }
  problems.positive("noise_sigma_n", o.noise_sigma_n);
  problems.positive("prior_sigma_fraction", o.prior_sigma_fraction);
  problems.positive("loss_scale_n", o.loss_scale_n);
  if (o.gauss_newton_steps < 1) problems.add_value("gauss_newton_steps", std::to_string(o.gauss_newton_steps), "must be ≥ 1");
  return problems.take();
}

MechanisticUpdate update_mechanistic(const planner::PlanResult& plan, const planner::PlanSettings& settings,
                                     const geometry::EngagementProfile& profile, const geometry::Tool& tool,
                                     const std::vector<NamedLog>& logs, const MechanisticCovariance& prior_covariance_in,
                                     const MechanisticUpdateOptions& options) {
  std::vector<InputProblem> problems = validate(options);
  if (!settings.mechanistic) problems.push_back({"settings.mechanistic", "is not set: the plan was not made with the mechanistic kind"});
  if (!problems.empty()) throw InputError(std::move(problems));

  MechanisticUpdate update;
  update.model = update.rls_model = *settings.mechanistic;
  update.covariance = prior_covariance_in;
  const PeakAtPlace kernel(settings, profile, tool);
  collect_samples(plan, settings, kernel, profile, tool.flutes, logs, options, update);
  if (update.samples.empty()) {
    update.messages.push_back("no usable per-revolution sample in any log: the model is unchanged");
    return update;
  }

  const Vector4 k0 = coefficients_of(*settings.mechanistic);
  const Matrix4 prior = prior_covariance(matrix_of(prior_covariance_in), k0, options.prior_sigma_fraction);
  update.before = errors_of(update.samples, k0);
  const Vector4 k_rls = rls_coefficients(update.samples, k0, prior, options);
  update.rls_model = with_coefficients(*settings.mechanistic, k_rls);
  update.after_rls = errors_of(update.samples, k_rls);

  Matrix4 covariance;
  const Vector4 k = batch_coefficients(update.samples, kernel, settings, profile, k0, prior, options, covariance,
                                       update.rms_error_after_n);
  update.model = with_coefficients(*settings.mechanistic, k);
  update.covariance = covariance_of(covariance);
  std::vector<double> measured, predicted;
  for (const MechanisticSample& s : update.samples) {
    measured.push_back(s.force_n);
    predicted.push_back(kernel.peak_n(update.model, nearest_sample(profile, s.s_mm), s.feed_mm_per_min));
  }
  update.after_batch = prediction_errors(measured, predicted);
  update.messages.push_back(errors_line("model planned with", update.before));
  update.messages.push_back(errors_line("after RLS (seed 003 Eq. 5, kernel regressor)", update.after_rls));
  update.messages.push_back(errors_line("after the batch refit", update.after_batch));
  update.status = ModelUpdateStatus::kOk;
  return update;
}

}  // namespace feedplan::learning
