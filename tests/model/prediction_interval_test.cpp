// Prediction intervals (model/prediction_interval.hpp) and the pooled revolution spread
// (model/revolution_spread.hpp) against truths the code does not produce: the coverage of the response
// surface's interval over many seeded synthetic data sets with known noise; the mechanistic fit σ against
// a Monte Carlo draw of the coefficients and against finite differences of the peak; the pooled spread
// against a hand computation.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/model_fit.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/model/prediction_interval.hpp"
#include "feedplan/model/revolution_spread.hpp"

namespace feedplan::model {
namespace {

constexpr double kPi = 3.14159265358979323846;

unsigned env_or(const char* name, unsigned fallback) {
  const char* text = std::getenv(name);
  return text != nullptr && *text != '\0' ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : fallback;
}

// ---------------------------------------------------------------------------------------------------
// Response surface

//! The true model; its centres and scales are those the fit derives from the design below.
ResponseSurfaceModel truth() {
  ResponseSurfaceModel m;
  m.beta = {400.0, 120.0, 60.0, 15.0, -8.0, 10.0};
  m.chip_center_mm = 0.07;
  m.chip_scale_mm = 0.05;
  m.contact_length_center_mm = 5.0;
  m.contact_length_scale_mm = 4.0;
  return m;
}

//! 8 chip thicknesses × 5 contact lengths: t_m 0.02–0.12 mm, L 1–9 mm.
std::vector<std::array<double, 2>> design() {
  std::vector<std::array<double, 2>> points;
  for (int i = 0; i < 8; ++i) {
    for (int j = 0; j < 5; ++j) points.push_back({0.02 + 0.1 * i / 7.0, 1.0 + 2.0 * j});
  }
  return points;
}

//! Points the intervals are judged at: the centre, near a corner, and between design points.
const std::array<std::array<double, 2>, 3> kQueries = {{{0.07, 5.0}, {0.03, 8.5}, {0.105, 2.2}}};

FitOptions squared_loss() {
  FitOptions options;
  options.loss = FitOptions::kSquared;
  return options;
}

// Without revolution spread the interval is a confidence interval of the mean: with Gaussian noise of
// σ = 4 N on 40 points and 6 coefficients, (F̂ − F)/σ_fit is Student-t with 34 degrees of freedom, and
// P(|T| ≤ 2) = 0.946. Over FEEDPLAN_TEST_COUNT seeded data sets the interval must cover the true mean
// between 90 and 99 % of the time at each query point (at 400 draws the binomial standard deviation of
// the rate is 1.1 %).
TEST(PredictionInterval, ResponseSurfaceCoversTheTrueMeanAtTheNominalRate) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 2024u);
  const unsigned count = env_or("FEEDPLAN_TEST_COUNT", 400u);
  const ResponseSurfaceModel t = truth();
  std::array<int, kQueries.size()> covered{};
  for (unsigned s = 0; s < count; ++s) {
    std::mt19937_64 rng(seed + s);
    std::normal_distribution<double> noise(0.0, 4.0);
    std::vector<FitSample> samples;
    for (const auto& p : design()) samples.push_back({p[0], p[1], predict(t, p[0], p[1]).force_n + noise(rng)});
    const FitResult fit = fit_model(samples, squared_loss());
    ASSERT_EQ(fit.status, FitStatus::kOk) << "seed " << seed + s;
    for (std::size_t q = 0; q < kQueries.size(); ++q) {
      const PredictionInterval i = response_surface_interval(fit.model, fit.covariance, kQueries[q][0], kQueries[q][1], 0.0);
      const double mean_n = predict(t, kQueries[q][0], kQueries[q][1]).force_n;
      covered[q] += mean_n >= i.lower_n && mean_n <= i.upper_n ? 1 : 0;
      EXPECT_EQ(i.spread_sd_n, 0.0);
    }
  }
  for (std::size_t q = 0; q < kQueries.size(); ++q) {
    const double rate = static_cast<double>(covered[q]) / count;
    std::printf("response-surface interval (z = 2, no spread) at t_m %.3f mm, L %.1f mm covers the true mean in %.1f %% "
                "of FEEDPLAN_TEST_COUNT=%u data sets (FEEDPLAN_TEST_SEED=%u); expected 94.6 %%\n",
                kQueries[q][0], kQueries[q][1], 100 * rate, count, seed);
    EXPECT_GE(rate, 0.90);
    EXPECT_LE(rate, 0.99);
  }
}

