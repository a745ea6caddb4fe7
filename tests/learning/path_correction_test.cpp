// learn_along_path on a hand-made plan and tooth periods. Oracles: the linear interpolation between
// peak places written out by hand, the look-ahead maximum, and — for the secant — a place whose true
// force is linear in t_m (F = α + β t_m) against a model of another shape, where the factor that makes
// the model right at the target is known in closed form.

#include <gtest/gtest.h>

#include <algorithm>
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

// F̂ straight in t_m: `at_center_n` at t_m = `center_mm`, rising by `per_center_n` per `center_mm` of t_m (the
// model's chip scale is its center), whatever L.
model::ResponseSurfaceModel line_in_chip_model(double center_mm, double at_center_n, double per_center_n) {
  model::ResponseSurfaceModel model;
  model.chip_center_mm = center_mm;
  model.chip_scale_mm = center_mm;
  model.beta = {at_center_n, per_center_n, 0, 0, 0, 0};
  return model;
}

// F̂ = 100 + 2000 t_m, N (t_m in mm).
model::ResponseSurfaceModel linear_model() { return line_in_chip_model(0.05, 200.0, 100.0); }

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

// `log` with each tooth period's contact length 30 % over the one before: more apart than
// kReadingSmoothingLengthSpread, so every reading stands alone (no averaging with its neighbours).
MeasuredRevolutions each_alone(MeasuredRevolutions log) {
  double length_mm = 2.0;
  for (ToothPeriodPeak& p : log.tooth_periods) {
    p.sample.contact_length_mm = length_mm;
    length_mm *= 1.3;
  }
  return log;
}

// Four consecutive tooth periods of 2 mm with peaks at 3, 5, 7, 9 mm: ratios 1.2, 1.6, 1.6, 1.0 to F̂ = 100.
MeasuredRevolutions four_periods() {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 1.5, 3.5, 3.0, 120.0), period(1, 3.5, 5.5, 5.0, 160.0), period(2, 5.5, 7.5, 7.0, 160.0),
                       period(3, 7.5, 9.5, 9.0, 100.0)};
  return each_alone(log);
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
  log.tooth_periods[1].runout_factor = 1.02;  // two flutes: windows 1 and 3 are the flute that cuts less
  log.tooth_periods[3].runout_factor = 1.02;
  const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, {});
  EXPECT_NEAR(step.place_correction[3], 1.2, 1e-12);         // window 0
  EXPECT_NEAR(step.place_correction[5], 1.6 * 1.02, 1e-12);  // window 1
  EXPECT_NEAR(step.place_correction[9], 1.0 * 1.02, 1e-12);  // window 3
  EXPECT_NEAR(step.measurement[5].force_n, 160.0 * 1.02, 1e-9);
}

TEST(LearnAlongPath, ToothPeriodsOfAFluteThatCutsMuchLessThanTheLargestAreNotLearnedFrom) {
  MeasuredRevolutions log = four_periods();
  log.tooth_periods[1].runout_factor = 1.25;  // beyond kMaxRunoutFactor: windows 1 and 3 are left out
  log.tooth_periods[3].runout_factor = 1.25;
  const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, {});
  EXPECT_NEAR(step.place_correction[3], 1.2, 1e-12);  // window 0
  EXPECT_NEAR(step.place_correction[5], 1.4, 1e-12);  // between the kept peaks at 3 and 7 (windows 0 and 2)
  EXPECT_NEAR(step.place_correction[7], 1.6, 1e-12);
  EXPECT_NEAR(step.place_correction[9], 1.6, 1e-12);  // past the last kept peak: its value
}

