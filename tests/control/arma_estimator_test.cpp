// The RLS of seed 002 (Goodwin & Sin's covariance resetting and dead zone) on a known ARMA system. The truth
// is the system the data were generated with; the data are the system's own response to a random feed
// sequence, with a white equation-error disturbance — the noise model under which least squares on the
// regressor of Eq. 21 is unbiased (an output-error noise would bias φ1, φ2, whatever the estimator).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "feedplan/control/arma_estimator.hpp"
#include "feedplan/control/arma_model.hpp"

namespace feedplan::control {
namespace {

// Poles 0.7 and 0.5, a zero at −0.6, steady gain (0.5 + 0.3)/(1 − 1.2 + 0.35) = 5.33 N per mm/min.
constexpr ArmaModel kTruth{-1.2, 0.35, 0.5, 0.3};
constexpr unsigned kSeed = 20240611;

// Feeds held for 2–5 samples at random levels in 50–150 mm/min: persistently exciting for four parameters.
class RandomFeed {
 public:
  explicit RandomFeed(unsigned seed) : rng_(seed) {}
  double next() {
    if (left_ == 0) {
      level_ = std::uniform_real_distribution<double>(50.0, 150.0)(rng_);
      left_ = std::uniform_int_distribution<int>(2, 5)(rng_);
    }
    --left_;
    return level_;
  }
  double last() const { return level_; }  //!< the feed returned last (100 before the first)