// With revolution-to-revolution spread: each design point is a cutting test of 25 revolutions whose peaks
// scatter by 4 % about the true mean; the model is fitted to the tests' mean peaks, the spread is pooled
// from their revolutions, and the interval must hold a new revolution's peak at a query point at the
// nominal rate (about 95 %: the fit σ is small beside the spread). Without the spread term the same
// intervals hold far fewer of them.
TEST(PredictionInterval, ResponseSurfaceWithSpreadHoldsANewRevolutionsPeak) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 77u);
  const unsigned count = env_or("FEEDPLAN_TEST_COUNT", 400u);
  constexpr double kSpreadRel = 0.04;
  constexpr int kRevolutions = 25;
  const ResponseSurfaceModel t = truth();
  int covered = 0, covered_without_spread = 0, draws = 0;
  double spread_sum = 0.0;
  for (unsigned s = 0; s < count; ++s) {
    std::mt19937_64 rng(seed + s);
    std::normal_distribution<double> unit(0.0, 1.0);
    std::vector<FitSample> samples;
    std::vector<std::vector<double>> peaks;
    for (const auto& p : design()) {
      const double mean_n = predict(t, p[0], p[1]).force_n;
      std::vector<double> test;
      double sum = 0.0;
      for (int k = 0; k < kRevolutions; ++k) {
        test.push_back(mean_n * (1.0 + kSpreadRel * unit(rng)));
        sum += test.back();
      }
      samples.push_back({p[0], p[1], sum / kRevolutions});
      peaks.push_back(test);
    }
    const FitResult fit = fit_model(samples, squared_loss());
    ASSERT_EQ(fit.status, FitStatus::kOk) << "seed " << seed + s;
    const double spread = pooled_revolution_spread_rel(peaks);
    spread_sum += spread;
    for (const auto& q : kQueries) {
      const double new_peak_n = predict(t, q[0], q[1]).force_n * (1.0 + kSpreadRel * unit(rng));
      const PredictionInterval i = response_surface_interval(fit.model, fit.covariance, q[0], q[1], spread);
      const PredictionInterval narrow = response_surface_interval(fit.model, fit.covariance, q[0], q[1], 0.0);
      covered += new_peak_n >= i.lower_n && new_peak_n <= i.upper_n ? 1 : 0;
      covered_without_spread += new_peak_n >= narrow.lower_n && new_peak_n <= narrow.upper_n ? 1 : 0;
      ++draws;
    }
  }
  const double rate = static_cast<double>(covered) / draws;
  const double rate_without = static_cast<double>(covered_without_spread) / draws;
  std::printf("response-surface interval (z = 2) with a pooled spread of %.2f %% (true 4 %%) holds a new revolution's "
              "peak in %.1f %% of %d draws, without the spread term in %.1f %% (FEEDPLAN_TEST_SEED=%u "
              "FEEDPLAN_TEST_COUNT=%u)\n",
              100 * spread_sum / count, 100 * rate, draws, 100 * rate_without, seed, count);
  EXPECT_NEAR(spread_sum / count, kSpreadRel, 0.001);
  EXPECT_GE(rate, 0.90);
  EXPECT_LE(rate, 0.99);
  EXPECT_LT(rate_without, 0.6);
}

TEST(PredictionInterval, ResponseSurfaceBadArgumentsAreNamed) {
  Covariance c;
  c(2, 2) = -1.0;
  c(0, 1) = std::nan("");
  ResponseSurfaceModel m = truth();
  m.chip_scale_mm = 0.0;
  try {
    response_surface_interval(m, c, -0.1, std::nan(""), -0.5, 0.0);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string text = e.what();
    for (const char* field : {"chip_mm", "contact_length_mm", "revolution_spread_rel", "z =", "covariance[1]",
                              "covariance[14]", "model.chip_scale_mm"}) {
      EXPECT_NE(text.find(field), std::string::npos) << field << " in\n" << text;
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Mechanistic peak

MechanisticModel al7075() {
  MechanisticModel m;  // Altintas, Manufacturing Automation, Table 2.1 (data/materials.yaml)
  m.ktc_n_per_mm2 = 796;
  m.krc_n_per_mm2 = 169;
  m.kac_n_per_mm2 = 222;
  m.kte_n_per_mm = 27.7;
  m.kre_n_per_mm = 30.8;
  m.kae_n_per_mm = 1.4;
  return m;
}

using Matrix4 = std::array<std::array<double, 4>, 4>;

//! A covariance of (K_tc, K_rc, K_te, K_re) from standard deviations and correlations.
Matrix4 covariance_of(const std::array<double, 4>& sd, const Matrix4& correlation) {
  Matrix4 c{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) c[i][j] = sd[i] * sd[j] * correlation[i][j];
  }
  return c;
}

//! Lower Cholesky factor; false when the matrix is not positive definite.
bool cholesky(const Matrix4& a, Matrix4& l) {
  l = {};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j <= i; ++j) {
      double sum = a[i][j];
      for (int k = 0; k < j; ++k) sum -= l[i][k] * l[j][k];
      if (i == j) {
        if (!(sum > 0.0)) return false;
        l[i][i] = std::sqrt(sum);
      } else {
        l[i][j] = sum / l[j][j];
      }
    }
  }
  return true;
}