// With the flute count known (a log from measured_revolutions), a place is never taken for less than a
// period the runout filter left out within half a turn of it — at an entry the factor that picks the
// dominant tooth comes from steady turns elsewhere, and the period left out may be the dominant one.
// Z = 4: two periods either side.
TEST(LearnAlongPath, APlaceIsNeverTakenForLessThanAPeriodLeftOutWithinHalfATurn) {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 1.5, 3.5, 3.0, 120.0), period(1, 3.5, 5.5, 5.0, 160.0), period(2, 5.5, 7.5, 7.0, 120.0),
                       period(3, 7.5, 9.5, 9.0, 100.0), period(4, 9.5, 11.5, 11.0, 100.0), period(5, 11.5, 13.5, 13.0, 100.0)};
  log.tooth_periods[1].runout_factor = 1.25;  // left out itself, as a flute that cuts less
  log = each_alone(log);
  const PathLearning alone = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, {});
  log.flutes = 4;
  const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, {});
  EXPECT_NEAR(alone.measurement[5].force_n, 120.0, 1e-9);  // between the kept peaks of windows 0 and 2
  for (const std::size_t i : {3u, 5u, 7u, 9u}) {
    EXPECT_NEAR(step.measurement[i].force_n, 160.0, 1e-9) << "sample " << i;  // windows 0, 2, 3 reach window 1
  }
  // Window 4 is three periods from window 1: its own peak (the kept window 2 does not raise it); halfway
  // between 160 N at 9 mm and 100 N at 11 mm.
  EXPECT_NEAR(step.measurement[10].force_n, 130.0, 1e-9);
}

// Tooth periods of 0.25 mm from s = 1.5 mm to 10 mm (peaks at their middles), at a constant chip and
// contact length, whose readings are F̂ = 100 N plus noise alternating ±6 N (+ at the plan's samples), from
// a log whose noise per row was measured at `noise_n` out of the cut.
MeasuredRevolutions steady_run_with_noise(double noise_n = 4.0) {
  MeasuredRevolutions log;
  log.noise.sigma_n = noise_n;
  for (long k = 0; k < 34; ++k) {
    const double s_mm = 1.5 + 0.25 * static_cast<double>(k);
    log.tooth_periods.push_back(period(k, s_mm - 0.125, s_mm + 0.125, s_mm, 100.0 + (k % 2 == 0 ? 6.0 : -6.0)));
  }
  return log;
}

// Single readings are averaged over kReadingSmoothingHalfWidth tooth periods either side by a local
// straight line: alternating noise of ±a comes out at ∓a / 7 in the middle of a steady run (three either
// side: the reading's own sign three times, the other four times) — moved by no more than
// kReadingSmoothingNoiseSigmas × the noise per row, and not at all from a log without noise.
TEST(LearnAlongPath, SingleReadingsOnASteadyStretchAreAveragedOverTheirNeighbours) {
  ASSERT_EQ(kReadingSmoothingHalfWidth, 3);
  ASSERT_EQ(kReadingSmoothingNoiseSigmas, 2.0);
  const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {steady_run_with_noise(4.0)}, 300.0, {});
  const PathLearning bounded = learn_along_path(plan_on_a_line(), flat_model(), {steady_run_with_noise(2.0)}, 300.0, {});
  const PathLearning quiet = learn_along_path(plan_on_a_line(), flat_model(), {steady_run_with_noise(0.0)}, 300.0, {});
  for (std::size_t i = 3; i <= 8; ++i) {
    EXPECT_NEAR(step.measurement[i].force_n, 100.0 - 6.0 / 7.0, 1e-9) << "sample " << i;  // read: 106 N
    EXPECT_NEAR(bounded.measurement[i].force_n, 106.0 - 2.0 * 2.0, 1e-9) << "sample " << i;
    EXPECT_NEAR(quiet.measurement[i].force_n, 106.0, 1e-9) << "sample " << i;
  }
}

// Where the engagement or the feed changes (a loop's entry or exit), readings are averaged only with
// those whose contact length and chip are within kReadingSmoothingLengthSpread of their own: a step in the
// force where L or t_m steps by 30 % is kept as measured, on both sides of it.
TEST(LearnAlongPath, ReadingsAreNotAveragedAcrossAChangeOfTheEngagementOrTheChip) {
  for (const bool chip_steps : {false, true}) {
    SCOPED_TRACE(chip_steps ? "t_m steps" : "L steps");
    MeasuredRevolutions log = steady_run_with_noise(30.0);  // the bound on the move out of the way
    for (ToothPeriodPeak& p : log.tooth_periods) {
      const bool after = p.s_peak_mm > 6.0;  // peaks from 6.25 mm on
      p.sample.force_n = after ? 150.0 : 100.0;
      if (after && chip_steps) p.sample.chip_mm *= 1.3;
      if (after && !chip_steps) p.sample.contact_length_mm *= 1.3;
    }
    const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, {});
    for (std::size_t i = 2; i <= 6; ++i) EXPECT_NEAR(step.measurement[i].force_n, 100.0, 1e-9) << "sample " << i;
    for (std::size_t i = 7; i <= 9; ++i) EXPECT_NEAR(step.measurement[i].force_n, 150.0, 1e-9) << "sample " << i;
  }
}

