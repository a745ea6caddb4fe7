// Recursive least squares on the model coefficients (seed 003 Eq. 5 with forgetting, covariance resetting and a
// dead zone): convergence to the true β on noise-free data, agreement with the closed-form exponentially
// weighted least-squares solution solved here by Gaussian elimination, tracking a step change, the dead zone,
// covariance resets on windup at the predicted sample, and the options' validation.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "gauss_solve.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/learning/rls.hpp"
#include "feedplan/model/model_prediction.hpp"

namespace feedplan::learning {
namespace {

using model::ResponseSurfaceModel;
using ::testing::HasSubstr;
using testing::Matrix;
using testing::Vector;
using testing::solve;

unsigned env_or(const char* name, unsigned fallback) {
  const char* text = std::getenv(name);
  return text != nullptr && *text != '\0' ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : fallback;
}

//! The true model: centres and scales such that t_m 0.02–0.12 mm and L 1–9 mm map onto [−1, 1].
ResponseSurfaceModel truth() {
  ResponseSurfaceModel m;
  m.beta = {400.0, 120.0, 60.0, 15.0, -8.0, 10.0};
  m.chip_center_mm = 0.07;
  m.chip_scale_mm = 0.05;
  m.contact_length_center_mm = 5.0;
  m.contact_length_scale_mm = 4.0;
  m.range = {0.02, 0.12, 1.0, 9.0};
  return m;
}

ResponseSurfaceModel scaled(const ResponseSurfaceModel& m, double factor) {
  ResponseSurfaceModel s = m;
  for (double& b : s.beta) b *= factor;
  return s;
}

//! `passes` × (8 chip thicknesses × 5 contact lengths) from `model`, with Gaussian noise of sigma_n.
std::vector<LearningSample> grid(const ResponseSurfaceModel& model, int passes, double sigma_n, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, sigma_n > 0.0 ? sigma_n : 1.0);
  std::vector<LearningSample> samples;
  for (int pass = 0; pass < passes; ++pass) {
    for (int i = 0; i < 8; ++i) {
      for (int j = 0; j < 5; ++j) {
        const double chip = 0.02 + 0.1 * i / 7.0;
        const double length = 1.0 + 2.0 * j;
        const double force = model::predict(model, chip, length).force_n + (sigma_n > 0.0 ? noise(rng) : 0.0);
        samples.push_back({chip, length, force, 1.0, 0.0});
      }
    }
  }
  return samples;
}


double trace(const model::Covariance& p) {
  double t = 0.0;
  for (int j = 0; j < 6; ++j) t += p(j, j);
  return t;
}

RlsOptions plain(double forgetting_factor) {
  RlsOptions options;
  options.forgetting_factor = forgetting_factor;
  options.dead_zone_n = 0.0;
  options.reset_trace_min_n2 = 0.0;
  options.reset_trace_max_n2 = std::numeric_limits<double>::infinity();
  return options;
}

TEST(Rls, ConvergesToTheTrueCoefficientsOnNoiseFreeData) {
  std::mt19937_64 rng(1);
  const ResponseSurfaceModel t = truth();
  RlsOptions options = plain(1.0);
  options.initial_variance_n2 = 1e10;  // a vague start: the regularisation bias is ~σ²/P₀ ≈ 1e-10
  const RlsResult r = rls_update(scaled(t, 0.7), grid(t, 1, 0.0, rng), options);
  EXPECT_EQ(r.n, 40);
  EXPECT_EQ(r.updates, 40);
  EXPECT_EQ(r.skipped_in_dead_zone, 0);
  EXPECT_EQ(r.resets, 0);
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(r.model.beta[j], t.beta[j], 1e-6 * std::abs(t.beta[j])) << "β index " << j;
  EXPECT_LT(r.rms_error_after_n, 1e-5);
  EXPECT_GT(r.rms_error_before_n, 50.0);
  // centres and scales are the start's
  EXPECT_EQ(r.model.chip_center_mm, t.chip_center_mm);
  EXPECT_EQ(r.model.contact_length_scale_mm, t.contact_length_scale_mm);
}

// With λ < 1, weights and a finite P₀, the recursion is the exact minimiser of
//   λᴺ (θ − θ₀)ᵀ P₀⁻¹ (θ − θ₀) + Σₖ λᴺ⁻ᵏ wₖ (Fₖ − ψₖᵀθ)² / σ²,
// whose normal equations are solved here; P is the inverse of their matrix.
TEST(Rls, MatchesTheClosedFormOfExponentiallyWeightedLeastSquares) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 2024u);
  std::cout << "RLS closed form: FEEDPLAN_TEST_SEED=" << seed << ", n = 80, noise σ = 3 N, λ = 0.97\n";
  std::mt19937_64 rng(seed);
  const ResponseSurfaceModel start = scaled(truth(), 0.7);
  std::vector<LearningSample> samples = grid(truth(), 2, 3.0, rng);
  std::uniform_real_distribution<double> weight(0.5, 2.0);
  for (LearningSample& s : samples) s.weight = weight(rng);
  samples.push_back({0.15, 12.0, 700.0, 1.0, 0.0});  // outside the start's range, to grow it
  RlsOptions options = plain(0.97);
  options.noise_sigma_n = 3.0;
  options.initial_variance_n2 = 400.0;
  const RlsResult r = rls_update(start, samples, options);

  const double lambda = options.forgetting_factor, sigma2 = options.noise_sigma_n * options.noise_sigma_n;
  const int n = static_cast<int>(samples.size());
  Matrix a{};
  Vector b{};
  const double prior = std::pow(lambda, n) / options.initial_variance_n2;
  for (int j = 0; j < 6; ++j) {
    a[j][j] += prior;
    b[j] += prior * start.beta[j];
  }
  for (int k = 0; k < n; ++k) {
    const Vector psi = model::regressors(start, samples[k].chip_mm, samples[k].contact_length_mm);
    const double c = std::pow(lambda, n - 1 - k) * samples[k].weight / sigma2;
    for (int i = 0; i < 6; ++i) {
      b[i] += c * psi[i] * samples[k].force_n;
      for (int j = 0; j < 6; ++j) a[i][j] += c * psi[i] * psi[j];
    }
  }
  const Vector expected = solve(a, b);
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(r.model.beta[j], expected[j], 1e-9 * std::abs(expected[j])) << "β index " << j;
  for (int c = 0; c < 6; ++c) {
    Vector unit{};
    unit[c] = 1.0;
    const Vector column = solve(a, unit);
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(r.covariance(i, c), column[i], 1e-8 * std::abs(column[c])) << "P(" << i << "," << c << ")";
      EXPECT_EQ(r.covariance(i, c), r.covariance(c, i));
    }
  }

  double before = 0.0, after = 0.0, weights = 0.0;
  for (const LearningSample& s : samples) {
    double predicted_after = 0.0;
    const Vector psi = model::regressors(start, s.chip_mm, s.contact_length_mm);
    for (int j = 0; j < 6; ++j) predicted_after += expected[j] * psi[j];
    before += s.weight * std::pow(s.force_n - model::predict(start, s.chip_mm, s.contact_length_mm).force_n, 2);
    after += s.weight * std::pow(s.force_n - predicted_after, 2);
    weights += s.weight;
  }
  EXPECT_NEAR(r.rms_error_before_n, std::sqrt(before / weights), 1e-9 * r.rms_error_before_n);
  EXPECT_NEAR(r.rms_error_after_n, std::sqrt(after / weights), 1e-6 * r.rms_error_after_n);

  // the range is the union of the start's and the samples'
  EXPECT_EQ(r.model.range.chip_min_mm, 0.02);
  EXPECT_EQ(r.model.range.chip_max_mm, 0.15);
  EXPECT_EQ(r.model.range.contact_length_min_mm, 1.0);
  EXPECT_EQ(r.model.range.contact_length_max_mm, 12.0);

  // the incremental class gives the same, sample by sample
  RecursiveLeastSquares rls(start, options);
  for (const LearningSample& s : samples) rls.add(s);
  EXPECT_EQ(rls.model().beta, r.model.beta);
  EXPECT_EQ(rls.covariance(), r.covariance);
}