MechanisticModel with_coefficients(MechanisticModel m, const std::array<double, 4>& k) {
  m.ktc_n_per_mm2 = k[0];
  m.krc_n_per_mm2 = k[1];
  m.kte_n_per_mm = k[2];
  m.kre_n_per_mm = k[3];
  return m;
}

std::array<double, 4> identified(const MechanisticModel& m) {
  return {m.ktc_n_per_mm2, m.krc_n_per_mm2, m.kte_n_per_mm, m.kre_n_per_mm};
}

struct PeakCase {
  const char* name;
  MechanisticModel model;
  CutterGeometry cutter;
  std::vector<ImmersionArc> arcs;
  double depth_mm;
  double feed_per_tooth_mm;
};

std::vector<PeakCase> peak_cases() {
  MechanisticModel runout = al7075();
  runout.runout_mm = {0.012, 0.0};
  MechanisticModel size = al7075();
  size.size_exponent = 0.2;
  return {
      {"down milling a_e 3 mm, D10 Z4 30°", al7075(), {5.0, 4, 30.0}, {{kPi - std::acos(1.0 - 3.0 / 5.0), kPi}}, 5.0, 0.1},
      {"slot, D10 Z2 30°, 12 µm runout", runout, {5.0, 2, 30.0}, {{0.0, kPi}}, 3.0, 0.05},
      {"up milling a_e 1 mm, D12 Z3 40°, size effect", size, {6.0, 3, 40.0}, {{0.0, std::acos(1.0 - 1.0 / 6.0)}}, 8.0, 0.08},
  };
}

// The fit σ is the first-order propagation of C through the peak. Two truths the code does not use: the
// standard deviation of the peaks of 4000 coefficient sets drawn from N(K, C) (within 5 %: the Monte Carlo
// error of a standard deviation is 1/√(2·4000) = 1.1 %, the rest is the peak's curvature over ±3 σ), and
// the gradient of the peak by central finite differences of predicted_peak_force_n (within 0.5 %).
TEST(PredictionInterval, MechanisticFitSigmaMatchesMonteCarloAndFiniteDifferences) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 5150u);
  constexpr int kDraws = 4000;
  const Matrix4 correlation = {{{1.0, 0.3, -0.6, 0.0}, {0.3, 1.0, 0.0, -0.5}, {-0.6, 0.0, 1.0, 0.2}, {0.0, -0.5, 0.2, 1.0}}};
  const Matrix4 c = covariance_of({25.0, 15.0, 3.0, 4.0}, correlation);
  Matrix4 l;
  ASSERT_TRUE(cholesky(c, l));
  for (const PeakCase& pc : peak_cases()) {
    SCOPED_TRACE(pc.name);
    const EngagedSection section{0.0, pc.depth_mm, pc.arcs};
    const std::span<const EngagedSection> sections(&section, 1);
    const PredictionInterval interval =
        mechanistic_peak_interval(pc.model, c, sections, pc.cutter, pc.feed_per_tooth_mm, 0.0);
    EXPECT_EQ(interval.predicted_n, predicted_peak_force_n(pc.model, sections, pc.cutter, pc.feed_per_tooth_mm));

    std::mt19937_64 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    const std::array<double, 4> k = identified(pc.model);
    double sum = 0.0, squares = 0.0;
    for (int d = 0; d < kDraws; ++d) {
      std::array<double, 4> e{}, drawn = k;
      for (double& v : e) v = unit(rng);
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j <= i; ++j) drawn[i] += l[i][j] * e[j];
      }
      const double peak = predicted_peak_force_n(with_coefficients(pc.model, drawn), sections, pc.cutter, pc.feed_per_tooth_mm);
      sum += peak;
      squares += peak * peak;
    }
    const double mc_sd = std::sqrt((squares - sum * sum / kDraws) / (kDraws - 1));

    std::array<double, 4> g{};
    for (int i = 0; i < 4; ++i) {
      const double h = 1e-3 * std::abs(k[i]);
      std::array<double, 4> up = k, down = k;
      up[i] += h;
      down[i] -= h;
      g[i] = (predicted_peak_force_n(with_coefficients(pc.model, up), sections, pc.cutter, pc.feed_per_tooth_mm) -
              predicted_peak_force_n(with_coefficients(pc.model, down), sections, pc.cutter, pc.feed_per_tooth_mm)) /
             (2 * h);
    }
    double fd_variance = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) fd_variance += g[i] * c[i][j] * g[j];
    }
    const double fd_sd = std::sqrt(fd_variance);
    std::printf("%s: peak %.1f N, fit σ %.3f N; Monte Carlo (%d draws, FEEDPLAN_TEST_SEED=%u) %.3f N (%+.2f %%), "
                "finite differences %.3f N (%+.3f %%)\n",
                pc.name, interval.predicted_n, interval.fit_sd_n, kDraws, seed, mc_sd,
                100 * (interval.fit_sd_n - mc_sd) / mc_sd, fd_sd, 100 * (interval.fit_sd_n - fd_sd) / fd_sd);
    EXPECT_NEAR(interval.fit_sd_n, mc_sd, 0.05 * mc_sd);
    EXPECT_NEAR(interval.fit_sd_n, fd_sd, 0.005 * fd_sd);
  }
}