TEST(LearnAlongPath, SkippedToothPeriodsAreNotBridgedAndUncoveredSamplesKeepThePreviousCorrection) {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 1.5, 2.5, 2.0, 150.0), period(1, 2.5, 3.5, 3.0, 150.0), period(4, 6.5, 7.5, 7.0, 50.0),
                       period(5, 7.5, 8.5, 8.0, 50.0)};
  PathLearning previous;
  previous.correction.assign(11, 1.1);  // as read back from a plan report: a correction, no measurements
  const PathLearning step = learn_along_path(plan_on_a_line(), flat_model(), {log}, 300.0, previous);
  EXPECT_NEAR(step.place_correction[2], 1.5, 1e-12);  // the model's shape scaled to the measurement
  EXPECT_NEAR(step.place_correction[4], 1.1, 1e-12);  // windows 2 and 3 were skipped: nothing measured here
  EXPECT_NEAR(step.place_correction[5], 1.1, 1e-12);
  EXPECT_NEAR(step.place_correction[7], 0.5, 1e-12);
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

TEST(LearnAlongPath, SecantInTheLogOfTheChipBetweenAFeedUnderAndOneOverTheTargetLandsJustUnderIt) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.04, true_force_n(0.04))}, 400.0, {});
  EXPECT_NEAR(first.place_correction[5], 290.0 / 180.0, 1e-12);  // the ratio at the feed run
  const PathLearning second = learn_along_path(plan, model, {at_sample_5(0.07, true_force_n(0.07))}, 400.0, first);
  // 290 N at 0.04 mm, 470 N at 0.07 mm: F = 290 + β ln(t / 0.04) meets 400 N at t* = 0.04 · 1.75^(110/180).
  const double chip_mm = 0.04 * std::pow(1.75, 110.0 / 180.0);
  EXPECT_NEAR(second.place_correction[5] * (100.0 + 2000.0 * chip_mm), 400.0, 1e-9);
  // The true force there (linear in t_m, so convex in ln t_m): under the target, by less than 4 %.
  EXPECT_LT(true_force_n(chip_mm), 400.0);
  EXPECT_GT(true_force_n(chip_mm), 0.96 * 400.0);
}

// Beyond two readings (both over the target) the power law through them is the nearer of the two secants
// to a force convex in ln t_m that still stays on its side: true force F = 50 + 6000 t_m read at 0.07 mm
// (470 N) and 0.055 mm (380 N) — the next chip's true force is at or over the 330 N target, closer to it
// than the line in ln t_m would have run it.
TEST(LearnAlongPath, BeyondTwoReadingsOverTheTargetThePowerLawStepsNearerThanTheLineAndNotPastTheTarget) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.07, true_force_n(0.07))}, 330.0, {});
  const PathLearning second = learn_along_path(plan, model, {at_sample_5(0.055, true_force_n(0.055))}, 330.0, first);
  const double steered_mm = (330.0 / second.place_correction[5] - 100.0) / 2000.0;  // c · F̂(t) = target
  const double power_law_mm = 0.055 * std::pow(330.0 / 380.0, std::log(0.055 / 0.07) / std::log(380.0 / 470.0));
  const double line_mm = 0.055 * std::exp((330.0 - 380.0) * std::log(0.055 / 0.07) / (380.0 - 470.0));
  EXPECT_NEAR(steered_mm, power_law_mm, 1e-9);
  EXPECT_GE(true_force_n(steered_mm), 330.0);
  EXPECT_LT(true_force_n(steered_mm) - 330.0, true_force_n(line_mm) - 330.0);
}

TEST(LearnAlongPath, SecantTargetIsKeptNearTheMeasuredFeeds) {
  // F = 50 + 3000 t_m measured at 0.04 and 0.07 mm, both under the target; 700 N would need t_m = 0.217 mm —
  // beyond kSecantReach × 0.07, so the next plan is steered to t_m = 0.14 mm: c · F̂(0.14) = 700.
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.04, 170.0)}, 700.0, {});
  const PathLearning second = learn_along_path(plan, model, {at_sample_5(0.07, 260.0)}, 700.0, first);
  const double reach_mm = 0.07 * kSecantReach;
  EXPECT_NEAR(second.place_correction[5] * (100.0 + 2000.0 * reach_mm), 700.0, 1e-9);
}

