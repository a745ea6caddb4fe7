// Seed 002's experiment (Figs. 9–10) on its own plant model: 500 N held while the cut changes from steel
// at 1 mm depth to steel at 2 mm and then to aluminium at 2 mm. The plant is the feed drive of Eq. 3 with
// the force gains seed 002's results imply (500 N at 360, 120 and 320 mm/min), sampled once per
// revolution (0.1 s), the force read with 10 N of white noise per revolution (seed 002's current-based
// force; its Fig. 6 shows deviations up to 100 N at the tooth level, less on a revolution's peak). The
// truth: seed 002's result that "the error bound of the controlled cutting force is within 50 N at the
// steady-state region for the desired command input of 500 N, regardless of the change of depth-of-cut and
// workpiece material", with the feeds the gains imply.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "feedplan/control/adaptive_robust_servo.hpp"
#include "feedplan/control/feed_drive.hpp"

namespace feedplan::control {
namespace {

constexpr double kPeriodS = 0.1;
constexpr unsigned kSeed = 1996;

// 10 s per cut; "steady state" is the last 5 s of each (the servo's slowest pole, 0.75 per sample, leaves
// 6e-7 of a transient after 5 s once the estimate has settled; the adaptation needs the first seconds).
TEST(AdaptiveRobustServo, HoldsFiveHundredNewtonsWithinFiftyAcrossDepthAndMaterial) {
  const std::array<double, 3> gains{500.0 / 360.0, 500.0 / 120.0, 500.0 / 320.0};
  const std::array<double, 3> feeds{360.0, 120.0, 320.0};
  AdaptiveRobustServoParameters parameters;
  AdaptiveRobustServo servo(parameters);
  FeedDriveProcess plant(FeedDriveParameters{}, kPeriodS, gains[0], parameters.programmed_feed_mm_per_min);
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 10.0);
  double force = plant.force_n();
  SCOPED_TRACE("noise seed " + std::to_string(kSeed));
  for (std::size_t cut = 0; cut < gains.size(); ++cut) {
    plant.set_force_gain(gains[cut]);
    double worst_n = 0.0, feed_sum = 0.0;
    for (int k = 0; k < 100; ++k) {
      const double ratio = servo.step(force + noise(rng), kPeriodS);
      force = plant.step(ratio * parameters.programmed_feed_mm_per_min);
      if (k >= 50) {
        worst_n = std::max(worst_n, std::abs(force - parameters.reference_force_n));
        feed_sum += plant.actual_feed_mm_per_min();
      }
    }
    EXPECT_LT(worst_n, 50.0) << "cut " << cut;
    // The mean feed over the steady 5 s within 5 % of the one that gives 500 N: the force's mean error
    // is a few newtons (the noise averages out over 50 samples), 5 % of 500 N is 25 N.
    EXPECT_NEAR(feed_sum / 50.0, feeds[cut], 0.05 * feeds[cut]) << "cut " << cut;
    std::printf("robust servo, cut %zu: worst steady error %.1f N, mean feed %.1f mm/min (expected %.0f)\n", cut,
                worst_n, feed_sum / 50.0, feeds[cut]);
  }
  EXPECT_EQ(servo.failed_assignments(), 0);
}

}  // namespace
}  // namespace feedplan::control
