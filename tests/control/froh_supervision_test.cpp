// Seed 004's supervisor (§III.E–F, §IV): the tracking index of Eq. 10 and the two switching schemes, against
// values worked out by hand.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "feedplan/control/beta_switching.hpp"
#include "feedplan/control/froh_model_reference_controller.hpp"
#include "feedplan/control/tracking_index.hpp"

namespace feedplan::control {
namespace {

// ∫₀¹ |t − 0.5| dt = 0.25 exactly; the trapezoid rule on 5 points (a node at the kink) is exact for a
// piecewise-linear integrand. And ∫₀^π |sin t| dt = 2: the rule's error with 64 intervals is about
// π³/(12·64²) · mean|sin''| ≈ 4e-4, so 1e-3.
TEST(TrackingIndex, PeriodAreaIsTheIntegralOfTheAbsoluteDifference) {
  const std::vector<double> line{0.0, 0.25, 0.5, 0.75, 1.0}, half(5, 0.5);
  EXPECT_NEAR(period_absolute_area(line, half, 1.0), 0.25, 1e-15);
  std::vector<double> sine, zero(65, 0.0);
  for (int i = 0; i <= 64; ++i) sine.push_back(std::sin(3.141592653589793 * i / 64.0));
  EXPECT_NEAR(period_absolute_area(sine, zero, 3.141592653589793), 2.0, 1e-3);
}

// Eq. 10 with λ = 0.5 over three periods: 4 + 0.5·2 + 0.25·8 = 7; λ = 1 sums them.
TEST(TrackingIndex, ForgettingWeightsTheNewestPeriodMost) {
  const std::vector<double> areas{4.0, 2.0, 8.0};
  EXPECT_DOUBLE_EQ(tracking_index(areas, 0.5), 7.0);
  EXPECT_DOUBLE_EQ(tracking_index(areas, 1.0), 14.0);
}

TEST(BetaSwitching, FixedSetTakesTheSmallestIndexAndTiesKeepTheActiveModel) {
  const std::vector<double> bank = seed_004_beta_bank();
  ASSERT_EQ(bank.size(), 15u);
  EXPECT_DOUBLE_EQ(bank.front(), 1.0);
  EXPECT_NEAR(bank.back(), -0.4, 1e-15);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(fixed_set_choice(std::vector<double>{3.0, 1.0, 2.0}, 0), 1u);
  EXPECT_EQ(fixed_set_choice(std::vector<double>{1.0, 2.0, 1.0}, 2), 2u);
  EXPECT_EQ(fixed_set_choice(std::vector<double>{nan, 2.0, 5.0}, 0), 1u);
}

// §III.F's steps from β = 0.2, Δβ = 0.2, m = 2: the upper neighbour wins (β = 0.4, Δβ kept), β stays (Δβ
// halves to 0.1), the lower neighbour wins (β = 0.3, neighbours 0.2 and 0.4); and at the top of the range the
// upper neighbour is clamped to 1.
TEST(BetaSwitching, NeighbourSearchFollowsSectionIIIF) {
  NeighbourBetaSearch search({0.2, 0.2, 2.0});
  EXPECT_TRUE(search.update({3.0, 2.0, 1.0}));
  EXPECT_NEAR(search.active_beta(), 0.4, 1e-15);
  EXPECT_NEAR(search.step(), 0.2, 1e-15);
  EXPECT_FALSE(search.update({3.0, 1.0, 1.0}));
  EXPECT_NEAR(search.step(), 0.1, 1e-15);
  EXPECT_NEAR(search.candidates()[0], 0.3, 1e-15);
  EXPECT_NEAR(search.candidates()[2], 0.5, 1e-15);
  EXPECT_TRUE(search.update({0.5, 1.0, 2.0}));
  EXPECT_NEAR(search.active_beta(), 0.3, 1e-15);
  EXPECT_NEAR(search.candidates()[0], 0.2, 1e-15);
  EXPECT_NEAR(search.candidates()[2], 0.4, 1e-15);
  NeighbourBetaSearch top({0.9, 0.2, 2.0});
  EXPECT_DOUBLE_EQ(top.candidates()[2], 1.0);
}

// The controller with a bank of one β never switches and holds the hold at that β; with the paper's bank
// and a residence of 1000 periods it cannot switch within 20 samples either.
TEST(BetaSwitching, SingleModelBankAndLongResidenceNeverSwitch) {
  FrohModelReferenceParameters zoh;
  zoh.betas = {0.0};
  FrohModelReferenceParameters slow;
  slow.residence_periods = 1000;
  for (const FrohModelReferenceParameters& p : {zoh, slow}) {
    FrohModelReferenceController controller(p);
    double force = 0.0;
    for (int k = 0; k < 20; ++k) {
      controller.step(force, 60.0 / 715.0);
      force = 0.5 * force + 300.0;  // any force: the switching is what is watched
    }
    EXPECT_EQ(controller.switches(), 0);
    EXPECT_DOUBLE_EQ(controller.active_beta(), p.betas.front());
  }
}

}  // namespace
}  // namespace feedplan::control