TEST(LearnAlongPath, CloseFeedsOrAForceFallingWithTheFeedScaleTheModelInstead) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.04, 290.0)}, 400.0, {});
  const double c1 = 290.0 / 180.0;
  // t_m 9 % apart (< kMinSecantSpread): a slope from these would be mostly noise.
  const PathLearning close = learn_along_path(plan, model, {at_sample_5(0.044, true_force_n(0.044))}, 400.0, first);
  EXPECT_GT(first.place_correction[5], 0.0);
  EXPECT_NEAR(c1, first.place_correction[5], 1e-12);
  EXPECT_NEAR(close.place_correction[5], true_force_n(0.044) / (100.0 + 2000.0 * 0.044), 1e-12);
  // A faster feed measuring less force: no slope to trust. The ratio 250 / 240 would run t_m = 0.142 mm, past
  // kSecantReach × 0.07 mm: the step stops there, c · F̂(0.14) = 400 — faster, as the place is under the target.
  const PathLearning falling = learn_along_path(plan, model, {at_sample_5(0.07, 250.0)}, 400.0, first);
  EXPECT_NEAR(falling.place_correction[5] * (100.0 + 2000.0 * 0.07 * kSecantReach), 400.0, 1e-9);
}

// Two readings over the target at chips 20 % apart: a secant through them is trusted only when their forces
// differ by more than the noise could make them (kMinSecantForceChange of the target, kSecantNoiseSigmas × the
// log's noise per row). 470 N at t_m 0.05 mm, then 440 N at 0.04 mm: both over the target, the power law
// through them, F = 440 (t / 0.04)^q with q = ln(440 / 470) / ln 0.8, meets 400 N at
// t_m = 0.04 · (400 / 440)^(1 / q) mm, in closed form.
TEST(LearnAlongPath, ASecantIsTrustedOnlyOnAForceChangeTheNoiseCannotMake) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.05, 470.0)}, 400.0, {});
  const double secant_chip_mm = 0.04 * std::pow(400.0 / 440.0, std::log(0.8) / std::log(440.0 / 470.0));
  for (const double noise_n : {0.0, 5.0, 12.0}) {
    SCOPED_TRACE(noise_n);
    MeasuredRevolutions log = at_sample_5(0.04, 440.0);
    log.noise.sigma_n = noise_n;
    const PathLearning second = learn_along_path(plan, model, {log}, 400.0, first);
    if (30.0 >= std::max(kMinSecantForceChange * 400.0, kSecantNoiseSigmas * noise_n)) {
      EXPECT_NEAR(second.place_correction[5], 400.0 / (100.0 + 2000.0 * secant_chip_mm), 1e-9);
    } else {
      EXPECT_NEAR(second.place_correction[5], 440.0 / (100.0 + 2000.0 * 0.04), 1e-12);  // the model's shape scaled
    }
  }
  // 4 N apart with no noise measured: under 2 % of the target, the model's shape scaled.
  const PathLearning close = learn_along_path(plan, model, {at_sample_5(0.04, 466.0)}, 400.0, first);
  EXPECT_NEAR(close.place_correction[5], 466.0 / 180.0, 1e-12);
}

// A secant far flatter than the model's shape (470 N at t_m 0.05 mm, 455 N at 0.04 mm: it would run t_m
// 0.018 mm) asks the model for no more than (F / target)^kSecantTrust of the c that runs the chip measured.
TEST(LearnAlongPath, AFlatSecantStepsNoFurtherThanItsTrustRegion) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.05, 470.0)}, 400.0, {});
  const PathLearning second = learn_along_path(plan, model, {at_sample_5(0.04, 455.0)}, 400.0, first);
  const double at_now = 400.0 / (100.0 + 2000.0 * 0.04);
  const double secant_chip_mm = 0.04 * std::exp((400.0 - 455.0) / ((455.0 - 470.0) / std::log(0.8)));
  ASSERT_GT(400.0 / (100.0 + 2000.0 * secant_chip_mm), at_now * std::pow(455.0 / 400.0, kSecantTrust));  // it binds
  EXPECT_NEAR(second.place_correction[5], at_now * std::pow(455.0 / 400.0, kSecantTrust), 1e-9);
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

// The t_m the planner runs at sample 5 with correction c under linear_model: c · (100 + 2000 t_m) = target.
double chip_run_mm(double c, double target_force_n) { return (target_force_n / c - 100.0) / 2000.0; }