// The spread part: s_rel · F̂, combined with the fit σ in quadrature, z of them either side.
TEST(PredictionInterval, MechanisticIntervalAddsTheSpreadInQuadrature) {
  const PeakCase pc = peak_cases().front();
  const EngagedSection section{0.0, pc.depth_mm, pc.arcs};
  const std::span<const EngagedSection> sections(&section, 1);
  const Matrix4 c = covariance_of({25.0, 15.0, 3.0, 4.0}, {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}});
  const PredictionInterval fit_only = mechanistic_peak_interval(pc.model, c, sections, pc.cutter, pc.feed_per_tooth_mm, 0.0, 3.0);
  const PredictionInterval spread_only = mechanistic_peak_interval(pc.model, Matrix4{}, sections, pc.cutter, pc.feed_per_tooth_mm, 0.05, 3.0);
  const PredictionInterval both = mechanistic_peak_interval(pc.model, c, sections, pc.cutter, pc.feed_per_tooth_mm, 0.05, 3.0);
  const double peak_n = predicted_peak_force_n(pc.model, sections, pc.cutter, pc.feed_per_tooth_mm);
  EXPECT_EQ(spread_only.fit_sd_n, 0.0);
  EXPECT_NEAR(spread_only.spread_sd_n, 0.05 * peak_n, 1e-9 * peak_n);
  EXPECT_NEAR(spread_only.upper_n - spread_only.predicted_n, 3.0 * 0.05 * peak_n, 1e-9 * peak_n);
  EXPECT_NEAR(fit_only.upper_n - fit_only.predicted_n, 3.0 * fit_only.fit_sd_n, 1e-9 * peak_n);
  const double half_width = 3.0 * std::sqrt(fit_only.fit_sd_n * fit_only.fit_sd_n + 0.05 * 0.05 * peak_n * peak_n);
  EXPECT_NEAR(both.upper_n, peak_n + half_width, 1e-9 * peak_n);
  EXPECT_NEAR(both.lower_n, peak_n - half_width, 1e-9 * peak_n);
}

// The peak's spindle angle is where the kernel's force reaches the peak.
TEST(PredictionInterval, PeakAngleIsWhereTheKernelReachesThePeak) {
  for (const PeakCase& pc : peak_cases()) {
    SCOPED_TRACE(pc.name);
    const EngagedSection section{0.0, pc.depth_mm, pc.arcs};
    const std::span<const EngagedSection> sections(&section, 1);
    const MechanisticPeak peak = predicted_peak(pc.model, sections, pc.cutter, pc.feed_per_tooth_mm);
    const MechanisticForce f = predicted_force(pc.model, sections, pc.cutter, pc.feed_per_tooth_mm, peak.spindle_angle_rad);
    EXPECT_NEAR(std::hypot(f.fx_n, f.fy_n), peak.force_n, 1e-9 * peak.force_n);
    EXPECT_EQ(peak.force_n, predicted_peak_force_n(pc.model, sections, pc.cutter, pc.feed_per_tooth_mm));
  }
}