 private:
  std::mt19937 rng_;
  double level_ = 100.0;
  int left_ = 0;
};

// P₀ = I: a weak prior, so that the data decide (the controller's default p₀ = 1e-5 trusts its starting
// model on purpose; here the start is deliberately wrong).
ArmaEstimatorParameters weak_prior() {
  ArmaEstimatorParameters parameters;
  parameters.initial_variance = 1.0;
  return parameters;
}

// Runs `samples` samples of `plant` from `estimator`'s point of view. `plant` must hold the feed
// feeds.last() from before (it starts at 100 mm/min, as RandomFeed does).
void feed(ArmaEstimator& estimator, ArmaPlant& plant, RandomFeed& feeds, std::mt19937& noise_rng, double sigma_n,
          int samples) {
  std::normal_distribution<double> noise(0.0, sigma_n);
  double f1 = plant.force_n(), f2 = f1, v1 = feeds.last();
  for (int t = 0; t < samples; ++t) {
    const double v = feeds.next();
    const double f = plant.step(v, noise(noise_rng));  // f(t+1), from v(t) and v(t−1)
    estimator.update(f, arma_regressor(f1, f2, v, v1));
    f2 = f1, f1 = f, v1 = v;
  }
}

// 2000 samples with σ = 2 N and no dead zone: every coefficient within 0.02 of the truth. The spread of
// the least-squares estimate is σ √(diag((ΦᵀΦ)⁻¹)) ≈ 2 / (√2000 · ~100) ≈ 5e-4 for θ and a few 1e-3 for φ
// (the force regressors are correlated), so 0.02 is five or more standard deviations.
TEST(ArmaEstimator, RecoversAKnownSystemFromNoisyData) {
  ArmaEstimatorParameters parameters = weak_prior();
  parameters.dead_zone_n = 0.0;
  parameters.reset_trace = 0.0;
  ArmaEstimator estimator(ArmaModel{-0.5, 0.0, 1.0, 1.0}, parameters);
  ArmaPlant plant(kTruth, 100.0);
  RandomFeed feeds(kSeed);
  std::mt19937 noise_rng(kSeed + 1);
  feed(estimator, plant, feeds, noise_rng, 2.0, 2000);
  SCOPED_TRACE("seed " + std::to_string(kSeed) + ", 2000 samples");
  const ArmaModel& m = estimator.model();
  EXPECT_NEAR(m.phi1, kTruth.phi1, 0.02);
  EXPECT_NEAR(m.phi2, kTruth.phi2, 0.02);
  EXPECT_NEAR(m.theta0, kTruth.theta0, 0.02);
  EXPECT_NEAR(m.theta1, kTruth.theta1, 0.02);
  EXPECT_EQ(estimator.updates(), 2000);
  std::printf("RLS after 2000 samples (σ = 2 N): φ1 %.4f φ2 %.4f θ0 %.4f θ1 %.4f (truth −1.2 0.35 0.5 0.3)\n", m.phi1,
              m.phi2, m.theta0, m.theta1);
}

// The dead zone as documented: with d = 4σ = 8 N, once the estimate predicts within the noise, samples
// stop moving it — at most a few percent of the last 1000 samples update (a 4σ Gaussian excursion has
// probability 6e-5; the updates that remain come from the estimate's own residual error) — and the
// estimate still lies within 0.05 of the truth (it stops where the a-priori error first falls inside d).
TEST(ArmaEstimator, DeadZoneStopsUpdatesOnceTheErrorIsWithinIt) {
  ArmaEstimatorParameters parameters = weak_prior();
  parameters.dead_zone_n = 8.0;
  parameters.reset_trace = 0.0;
  ArmaEstimator estimator(ArmaModel{-0.5, 0.0, 1.0, 1.0}, parameters);
  ArmaPlant plant(kTruth, 100.0);
  RandomFeed feeds(kSeed);
  std::mt19937 noise_rng(kSeed + 1);
  feed(estimator, plant, feeds, noise_rng, 2.0, 1000);
  const int updates_before = estimator.updates();
  feed(estimator, plant, feeds, noise_rng, 2.0, 1000);
  EXPECT_LE(estimator.updates() - updates_before, 30);
  EXPECT_EQ(estimator.updates() + estimator.skipped_in_dead_zone(), 2000);
  const ArmaModel& m = estimator.model();
  EXPECT_NEAR(m.phi1, kTruth.phi1, 0.05);
  EXPECT_NEAR(m.phi2, kTruth.phi2, 0.05);
  EXPECT_NEAR(m.theta0, kTruth.theta0, 0.05);
  EXPECT_NEAR(m.theta1, kTruth.theta1, 0.05);
}

// Covariance resetting as documented: after 500 samples the plant changes (its gain triples, a deeper
// cut). Without resetting P has shrunk like 1/t and the estimate crawls towards the new plant; with
// resetting (whenever trace P falls below 1/100 of trace P₀) it gets there. 100 samples after the change
// the resetting estimator's θ0 is within 0.05 of the new 1.5, and closer than the plain one's.
TEST(ArmaEstimator, CovarianceResettingFollowsAChangedPlant) {
  const ArmaModel changed{kTruth.phi1, kTruth.phi2, 3.0 * kTruth.theta0, 3.0 * kTruth.theta1};
  auto run = [&](double reset_trace) {
    ArmaEstimatorParameters parameters = weak_prior();
    parameters.dead_zone_n = 0.0;
    parameters.reset_trace = reset_trace;
    ArmaEstimator estimator(ArmaModel{-0.5, 0.0, 1.0, 1.0}, parameters);
    ArmaPlant plant(kTruth, 100.0);
    RandomFeed feeds(kSeed);
    std::mt19937 noise_rng(kSeed + 1);
    feed(estimator, plant, feeds, noise_rng, 2.0, 500);
    plant.set_model(changed);
    feed(estimator, plant, feeds, noise_rng, 2.0, 100);
    return estimator;
  };
  const ArmaEstimator plain = run(0.0);
  const ArmaEstimator resetting = run(0.04);
  EXPECT_EQ(plain.resets(), 0);
  EXPECT_GT(resetting.resets(), 0);
  EXPECT_NEAR(resetting.model().theta0, changed.theta0, 0.05);
  EXPECT_LT(std::abs(resetting.model().theta0 - changed.theta0), std::abs(plain.model().theta0 - changed.theta0));
}

}  // namespace
}  // namespace feedplan::control