// A place whose true force has another shape than the model: a size effect and an edge force,
// F = 40 + 3950 t_m^0.8 (N, t_m in mm). Each step cuts at the t_m the previous c makes the planner run.
double concave_force_n(double chip_mm) { return 40.0 + 3950.0 * std::pow(chip_mm, 0.8); }

TEST(LearnAlongPath, ConvergesOnAForceOfAnotherShapeAndNeverSlowsAPlaceMeasuredUnderTheTarget) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const double target_n = 400.0;
  const double chip_at_target_mm = std::pow((target_n - 40.0) / 3950.0, 1.0 / 0.8);  // the root, closed form
  double chip_mm = 0.08;  // cycle 1: the model's own plan runs thicker than the root (about +40 % force)
  PathLearning state;
  std::vector<double> errors;
  for (int cycle = 1; cycle <= 4; ++cycle) {
    const double force_n = concave_force_n(chip_mm);
    errors.push_back(std::abs(force_n - target_n) / target_n);
    state = learn_along_path(plan, model, {at_sample_5(chip_mm, force_n)}, target_n, state);
    const double next_mm = chip_run_mm(state.place_correction[5], target_n);
    if (force_n <= target_n) {
      EXPECT_GE(next_mm, chip_mm - 1e-12) << "cycle " << cycle;  // never slowed
    } else {
      EXPECT_LT(next_mm, chip_mm) << "cycle " << cycle;
    }
    chip_mm = next_mm;
  }
  EXPECT_GT(errors[0], 0.3);
  EXPECT_LT(errors[2], 0.03);  // cycle 3
  EXPECT_LT(errors[3], 0.01);  // cycle 4
  EXPECT_NEAR(chip_mm, chip_at_target_mm, 0.02 * chip_at_target_mm);
}

TEST(LearnAlongPath, AimsAtAChipSoAGlobalRefitBetweenPartsDoesNotMoveTheNextFeed) {
  const auto plan = plan_on_a_line();
  const PathLearning first = learn_along_path(plan, linear_model(), {at_sample_5(0.04, true_force_n(0.04))}, 400.0, {});
  const PathLearning second = learn_along_path(plan, linear_model(), {at_sample_5(0.07, true_force_n(0.07))}, 400.0, first);
  model::ResponseSurfaceModel refitted = linear_model();  // the same step against a model refitted 30 % higher
  for (double& b : refitted.beta) b *= 1.3;
  const PathLearning moved = learn_along_path(plan, refitted, {at_sample_5(0.07, true_force_n(0.07))}, 400.0, first);
  EXPECT_NEAR(moved.place_correction[5] * 1.3, second.place_correction[5], 1e-12);  // the same t_m is run
}

// F̂ = 175 + 500 t_m, N: nearly flat at t_m 0.01 mm (d ln F̂ / d ln t_m = 0.03), as a response surface
// extrapolates below its thinnest straight cut.
model::ResponseSurfaceModel flat_in_chip_model() { return line_in_chip_model(0.01, 180.0, 5.0); }

// Near the force floor the model extrapolates nearly flat: F̂ = 175 + 500 t_m (d ln F̂ / d ln t_m = 0.03 at
// 0.01 mm). A place read 178 N at t_m 0.010 mm under a 190 N target: the model's shape scaled would run the
// chip to the reach (kSecantReach × 0.010 mm). The force's shape is not known, only that it is concave with
// F(0) ≥ 0; of those, the one rising fastest past the reading is F = 178 · t / 0.010 (no edge force), which
// is 356 N at the reach. The next chip is the one at which that force meets the target: 0.010 · 190 / 178 mm.
TEST(LearnAlongPath, WhereTheModelIsFlatAPlaceUnderTheTargetSpeedsUpNoFurtherThanAProportionalForceAllows) {
  const auto flat_in_chip = flat_in_chip_model();
  const auto plan = plan_on_a_line();
  const PathLearning step = learn_along_path(plan, flat_in_chip, {at_sample_5(0.010, 178.0)}, 190.0, {});
  const double next_chip_mm = (190.0 / step.place_correction[5] - 175.0) / 500.0;  // c · F̂(t_m) = target
  EXPECT_NEAR(next_chip_mm, 0.010 * 190.0 / 178.0, 1e-12);
  EXPECT_LE(178.0 * next_chip_mm / 0.010, 190.0 + 1e-9);  // the fastest-rising concave force: at the target
  // Where the model rises as a cutting force does (linear_model: exponent 0.8 at 0.04 mm), its shape is kept.
  const PathLearning steep = learn_along_path(plan, linear_model(), {at_sample_5(0.04, 290.0)}, 400.0, {});
  EXPECT_NEAR(steep.place_correction[5], 290.0 / 180.0, 1e-12);
}