// After β changes by 30 %, a forgetting factor < 1 forgets the old process; λ = 1 averages both.
TEST(Rls, ForgettingFactorTracksAStepChange) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 7u);
  std::cout << "RLS step change: FEEDPLAN_TEST_SEED=" << seed << ", 200 + 200 samples, noise σ = 2 N\n";
  std::mt19937_64 rng(seed);
  const ResponseSurfaceModel before = truth();
  const ResponseSurfaceModel after = scaled(truth(), 1.3);
  std::vector<LearningSample> samples = grid(before, 5, 2.0, rng);
  const std::vector<LearningSample> changed = grid(after, 5, 2.0, rng);
  samples.insert(samples.end(), changed.begin(), changed.end());

  RlsOptions forgetting;  // the defaults (dead zone 2 N) but a shorter memory
  forgetting.forgetting_factor = 0.95;
  RecursiveLeastSquares rls(before, forgetting);
  std::vector<double> errors;
  for (const LearningSample& s : samples) errors.push_back(std::abs(rls.add(s).error_n));
  double first = 0.0, last = 0.0;
  for (int k = 200; k < 220; ++k) first += errors[k] / 20.0;
  for (int k = 360; k < 400; ++k) last += errors[k] / 40.0;
  EXPECT_GT(first, 50.0);  // the change is 30 % of 250–700 N
  EXPECT_LT(last, 3.0);    // back to the noise
  for (int j = 0; j < 6; ++j) {
    EXPECT_NEAR(rls.model().beta[j], after.beta[j], 0.02 * std::abs(after.beta[0])) << "β index " << j;
  }

  RlsOptions remembering = forgetting;
  remembering.forgetting_factor = 1.0;
  const RlsResult r = rls_update(before, samples, remembering);
  // between 400 and 520 N: the first 200 samples still count (fewer of them, as many lay within the dead zone)
  EXPECT_GT(std::abs(r.model.beta[0] - after.beta[0]), 15.0);
}

