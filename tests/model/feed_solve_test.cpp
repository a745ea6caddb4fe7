// The feed that meets a target force (docs/method.md §5.3): hand-solved quadratics for each status, the linear
// case, bad arguments, and a seeded property test against an independent root computation in f.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/feed_solve.hpp"
#include "feedplan/model/model_prediction.hpp"

namespace feedplan::model {
namespace {

using ::testing::HasSubstr;

unsigned env_or(const char* name, unsigned fallback) {
  const char* text = std::getenv(name);
  return text != nullptr && *text != '\0' ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : fallback;
}

//! X1 = (t_m − 0.05)/0.05 = 20 t_m − 1, X2 = (L − 5)/5; range t_m 0.02–0.12 mm (X1 −0.6…1.4), L 2–8 mm.
ResponseSurfaceModel model_with(double b0, double b1, double b11, double b2 = 0.0, double b22 = 0.0,
                                double b12 = 0.0) {
  ResponseSurfaceModel model;
  model.beta = {b0, b1, b2, b11, b22, b12};
  model.chip_center_mm = 0.05;
  model.chip_scale_mm = 0.05;
  model.contact_length_center_mm = 5.0;
  model.contact_length_scale_mm = 5.0;
  model.range = {0.02, 0.12, 2.0, 8.0};
  return model;
}

constexpr double kK = 0.5;  // chip factor: f = t_m / 0.5 = 2 t_m

TEST(FeedSolve, ConvexRisingHandSolved) {
  // F = 300 + 100 X + 20 X², target 400: X² + 5X − 5 = 0 → X = (−5 + 3√5)/2, t_m = (1 + X)/20 = 3(√5 − 1)/40.
  const FeedSolution s = solve_feed(model_with(300, 100, 20), kK, 5.0, 400.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kOk);
  const double chip = 3.0 * (std::sqrt(5.0) - 1.0) / 40.0;
  EXPECT_NEAR(s.chip_mm, chip, 1e-15);
  EXPECT_NEAR(s.feed_per_tooth_mm, chip / kK, 1e-15);
  ASSERT_TRUE(s.root_feed_per_tooth_mm.has_value());
  EXPECT_DOUBLE_EQ(*s.root_feed_per_tooth_mm, s.feed_per_tooth_mm);
  EXPECT_NEAR(s.predicted_force_n, 400.0, 1e-10);
  EXPECT_TRUE(s.message.empty());
  EXPECT_FALSE(s.contact_length_outside);
}

TEST(FeedSolve, ConcaveRisingTakesTheSmallerRoot) {
  // F = 300 + 100 X − 20 X², target 350: X² − 5X + 2.5 = 0; the rising root is the smaller,
  // X = (5 − √15)/2 (the vertex is at X = 2.5), t_m = (7 − √15)/40.
  const FeedSolution s = solve_feed(model_with(300, 100, -20), kK, 5.0, 350.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kOk);
  EXPECT_NEAR(s.chip_mm, (7.0 - std::sqrt(15.0)) / 40.0, 1e-15);
}

TEST(FeedSolve, ConvexWithFallingRootAtSmallerFeedReturnsTheRisingOne) {
  // F = 100 + 50 X + 100 X², target 120: 100X² + 50X − 20 = 0 → X = (−50 ± √10500)/200. The falling root
  // X = −0.762 lies at t_m = 0.0119 mm > 0 (a positive feed), but dF/df < 0 there; the answer is the rising one.
  const FeedSolution s = solve_feed(model_with(100, 50, 100), kK, 5.0, 120.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kOk);
  const double x = (-50.0 + std::sqrt(10500.0)) / 200.0;
  EXPECT_NEAR(s.chip_mm, (1.0 + x) / 20.0, 1e-15);
  const double falling_chip = (1.0 + (-50.0 - std::sqrt(10500.0)) / 200.0) / 20.0;
  ASSERT_GT(falling_chip, 0.0);
  EXPECT_GT(s.chip_mm, falling_chip);
}

TEST(FeedSolve, ContactLengthEntersThroughBetaTwoTwentyTwoAndTwelve) {
  // β = {300, 100, 50, 20, 10, 30} at L = 7.5 (X2 = 0.5): A = 300 + 25 + 2.5 = 327.5, B = 100 + 15 = 115,
  // C = 20; target 400: 20X² + 115X − 72.5 = 0 → X = (−115 + √19025)/40.
  const FeedSolution s = solve_feed(model_with(300, 100, 20, 50, 10, 30), kK, 7.5, 400.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kOk);
  EXPECT_NEAR(s.chip_mm, (1.0 + (-115.0 + std::sqrt(19025.0)) / 40.0) / 20.0, 1e-15);
}

TEST(FeedSolve, LinearModel) {
  // β11 = 0: F = 300 + 100 X, target 350 → X = 0.5, t_m = 0.075 mm, f = 0.15 mm.
  const FeedSolution s = solve_feed(model_with(300, 100, 0), kK, 5.0, 350.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kOk);
  EXPECT_NEAR(s.chip_mm, 0.075, 1e-15);
  EXPECT_NEAR(s.feed_per_tooth_mm, 0.15, 1e-15);
  // A vanishing β11 of either sign is the same answer to rounding, not a division by a tiny number.
  for (double tiny : {1e-13, -1e-13, 1e-300, -1e-300}) {
    const FeedSolution t = solve_feed(model_with(300, 100, tiny), kK, 5.0, 350.0);
    EXPECT_EQ(t.status, FeedSolveStatus::kOk) << tiny;
    EXPECT_NEAR(t.chip_mm, 0.075, 1e-14) << tiny;
  }
}

TEST(FeedSolve, DecreasingLinearModel) {
  // F = 300 − 50 X falls with the feed: F(t_m = 0) = F(X = −1) = 350.
  const ResponseSurfaceModel model = model_with(300, -50, 0);
  FeedSolution s = solve_feed(model, kK, 5.0, 320.0);  // above at f → 0+: target below model
  EXPECT_EQ(s.status, FeedSolveStatus::kTargetBelowModel);
  EXPECT_NEAR(s.feed_per_tooth_mm, 0.02 / kK, 1e-15);
  s = solve_feed(model, kK, 5.0, 400.0);  // never reached; the range maximum is at t_min (X = −0.6): 330 N
  EXPECT_EQ(s.status, FeedSolveStatus::kUnreachable);
  EXPECT_NEAR(s.chip_mm, 0.02, 1e-15);
  EXPECT_NEAR(s.predicted_force_n, 330.0, 1e-10);
}

TEST(FeedSolve, ClampedAboveRange) {
  // F = 300 + 100 X + 20 X², target 600: X² + 5X − 15 = 0 → X = (−5 + √85)/2 = 2.11 → t_m = 0.1555 > 0.12.
  const FeedSolution s = solve_feed(model_with(300, 100, 20), kK, 5.0, 600.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kClampedToRange);
  EXPECT_NEAR(s.chip_mm, 0.12, 1e-15);
  EXPECT_NEAR(s.feed_per_tooth_mm, 0.24, 1e-15);
  ASSERT_TRUE(s.root_feed_per_tooth_mm.has_value());
  EXPECT_NEAR(*s.root_feed_per_tooth_mm, (1.0 + (-5.0 + std::sqrt(85.0)) / 2.0) / 20.0 / kK, 1e-15);
  EXPECT_NEAR(s.predicted_force_n, 300.0 + 140.0 + 20.0 * 1.96, 1e-10);  // X = 1.4
  EXPECT_THAT(s.message, HasSubstr("above the fitted t_m range 0.02–0.12 mm"));
  EXPECT_THAT(s.message, HasSubstr("clamped"));
}

TEST(FeedSolve, ClampedBelowRange) {
  // Target 240: X² + 5X + 3 = 0 → X = (−5 + √13)/2 = −0.697 → t_m = 0.0151 < 0.02.
  const FeedSolution s = solve_feed(model_with(300, 100, 20), kK, 5.0, 240.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kClampedToRange);
  EXPECT_NEAR(s.chip_mm, 0.02, 1e-15);
  ASSERT_TRUE(s.root_feed_per_tooth_mm.has_value());
  EXPECT_NEAR(*s.root_feed_per_tooth_mm, (1.0 + (-5.0 + std::sqrt(13.0)) / 2.0) / 20.0 / kK, 1e-15);
  EXPECT_NEAR(s.predicted_force_n, 300.0 - 60.0 + 20.0 * 0.36, 1e-10);  // X = −0.6
  EXPECT_THAT(s.message, HasSubstr("below the fitted t_m range"));
}

TEST(FeedSolve, TargetBelowModel) {
  // F(t_m = 0) = F(X = −1) = 300 − 100 + 20 = 220 > target 200; the rising root X = (−5 + √5)/2 = −1.38 is at
  // a negative feed.
  const FeedSolution s = solve_feed(model_with(300, 100, 20), kK, 5.0, 200.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kTargetBelowModel);
  EXPECT_NEAR(s.feed_per_tooth_mm, 0.02 / kK, 1e-15);
  EXPECT_FALSE(s.root_feed_per_tooth_mm.has_value());
  EXPECT_NEAR(s.predicted_force_n, 247.2, 1e-10);
  EXPECT_THAT(s.message, HasSubstr("already above the target 200 N"));
  // A convex model entirely above the target (no real root at all) is the same case.
  const FeedSolution t = solve_feed(model_with(300, 10, 20), kK, 5.0, 200.0);
  EXPECT_EQ(t.status, FeedSolveStatus::kTargetBelowModel);
}

TEST(FeedSolve, UnreachableAtConcaveMaximum) {
  // F = 300 + 100 X − 40 X²: vertex X = 1.25 (t_m = 0.1125, inside), maximum 362.5 N < target 400.
  const FeedSolution s = solve_feed(model_with(300, 100, -40), kK, 5.0, 400.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kUnreachable);
  EXPECT_NEAR(s.chip_mm, 0.1125, 1e-15);
  EXPECT_NEAR(s.feed_per_tooth_mm, 0.225, 1e-15);
  EXPECT_NEAR(s.predicted_force_n, 362.5, 1e-10);
  EXPECT_FALSE(s.root_feed_per_tooth_mm.has_value());
  EXPECT_THAT(s.message, HasSubstr("never reaches the target 400 N"));
}

TEST(FeedSolve, ConcaveBeyondRangeIsClampedOrUnreachable) {
  // F = 300 + 100 X − 10 X²: vertex X = 5 (t_m = 0.3, beyond the range), maximum 550 N.
  const ResponseSurfaceModel model = model_with(300, 100, -10);
  // Target 500: D = 10000 − 8000, rising root X = (100 − √2000)/20 = 2.76 → t_m = 0.188: clamped at t_max.
  FeedSolution s = solve_feed(model, kK, 5.0, 500.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kClampedToRange);
  ASSERT_TRUE(s.root_feed_per_tooth_mm.has_value());
  EXPECT_NEAR(*s.root_feed_per_tooth_mm, (1.0 + (100.0 - std::sqrt(2000.0)) / 20.0) / 20.0 / kK, 1e-15);
  // Target 600 > 550: unreachable; the largest F̂ in range is at t_max (X = 1.4): 300 + 140 − 19.6.
  s = solve_feed(model, kK, 5.0, 600.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kUnreachable);
  EXPECT_NEAR(s.chip_mm, 0.12, 1e-15);
  EXPECT_NEAR(s.predicted_force_n, 420.4, 1e-10);
}

TEST(FeedSolve, ContactLengthOutsideRangeIsFlagged) {
  const FeedSolution s = solve_feed(model_with(300, 100, 20), kK, 9.0, 400.0);
  EXPECT_EQ(s.status, FeedSolveStatus::kOk);
  EXPECT_TRUE(s.contact_length_outside);
  EXPECT_THAT(s.message, HasSubstr("L = 9 mm lies outside the fitted L range 2–8 mm"));
}

TEST(FeedSolve, BadArgumentsAreInputErrors) {
  const ResponseSurfaceModel model = model_with(300, 100, 20);
  const auto fields_of = [&](const ResponseSurfaceModel& m, double k, double l, double target) {
    std::vector<std::string> fields;
    try {
      solve_feed(m, k, l, target);
    } catch (const InputError& error) {
      for (const auto& p : error.problems()) fields.push_back(p.field);
    }
    return fields;
  };
  EXPECT_THAT(fields_of(model, 0.0, 5.0, 400.0), ::testing::ElementsAre("chip_factor"));
  EXPECT_THAT(fields_of(model, 1.5, 5.0, 400.0), ::testing::ElementsAre("chip_factor"));
  EXPECT_THAT(fields_of(model, 0.5, -1.0, 400.0), ::testing::ElementsAre("contact_length_mm"));
  EXPECT_THAT(fields_of(model, 0.5, 5.0, std::numeric_limits<double>::quiet_NaN()),
              ::testing::ElementsAre("target_force_n"));
  EXPECT_THAT(fields_of(model, 0.5, 5.0, -10.0), ::testing::ElementsAre("target_force_n"));
  ResponseSurfaceModel broken = model;
  broken.beta[kBeta11] = std::numeric_limits<double>::infinity();
  EXPECT_THAT(fields_of(broken, 1.0, 5.0, 400.0), ::testing::ElementsAre("model.beta[3]"));
  EXPECT_NO_THROW(solve_feed(model, 1.0, 0.0, 400.0));
}

//! Every positive root of F̂(f) = target with dF̂/df > 0, in f directly: F̂ expanded as a2 f² + a1 f + a0
//! (long double, textbook formula) — a different route from the solver's, which works in X1.
std::vector<long double> rising_roots_in_feed(const ResponseSurfaceModel& m, double k, double length, double target) {
  const long double x2 = (length - m.contact_length_center_mm) / static_cast<long double>(m.contact_length_scale_mm);
  const auto& b = m.beta;
  const long double A = b[0] + b[2] * x2 + b[4] * x2 * x2, B = b[1] + b[5] * x2, C = b[3];
  const long double c1 = m.chip_center_mm, s1 = m.chip_scale_mm;
  // X1 = (k f − c1)/s1 = p f + q
  const long double p = k / s1, q = -c1 / s1;
  const long double a2 = C * p * p, a1 = B * p + 2 * C * p * q, a0 = A + B * q + C * q * q - target;
  std::vector<long double> roots;
  if (a2 == 0) {
    if (a1 != 0) roots.push_back(-a0 / a1);
  } else {
    const long double d = a1 * a1 - 4 * a2 * a0;
    if (d >= 0) {
      roots.push_back((-a1 - std::sqrt(d)) / (2 * a2));
      roots.push_back((-a1 + std::sqrt(d)) / (2 * a2));
    }
  }
  std::vector<long double> rising;
  for (long double f : roots) {
    if (f > 0 && 2 * a2 * f + a1 > 0) rising.push_back(f);
  }
  return rising;
}

TEST(FeedSolveProperty, RandomIncreasingModels) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 20240517u);
  const unsigned count = env_or("FEEDPLAN_TEST_COUNT", 20000u);
  std::cout << "feed solve property: FEEDPLAN_TEST_SEED=" << seed << " FEEDPLAN_TEST_COUNT=" << count << "\n";
  std::mt19937_64 rng(seed);
  const auto uniform = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::map<FeedSolveStatus, int> statuses;
  double worst_relative_error = 0.0;
  for (unsigned n = 0; n < count; ++n) {
    ResponseSurfaceModel m;
    const double t_min = uniform(0.005, 0.05), t_max = t_min + uniform(0.02, 0.2);
    const double l_min = uniform(0.5, 5.0), l_max = l_min + uniform(1.0, 10.0);
    m.range = {t_min, t_max, l_min, l_max};
    m.chip_center_mm = 0.5 * (t_min + t_max) * uniform(0.8, 1.2);
    m.chip_scale_mm = 0.5 * (t_max - t_min) * uniform(0.5, 2.0);
    m.contact_length_center_mm = 0.5 * (l_min + l_max);
    m.contact_length_scale_mm = 0.5 * (l_max - l_min);
    const double k = uniform(0.05, 1.0);
    const double length = uniform(l_min, l_max);
    const double x_lo = (t_min - m.chip_center_mm) / m.chip_scale_mm;
    const double x_hi = (t_max - m.chip_center_mm) / m.chip_scale_mm;
    const double x2 = (length - m.contact_length_center_mm) / m.contact_length_scale_mm;
    // Draw until F̂ increases in t_m over the whole range at this L: B + 2 C X1 > 0 at both ends.
    for (;;) {
      m.beta = {uniform(50, 800), uniform(0, 300), uniform(-100, 100), uniform(-80, 80), uniform(-40, 40),
                uniform(-60, 60)};
      if (n % 10 == 0) m.beta[kBeta11] = 0.0;  // the linear case too
      const double B = m.beta[kBeta1] + m.beta[kBeta12] * x2, C = m.beta[kBeta11];
      if (B + 2 * C * x_lo > 0 && B + 2 * C * x_hi > 0) break;
    }
    const double f_lo = predict(m, t_min, length).force_n, f_hi = predict(m, t_max, length).force_n;
    // Mostly targets inside [F̂(t_min), F̂(t_max)] (kOk), some beyond either end.
    const double u = uniform(-0.3, 1.3);
    const double target = f_lo + u * (f_hi - f_lo);
    if (!(target > 0)) continue;
    const FeedSolution s = solve_feed(m, k, length, target);
    ++statuses[s.status];
    const std::string where = "case " + std::to_string(n) + " (seed " + std::to_string(seed) + ")";
    const std::vector<long double> roots = rising_roots_in_feed(m, k, length, target);
    const double force_at_feed = predict(m, k * s.feed_per_tooth_mm, length).force_n;
    EXPECT_NEAR(s.predicted_force_n, force_at_feed, 1e-9 * std::abs(force_at_feed)) << where;
    switch (s.status) {
      case FeedSolveStatus::kOk: {
        const double relative = std::abs(force_at_feed - target) / target;
        worst_relative_error = std::max(worst_relative_error, relative);
        EXPECT_LE(relative, 1e-9) << where;
        ASSERT_FALSE(roots.empty()) << where;
        // f* is the smallest positive rising root (there is at most one; the oracle lists all).
        for (long double r : roots) EXPECT_LE(s.feed_per_tooth_mm, r * (1 + 1e-9L)) << where;
        EXPECT_NEAR(s.feed_per_tooth_mm, static_cast<double>(roots.front()), 1e-9 * s.feed_per_tooth_mm) << where;
        EXPECT_GE(u, -1e-6) << where;
        EXPECT_LE(u, 1 + 1e-6) << where;
        break;
      }
      case FeedSolveStatus::kClampedToRange: {
        ASSERT_TRUE(s.root_feed_per_tooth_mm.has_value()) << where;
        ASSERT_EQ(roots.size(), 1u) << where;
        EXPECT_NEAR(*s.root_feed_per_tooth_mm, static_cast<double>(roots.front()), 1e-9 * *s.root_feed_per_tooth_mm) << where;
        const double root_chip = k * *s.root_feed_per_tooth_mm;
        EXPECT_TRUE(root_chip < t_min || root_chip > t_max) << where;
        EXPECT_DOUBLE_EQ(s.chip_mm, root_chip > t_max ? t_max : t_min) << where;
        // The model rises over the range: at the clamped edge it is below the target above, over it below.
        if (root_chip > t_max) {
          EXPECT_LT(force_at_feed, target) << where;
        } else {
          EXPECT_GT(force_at_feed, target) << where;
        }
        break;
      }
      case FeedSolveStatus::kTargetBelowModel:
        EXPECT_TRUE(roots.empty()) << where;
        EXPECT_DOUBLE_EQ(s.chip_mm, t_min) << where;
        EXPECT_GE(force_at_feed, target) << where;
        EXPECT_LT(u, 0.0) << where;
        break;
      case FeedSolveStatus::kUnreachable:
        EXPECT_TRUE(roots.empty()) << where;
        EXPECT_LT(f_hi, target) << where;
        EXPECT_GT(u, 1.0) << where;
        break;
    }
  }
  std::cout << "feed solve property: ok " << statuses[FeedSolveStatus::kOk] << ", clamped "
            << statuses[FeedSolveStatus::kClampedToRange] << ", target below model "
            << statuses[FeedSolveStatus::kTargetBelowModel] << ", unreachable "
            << statuses[FeedSolveStatus::kUnreachable] << "; worst |F̂ − target|/target " << worst_relative_error
            << "\n";
  EXPECT_GT(statuses[FeedSolveStatus::kOk], static_cast<int>(count) / 2);
  EXPECT_GT(statuses[FeedSolveStatus::kClampedToRange], 0);
}

}  // namespace
}  // namespace feedplan::model