// 198 N at t_m 0.010 mm against 180 N: the model's shape would slow the chip to its slowing reach (1/8); the
// first step slows it only as far as a force rising with kMinFirstSlowingExponent needs,
// t_m = 0.010 · (180 / 198)^(1 / 0.25) mm. A second reading over the target that differs from the first by
// less than the noise could make it says the force is flat there: the model's shape, within its reach.
TEST(LearnAlongPath, AFirstStepFromOverTheTargetSlowsNoFurtherThanAForceOfTheSmallestTrustedRise) {
  const auto model = flat_in_chip_model();
  const auto plan = plan_on_a_line();
  const auto chip_run_mm = [](double c) { return (180.0 / c - 175.0) / 500.0; };  // c · F̂(t_m) = target
  const PathLearning first = learn_along_path(plan, model, {at_sample_5(0.010, 198.0)}, 180.0, {});
  const double first_chip_mm = 0.010 * std::pow(180.0 / 198.0, 1.0 / kMinFirstSlowingExponent);
  EXPECT_NEAR(chip_run_mm(first.place_correction[5]), first_chip_mm, 1e-12);
  EXPECT_GT(first_chip_mm, 0.010 / kSlowingReach);  // the bound binds
  const PathLearning second = learn_along_path(plan, model, {at_sample_5(first_chip_mm, 197.0)}, 180.0, first);
  EXPECT_NEAR(chip_run_mm(second.place_correction[5]), first_chip_mm / kSlowingReach, 1e-12);
  // Where the model rises as a cutting force does (linear_model: exponent 0.8 at 0.04 mm), the first step
  // is the model's shape scaled.
  const PathLearning steep = learn_along_path(plan, linear_model(), {at_sample_5(0.04, 470.0)}, 400.0, {});
  EXPECT_NEAR(steep.place_correction[5], 470.0 / 180.0, 1e-12);
}

TEST(LearnAlongPath, WithinTheHoldBandThePlaceKeepsItsChip) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  const double force_n = 400.0 * (1.0 + 0.5 * kHoldBand);
  const PathLearning step = learn_along_path(plan, model, {at_sample_5(0.05, force_n)}, 400.0, {});
  EXPECT_NEAR(chip_run_mm(step.place_correction[5], 400.0), 0.05, 1e-12);
}

TEST(LearnAlongPath, BracketKeepsTheNearestEndsAndDropsOneTheLatestMeasurementContradicts) {
  const auto model = linear_model();
  const auto plan = plan_on_a_line();
  PathLearning state = learn_along_path(plan, model, {at_sample_5(0.04, 250.0)}, 300.0, {});
  state = learn_along_path(plan, model, {at_sample_5(0.08, 350.0)}, 300.0, state);
  EXPECT_DOUBLE_EQ(state.bracket[5].below_chip_mm, 0.04);
  EXPECT_DOUBLE_EQ(state.bracket[5].above_chip_mm, 0.08);
  EXPECT_FALSE(state.bracket[4].has_below());  // sample 4 is outside the period
  // The secant in ln t_m between the ends: t* = 0.04 · 2^(1/2) mm.
  EXPECT_NEAR(chip_run_mm(state.place_correction[5], 300.0), 0.04 * std::sqrt(2.0), 1e-12);
  // Over the target at 0.035 mm, thinner than the lower end: that end is contradicted and dropped.
  state = learn_along_path(plan, model, {at_sample_5(0.035, 320.0)}, 300.0, state);
  EXPECT_FALSE(state.bracket[5].has_below());
  EXPECT_DOUBLE_EQ(state.bracket[5].above_chip_mm, 0.035);
  EXPECT_LT(chip_run_mm(state.place_correction[5], 300.0), 0.035);
}