TEST(Rls, DeadZoneSkipsSmallErrors) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 11u);
  std::mt19937_64 rng(seed);
  const ResponseSurfaceModel t = truth();
  std::vector<LearningSample> samples = grid(t, 1, 0.0, rng);
  std::uniform_real_distribution<double> noise(-1.5, 1.5);
  for (LearningSample& s : samples) s.force_n += noise(rng);
  samples.push_back({0.2, 10.0, model::predict(t, 0.2, 10.0).force_n + 1.9, 1.0, 0.0});

  RlsOptions options;
  options.dead_zone_n = 2.0;
  const RlsResult skipped = rls_update(t, samples, options);
  EXPECT_EQ(skipped.skipped_in_dead_zone, 41);
  EXPECT_EQ(skipped.updates, 0);
  EXPECT_EQ(skipped.model.beta, t.beta);
  EXPECT_EQ(skipped.model.range.chip_max_mm, 0.2);  // skipped samples still count for the range
  EXPECT_EQ(skipped.model.range.contact_length_max_mm, 10.0);

  options.dead_zone_n = 0.0;
  const RlsResult all = rls_update(t, samples, options);
  EXPECT_EQ(all.skipped_in_dead_zone, 0);
  EXPECT_EQ(all.updates, 41);
  EXPECT_NE(all.model.beta, t.beta);

  // an error just beyond the dead zone is learned from
  options.dead_zone_n = 2.0;
  RecursiveLeastSquares rls(t, options);
  const RlsStep step = rls.add({0.07, 5.0, t.beta[0] + 2.5, 1.0, 0.0});
  EXPECT_TRUE(step.updated);
  EXPECT_NEAR(step.error_n, 2.5, 1e-12);
  EXPECT_EQ(rls.updates(), 1);
  EXPECT_GT(rls.model().beta[0], t.beta[0]);
}

// One sample repeated with λ < 1 excites one direction of ψ; P in the five others grows by exactly 1/λ
// per update (the update changes P only along Pψ), so trace(P) passes the cap after the first k updates
// with 5 P₀ λ⁻ᵏ > cap, and every k updates after each reset.
TEST(Rls, CovarianceResetsOnWindupWithoutExcitation) {
  const ResponseSurfaceModel t = truth();
  std::vector<LearningSample> samples;
  for (int k = 0; k < 200; ++k) {
    samples.push_back({0.09, 6.0, model::predict(t, 0.09, 6.0).force_n + (k % 2 == 0 ? 3.0 : -3.0), 1.0, 0.0});
  }
  RlsOptions options;
  options.forgetting_factor = 0.9;
  options.dead_zone_n = 0.0;
  int k = 1;
  while (5.0 * options.initial_variance_n2 * std::pow(options.forgetting_factor, -k) <= options.reset_trace_max_n2) ++k;
  ASSERT_EQ(k, 73);

  RecursiveLeastSquares rls(t, options);
  std::vector<int> reset_at;
  for (int i = 0; i < 200; ++i) {
    if (rls.add(samples[i]).reset) {
      reset_at.push_back(i + 1);
      model::Covariance p0;
      for (int j = 0; j < 6; ++j) p0(j, j) = options.initial_variance_n2;
      EXPECT_EQ(rls.covariance(), p0);
    }
  }
  EXPECT_THAT(reset_at, ::testing::ElementsAre(k, 2 * k));
  EXPECT_EQ(rls.resets(), 2);
  EXPECT_LE(trace(rls.covariance()), options.reset_trace_max_n2);

  options.forgetting_factor = 1.0;  // no windup: P only shrinks along ψ
  const RlsResult r = rls_update(t, samples, options);
  EXPECT_EQ(r.resets, 0);
  EXPECT_NEAR(trace(r.covariance), 5.0 * options.initial_variance_n2, 1.0);
}

