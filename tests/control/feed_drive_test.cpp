// Seed 002's feed drive, 14 e^{−0.08 s}/(s + 14) (Eq. 3), sampled once per revolution. The truth is the
// continuous step response y(t) = 1 − e^{−14 (t − 0.08)} for t ≥ 0.08 s (0 before), read at the sample
// times, and the modified z-transform's weights worked out by hand for T = 0.1 s.

#include <gtest/gtest.h>

#include <cmath>

#include "feedplan/control/arma_model.hpp"
#include "feedplan/control/feed_drive.hpp"

namespace feedplan::control {
namespace {

double continuous_step_response(double t_s, double dead_time_s) {
  return t_s < dead_time_s ? 0.0 : 1.0 - std::exp(-14.0 * (t_s - dead_time_s));
}

// A unit step of the command from 0 (a 100 mm/min step, force gain 1 N per mm/min) sampled at 0.1 s
// (dead time within one period) and at 0.03 s (dead time 2 periods + 0.02 s): the samples are the
// continuous response at the sample times to 1e-9 N — the discretisation is exact, not approximate.
TEST(FeedDrive, SampledStepResponseIsTheContinuousOne) {
  for (double period_s : {0.1, 0.03}) {
    FeedDriveProcess drive(FeedDriveParameters{}, period_s, 1.0, 0.0);
    for (int k = 1; k <= 20; ++k) {
      const double force = drive.step(100.0);
      EXPECT_NEAR(force, 100.0 * continuous_step_response(k * period_s, 0.08), 1e-9) << "T = " << period_s << ", k = " << k;
    }
  }
}

// The ARMA form at T = 0.1 s with K_f = 500/360 N per mm/min (seed 002's first cut): by hand, α = e^{−1.4}
// = 0.246597, the command of the previous period acts for δ = 0.08 s and then decays for 0.02 s:
// e^{−0.28}(1 − e^{−1.12}) = 0.509187, the current one for 0.02 s: 1 − e^{−0.28} = 0.244216. So φ1 = −0.246597,
// φ2 = 0, θ0 = 0.339189, θ1 = 0.707204 — the adaptive servo's default starting model. And with the dead time
// over a period there is no second-order form.
TEST(FeedDrive, ArmaEquivalentHasTheHandWorkedWeights) {
  const auto model = arma_equivalent(FeedDriveParameters{}, 0.1, 500.0 / 360.0);
  ASSERT_TRUE(model.has_value());
  EXPECT_NEAR(model->phi1, -0.246597, 1e-6);
  EXPECT_EQ(model->phi2, 0.0);
  EXPECT_NEAR(model->theta0, 0.244216 * 500.0 / 360.0, 1e-6);
  EXPECT_NEAR(model->theta1, 0.509187 * 500.0 / 360.0, 1e-6);
  EXPECT_FALSE(arma_equivalent(FeedDriveParameters{}, 0.03, 1.0).has_value());
}

// The ARMA plant run with those coefficients and the drive itself give the same forces for any command
// sequence (here a staircase), sample for sample.
TEST(FeedDrive, ArmaPlantOfTheEquivalentMatchesTheDrive) {
  const double gain = 4.0;
  const ArmaModel model = *arma_equivalent(FeedDriveParameters{}, 0.1, gain);
  FeedDriveProcess drive(FeedDriveParameters{}, 0.1, gain, 200.0);
  ArmaPlant arma(model, 200.0);
  for (int k = 0; k < 40; ++k) {
    const double command = 200.0 + 25.0 * ((k / 4) % 5);
    EXPECT_NEAR(arma.step(command), drive.step(command), 1e-9) << k;
  }
}

}  // namespace
}  // namespace feedplan::control