TEST(PredictionInterval, NothingEngagedGivesAZeroInterval) {
  const std::vector<ImmersionArc> back{{kPi + 0.5, kPi + 1.0}};
  const EngagedSection section{0.0, 5.0, back};
  const PredictionInterval i = mechanistic_peak_interval(al7075(), covariance_of({25, 15, 3, 4}, {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}}),
                                                         std::span<const EngagedSection>(&section, 1), {5.0, 4, 30.0}, 0.1, 0.05);
  EXPECT_EQ(i.predicted_n, 0.0);
  EXPECT_EQ(i.lower_n, 0.0);
  EXPECT_EQ(i.upper_n, 0.0);
}

TEST(PredictionInterval, MechanisticBadArgumentsAreNamed) {
  MechanisticModel m = al7075();
  m.ktc_n_per_mm2 = std::nan("");
  Matrix4 c{};
  c[3][3] = -2.0;
  c[1][2] = INFINITY;
  const std::vector<ImmersionArc> arcs{{1.0, 0.5}};
  const EngagedSection section{2.0, 1.0, arcs};
  try {
    mechanistic_peak_interval(m, c, std::span<const EngagedSection>(&section, 1), {5.0, 0, 30.0}, 0.0, -1.0, std::nan(""));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string text = e.what();
    for (const char* field : {"mechanistic.ktc_n_per_mm2", "mechanistic.cutter.flutes", "sections[0].top_mm",
                              "sections[0].arcs[0]", "feed_per_tooth_mm", "covariance[1][2]", "covariance[3][3]",
                              "revolution_spread_rel", "z ="}) {
      EXPECT_NE(text.find(field), std::string::npos) << field << " in\n" << text;
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Pooled revolution spread

// By hand: test 1 {100, 110, 90}, mean 100, relative deviations 0, 0.1, −0.1 (sum of squares 0.02, 2
// degrees of freedom); test 2 {200, 220}, mean 210, ±10/210 (sum of squares 2·(10/210)², 1 degree of
// freedom); a one-revolution test adds nothing. s² = (0.02 + 0.0045351…) / 3.
TEST(RevolutionSpread, PoolsRelativeDeviationsAboutEachTestsMean) {
  const double expected = std::sqrt((0.02 + 2 * (10.0 / 210) * (10.0 / 210)) / 3);
  EXPECT_NEAR(pooled_revolution_spread_rel({{100, 110, 90}, {200, 220}, {500}}), expected, 1e-12);
  EXPECT_NEAR(expected, 0.0904344, 1e-6);
  // Levels do not count as spread: a test scaled by 10 has the same relative spread.
  EXPECT_NEAR(pooled_revolution_spread_rel({{1000, 1100, 900}}), 0.1, 1e-12);
}

TEST(RevolutionSpread, RecoversAKnownRelativeSpread) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 99u);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<double>> tests;
  for (double level : {250.0, 500.0, 750.0}) {
    std::vector<double> peaks;
    for (int k = 0; k < 2000; ++k) peaks.push_back(level * (1.0 + 0.03 * unit(rng)));
    tests.push_back(peaks);
  }
  // 5997 degrees of freedom: the estimate's standard error is 0.03/√(2·5997) = 0.0003.
  EXPECT_NEAR(pooled_revolution_spread_rel(tests), 0.03, 0.0012) << "FEEDPLAN_TEST_SEED=" << seed;
}

TEST(RevolutionSpread, BadPeaksAreNamed) {
  EXPECT_THROW(pooled_revolution_spread_rel({}), InputError);
  EXPECT_THROW(pooled_revolution_spread_rel({{300.0}, {400.0}}), InputError);
  try {
    pooled_revolution_spread_rel({{1.0, std::nan("")}, {0.0, 0.0}, {-3.0, 2.0}});
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("peaks_per_test_n[0][1]"), std::string::npos) << text;
    EXPECT_NE(text.find("peaks_per_test_n[1] has mean 0"), std::string::npos) << text;
    EXPECT_NE(text.find("peaks_per_test_n[2][0]"), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace feedplan::model