// With λ = 1 and exciting samples P shrinks like 1/n; a floor on its trace resets it to P₀.
TEST(Rls, CovarianceResetsWhenTheGainDiesAway) {
  std::mt19937_64 rng(3);
  RlsOptions options = plain(1.0);
  options.reset_trace_min_n2 = 0.5;
  const std::vector<LearningSample> samples = grid(truth(), 10, 1.0, rng);
  RecursiveLeastSquares rls(truth(), options);
  double previous_trace = trace(rls.covariance());
  for (const LearningSample& s : samples) {
    const RlsStep step = rls.add(s);
    const double now = trace(rls.covariance());
    if (step.reset) {
      EXPECT_EQ(now, 6.0 * options.initial_variance_n2);
    } else {
      EXPECT_LE(now, previous_trace);  // λ = 1: every update lowers P
      EXPECT_GE(now, options.reset_trace_min_n2);
    }
    previous_trace = now;
  }
  EXPECT_GE(rls.resets(), 1);
}

TEST(Rls, ValidateNamesEveryField) {
  EXPECT_TRUE(validate(RlsOptions{}).empty());
  RlsOptions bad;
  bad.forgetting_factor = 1.5;
  bad.dead_zone_n = -1.0;
  bad.noise_sigma_n = 0.0;
  bad.initial_variance_n2 = std::numeric_limits<double>::quiet_NaN();
  bad.reset_trace_min_n2 = -1.0;
  bad.reset_trace_max_n2 = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> fields;
  for (const InputProblem& p : validate(bad)) fields.push_back(p.field);
  EXPECT_THAT(fields, ::testing::ElementsAre("rls.forgetting_factor", "rls.dead_zone_n", "rls.noise_sigma_n",
                                             "rls.initial_variance_n2", "rls.reset_trace_min_n2",
                                             "rls.reset_trace_max_n2"));

  RlsOptions inconsistent;  // trace(P0) = 6e4 lies outside [min, max]
  inconsistent.reset_trace_min_n2 = 1e5;
  inconsistent.reset_trace_max_n2 = 1e4;
  const std::vector<InputProblem> problems = validate(inconsistent);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].field, "rls.reset_trace_min_n2");
  EXPECT_THAT(problems[0].message, HasSubstr("trace(P0)"));
  EXPECT_EQ(problems[1].field, "rls.reset_trace_max_n2");
  RlsOptions zero_lambda;
  zero_lambda.forgetting_factor = 0.0;
  ASSERT_EQ(validate(zero_lambda).size(), 1u);
  EXPECT_EQ(to_string(validate(zero_lambda)[0]), "rls.forgetting_factor = 0: must be in (0, 1]");
}

TEST(Rls, BadInputThrowsNamingEveryProblem) {
  const ResponseSurfaceModel t = truth();
  std::vector<LearningSample> samples{{0.05, 4.0, 300.0, 1.0, 0.0},
                                      {0.05, -1.0, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}};
  RlsOptions options;
  options.dead_zone_n = -2.0;
  try {
    rls_update(t, samples, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    std::vector<std::string> fields;
    for (const InputProblem& p : e.problems()) fields.push_back(p.field);
    EXPECT_THAT(fields, ::testing::ElementsAre("rls.dead_zone_n", "samples[1].contact_length_mm",
                                               "samples[1].force_n", "samples[1].weight"));
  }
  ResponseSurfaceModel bad_model = t;
  bad_model.chip_scale_mm = 0.0;
  EXPECT_THROW(RecursiveLeastSquares(bad_model, RlsOptions{}), InputError);
  RecursiveLeastSquares rls(t);
  EXPECT_THROW(rls.add(samples[1]), InputError);
  EXPECT_EQ(rls.updates() + rls.skipped_in_dead_zone(), 0);

  const RlsResult none = rls_update(t, {}, RlsOptions{});
  EXPECT_EQ(none.n, 0);
  EXPECT_EQ(none.model.beta, t.beta);
  EXPECT_EQ(none.rms_error_before_n, 0.0);
}

}  // namespace
}  // namespace feedplan::learning
