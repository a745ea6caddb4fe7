// learn_along_path on a hand-made plan and tooth periods. Oracles: the linear interpolation between
// peak places written out by hand, the look-ahead maximum, and — for the secant — a place whose true
// force is linear in t_m (F = α + β t_m) against a model of another shape, where the factor that makes
// the model right at the target is known in closed form.

#include <gtest/gtest.h>

#include <cmath>

#include "feedplan/learning/path_correction.hpp"

namespace feedplan::learning {
namespace {

// Plan samples at s = 0, 1, …, 10 mm, engaged from s = 2 on except `not_engaged`.
planner::PlanResult plan_on_a_line(int not_engaged = -1) {
  planner::PlanResult plan;
  for (int i = 0; i <= 10; ++i) {
    planner::PlannedSample s;
    s.s_mm = i;
    s.engaged = i >= 2 && i != not_engaged;
    plan.samples.push_back(s);
  }
  return plan;
}

// F̂ = 100 N everywhere.
model::ResponseSurfaceModel flat_model() {
  model::ResponseSurfaceModel model;
  model.beta = {100.0, 0, 0, 0, 0, 0};
  return model;
}

// F̂ = 100 + 2000 t_m, N (t_m in mm).
model::ResponseSurfaceModel linear_model() {
  model::ResponseSurfaceModel model;
  model.chip_center_mm = 0.05;
  model.chip_scale_mm = 0.05;
  model.beta = {200.0, 100.0, 0, 0, 0, 0};
  return model;
}

ToothPeriodPeak period(long window, double s_start_mm, double s_end_mm, double s_peak_mm, double force_n,
                       double chip_mm = 0.05) {
  ToothPeriodPeak p;
  p.window = window;
  p.s_start_mm = s_start_mm;
  p.s_end_mm = s_end_mm;
  p.s_peak_mm = s_peak_mm;
  p.sample.chip_mm = chip_mm;
  p.sample.contact_length_mm = 4.0;
  p.sample.force_n = force_n;
  return p;
}

// Four consecutive tooth periods of 2 mm with peaks at 3, 5, 7, 9 mm: ratios 1.2, 1.6, 1.6, 1.0 to F̂ = 100.
MeasuredRevolutions four_periods() {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 1.5, 3.5, 3.0, 120.0), period(1, 3.5, 5.5, 5.0, 160.0), period(2, 5.5, 7.5, 7.0, 160.0),
                       period(3, 7.5, 9.5, 9.0, 100.0)};
  return log;
}

TEST(LearnAlongPath, FirstStepInterpolatesTheRatioBetweenPeakPlaces) {
  const PathLearning step = learn_along_path(plan_on_a_line(6), flat_model(), {four_periods()}, 300.0, {});
  const auto& c = step.place_correction;
  ASSERT_EQ(c.size(), 11u);
  EXPECT_DOUBLE_EQ(c[0], 1.0);        // outside every period
  EXPECT_DOUBLE_EQ(c[1], 1.0);        // not engaged
  EXPECT_NEAR(c[2], 1.2, 1e-12);      // before the first peak: its value
  EXPECT_NEAR(c[3], 1.2, 1e-12);
  EXPECT_NEAR(c[4], 1.4, 1e-12);      // halfway between 1.2 and 1.6
  EXPECT_NEAR(c[5], 1.6, 1e-12);
  EXPECT_DOUBLE_EQ(c[6], 1.0);        // not engaged: untouched
  EXPECT_NEAR(c[8], 1.3, 1e-12);
  EXPECT_NEAR(c[9], 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(c[10], 1.0);       // past the last period's end (9.5)
  EXPECT_NEAR(step.measurement[4].force_n, 140.0, 1e-9);
  EXPECT_NEAR(step.measurement[4].window_mm, 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(step.measurement[10].force_n, 0.0);

  // What the planner gets: the largest c over the next window (2 mm) of path from each sample.
  const auto& ahead = step.correction;
  EXPECT_NEAR(ahead[2], 1.4, 1e-12);  // c at s = 2, 3, 4
  EXPECT_NEAR(ahead[3], 1.6, 1e-12);  // … 3, 4, 5
  EXPECT_NEAR(ahead[7], 1.6, 1e-12);
  EXPECT_NEAR(ahead[8], 1.3, 1e-12);  // c falls along the path: nothing larger ahead
  EXPECT_NEAR(ahead[9], 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(ahead[6], 1.0);    // not measured: no window
  EXPECT_DOUBLE_EQ(ahead[0], 1.0);
}

TEST(LearnAlongPath, RunoutFactorScalesEachToothPeriodToTheRevolutionPeak) {
  MeasuredRevolutions log = four_periods();
  log.tooth_periods[1].runout_factor = 1.25;  // two flutes: windows 1 and 3 are the flute that cuts less
  log.tooth_periods[3].runout_factor = 1.25;
  const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, {});
  EXPECT_NEAR(step.place_correction[3], 1.2, 1e-12);         // window 0
  EXPECT_NEAR(step.place_correction[5], 1.6 * 1.25, 1e-12);  // window 1
  EXPECT_NEAR(step.place_correction[9], 1.0 * 1.25, 1e-12);  // window 3
  EXPECT_NEAR(step.measurement[5].force_n, 200.0, 1e-9);
}

TEST(LearnAlongPath, SkippedToothPeriodsAreNotBridgedAndUncoveredSamplesKeepThePreviousCorrection) {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 1.5, 2.5, 2.0, 150.0), period(1, 2.5, 3.5, 3.0, 150.0), period(4, 6.5, 7.5, 7.0, 50.0),
                       period(5, 7.5, 8.5, 8.0, 50.0)};
  PathLearning previous;
  previous.correction.assign(11, 1.1);  // as read back from a plan report: a correction, no measurements
  const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, previous);
  EXPECT_NEAR(step.place_correction[2], std::sqrt(1.1 * 1.5), 1e-12);  // damped: c was measured before
  EXPECT_NEAR(step.place_correction[4], 1.1, 1e-12);  // windows 2 and 3 were skipped: nothing measured here
  EXPECT_NEAR(step.place_correction[5], 1.1, 1e-12);
  EXPECT_NEAR(step.place_correction[7], std::sqrt(1.1 * 0.5), 1e-12);
  EXPECT_NEAR(step.place_correction[10], 1.1, 1e-12);
}