// A place sped up runs a longer tooth period next time, by as much as its chip grows (the period's length on the
// path is the feed per tooth): its look-ahead reaches that much further. Sample 5 read 290 N at t_m 0.04 mm in a
// period 0.7 mm long (the next chip: c · F̂ = 400 N with c = 290 / 180); sample 6, a separate run, 600 N. Within
// 0.7 mm of sample 5 lies no sample; within the longer period of the next plan lies sample 6, whose c would slow
// 5 — but not below the chip 5 was measured to bear (0.04 mm: c = 400 / 180).
TEST(LearnAlongPath, APlaceSpedUpLooksAheadAsFarAsItsNextToothPeriod) {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 4.8, 5.5, 5.0, 290.0, 0.04), period(2, 5.5, 6.5, 6.0, 600.0, 0.04)};
  const PathLearning step = learn_along_path(plan_on_a_line(), linear_model(), {log}, 400.0, {});
  const double next_chip_mm = chip_run_mm(290.0 / 180.0, 400.0);
  ASSERT_GE(5.0 + 0.7 * next_chip_mm / 0.04, 6.0);  // the next period reaches sample 6
  EXPECT_NEAR(step.place_correction[5], 290.0 / 180.0, 1e-12);
  EXPECT_NEAR(step.measurement[5].window_mm, 0.7 * next_chip_mm / 0.04, 1e-6);
  EXPECT_NEAR(step.correction[5], 400.0 / 180.0, 1e-12);
}

TEST(LearnAlongPath, LookAheadDoesNotSlowAPlaceBelowTheChipItWasMeasuredUnderTheTargetAt) {
  // Sample 4 under the target at t_m 0.05 (300 N), sample 5 over it: the look-ahead would give 4 the c of 5.
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 3.5, 4.5, 4.0, 300.0, 0.05), period(1, 4.5, 5.5, 5.0, 600.0, 0.05)};
  const PathLearning step = learn_along_path(plan_on_a_line(), linear_model(), {log}, 400.0, {});
  EXPECT_GT(step.place_correction[5], step.place_correction[4]);
  EXPECT_GE(chip_run_mm(step.correction[4], 400.0), 0.05 - 1e-12);
  EXPECT_NEAR(step.correction[5], step.place_correction[5], 1e-12);
}

// The look-ahead carries the feed per tooth ahead as well as the c: a tooth period spans both places at one
// feed per tooth, while L — and with it F̂ and c — changes under it. Model F̂ = 100 + 2000 t_m; sample 4
// (chip factor t_m / f_z = 1) read 500 N at t_m 0.05 mm, so it is steered to c = 2.5, t_m 0.03 mm, f_z 0.03 mm;
// sample 5 read 450 N at t_m 0.025 mm: c = 450 / 150, steered to 100 + 2000 t_m = 400 / c, t_m = 0.0167 mm.
// At an exit (sample 5's chip factor 0.3: f_z 0.056 mm, faster than sample 4's) sample 4 keeps its own c;
// at an entry (chip factor 0.6: f_z 0.0278 mm) it runs that feed per tooth, a c below sample 5's.
TEST(LearnAlongPath, LookAheadSlowsAPlaceToTheFeedPerToothAheadNotToTheCorrectionAhead) {
  MeasuredRevolutions log;
  log.tooth_periods = {period(0, 3.5, 4.5, 4.0, 500.0, 0.05), period(1, 4.5, 5.5, 5.0, 450.0, 0.025)};
  const double c5 = 450.0 / 150.0;
  const double chip5_mm = (400.0 / c5 - 100.0) / 2000.0;
  for (const double chip_factor_5 : {0.3, 0.6}) {
    SCOPED_TRACE(chip_factor_5);
    planner::PlanResult plan = plan_on_a_line();
    plan.samples[4].chip_factor = 1.0;
    plan.samples[5].chip_factor = chip_factor_5;
    const PathLearning step = learn_along_path(plan, linear_model(), {log}, 400.0, {});
    ASSERT_NEAR(step.place_correction[4], 2.5, 1e-12);
    ASSERT_NEAR(step.place_correction[5], c5, 1e-12);
    const double feed_per_tooth_5_mm = chip5_mm / chip_factor_5;
    if (feed_per_tooth_5_mm > 0.03) {
      EXPECT_NEAR(step.correction[4], 2.5, 1e-12);  // c-max would have given it c5
    } else {
      EXPECT_NEAR(step.correction[4], 400.0 / (100.0 + 2000.0 * feed_per_tooth_5_mm * 1.0), 1e-6);
      EXPECT_LT(step.correction[4], c5);
    }
  }
}

}  // namespace
}  // namespace feedplan::learning