// One tooth period over s = 4.5 … 5.5 mm (plan sample 5) at t_m = chip_mm with peak force_n.
MeasuredRevolutions at_sample_5(double chip_mm, double force_n) {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 4.5, 5.5, 5.0, force_n, chip_mm)};
  return log;
}

// The true force at sample 5: F = 50 + 6000 t_m; the model says 100 + 2000 t_m.
double true_force_n(double chip_mm) { return 50.0 + 6000.0 * chip_mm; }

TEST(LearnAlongPath, SecantThroughTwoFeedsMakesTheModelRightAtTheTarget) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.04, true_force_n(0.04))}, 400.0, {});
  EXPECT_NEAR(first.place_correction[5], 290.0 / 180.0, 1e-12);  // the ratio at the feed run
  const PathLearning second = learn_along_path(plan, model, {at_sample_5(0.07, true_force_n(0.07))}, 400.0, first);
  // The force reaches 400 N at t* = (400 − 50) / 6000; there c · F̂(t*) must be the true force.
  const double chip_at_target = 350.0 / 6000.0;
  const double c = second.place_correction[5];
  EXPECT_NEAR(c * (100.0 + 2000.0 * chip_at_target), 400.0, 1e-9);
  // The ratio measured at either feed would be wrong there.
  EXPECT_GT(std::abs(c - 470.0 / 240.0), 0.1);
  EXPECT_GT(std::abs(c - 290.0 / 180.0), 0.2);
}

TEST(LearnAlongPath, SecantTargetIsKeptNearTheMeasuredFeeds) {
  // F = 50 + 3000 t_m measured at 0.04 and 0.07 mm; 800 N would need t_m = 0.25 mm — beyond
  // kSecantReach × 0.07, so c is taken at t_m = 0.14 mm.
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.04, 170.0)}, 800.0, {});
  const PathLearning second = learn_along_path(plan, model, {at_sample_5(0.07, 260.0)}, 800.0, first);
  const double reach_mm = 0.07 * kSecantReach;
  EXPECT_NEAR(second.place_correction[5], (50.0 + 3000.0 * reach_mm) / (100.0 + 2000.0 * reach_mm), 1e-12);
}

TEST(LearnAlongPath, CloseFeedsOrAForceFallingWithTheFeedAreDampedInstead) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.04, 290.0)}, 400.0, {});
  const double c1 = 290.0 / 180.0;
  // t_m 9 % apart (< kMinSecantSpread): a slope from these would be mostly noise.
  const PathLearning close = learn_along_path(plan, model, {at_sample_5(0.044, true_force_n(0.044))}, 400.0, first);
  EXPECT_NEAR(close.place_correction[5], std::sqrt(c1 * true_force_n(0.044) / (100.0 + 2000.0 * 0.044)), 1e-12);
  // A faster feed measuring less force: no slope to trust.
  const PathLearning falling = learn_along_path(plan, model, {at_sample_5(0.07, 250.0)}, 400.0, first);
  EXPECT_NEAR(falling.place_correction[5], std::sqrt(c1 * 250.0 / 240.0), 1e-12);
}

TEST(LearnAlongPath, ClampedAndAveragedOverLogs) {
  const auto model = flat_model();
  const auto plan = plan_on_a_line();
  EXPECT_DOUBLE_EQ(learn_along_path(plan, model, {at_sample_5(0.05, 900.0)}, 300.0, {}).place_correction[5],
                   kMaxPathCorrection);
  EXPECT_DOUBLE_EQ(learn_along_path(plan, model, {at_sample_5(0.05, 10.0)}, 300.0, {}).place_correction[5],
                   kMinPathCorrection);
  const PathLearning two = learn_along_path(plan, model, {at_sample_5(0.05, 120.0), at_sample_5(0.05, 140.0)}, 300.0, {});
  EXPECT_NEAR(two.place_correction[5], 1.3, 1e-12);
}

}  // namespace
}  // namespace feedplan::learning
