// compare_peaks on a hand-made plan: which revolutions count as in cut, held and steady, and the
// error statistics computed by hand.

#include <gtest/gtest.h>

#include <cmath>

#include "feedplan/planner/peak_comparison.hpp"

namespace feedplan::planner {
namespace {

// Samples every 1 mm over 0..30 mm: air up to 10, then force-limited at 40° inside the model's range up
// to 20, then limited by the machine's maximum feed at a rising engagement up to 30; the machine runs at
// every limit.
PlanResult hand_made_plan() {
  PlanResult result;
  for (int i = 0; i <= 30; ++i) {
    PlannedSample s;
    s.s_mm = i;
    s.engaged = i >= 10;
    s.engagement_rad = i < 10 ? 0.0 : i <= 20 ? 0.7 : 0.7 + 0.05 * (i - 20);
    s.limit_reason = i < 10 ? FeedLimitReason::kAirFeed : i <= 20 ? FeedLimitReason::kForce : FeedLimitReason::kMaxFeed;
    s.within_model_range = s.engaged;
    s.predicted_force_n = s.engaged ? 100.0 : 0.0;
    s.feed_limit_mm_per_min = 500.0;
    s.feed_mm_per_min = 500.0;
    result.samples.push_back(s);
  }
  return result;
}

TEST(PeakComparison, ClassifiesRevolutionsAndComputesErrors) {
  const PlanResult plan = hand_made_plan();
  const std::vector<MeasuredRevolution> revolutions = {
      {1.0, 4.0, 0.0},     // air
      {11.0, 14.0, 103.0}, // steady, +3 %
      {15.0, 18.0, 96.0},  // steady, −4 %
      {22.0, 26.0, 120.0}, // in cut, max feed binds: not held, +20 % overshoot
  };
  const PeakComparison c = compare_peaks(plan, 100.0, revolutions);
  EXPECT_EQ(c.in_cut, 3);
  EXPECT_EQ(c.held, 2);
  EXPECT_EQ(c.steady, 2);
  EXPECT_FALSE(c.revolutions[0].in_cut);
  EXPECT_TRUE(c.revolutions[1].steady);
  EXPECT_FALSE(c.revolutions[3].held);
  EXPECT_NEAR(c.max_abs_error_percent, 4.0, 1e-12);
  EXPECT_EQ(c.worst_held, 2);
  EXPECT_NEAR(c.rms_error_percent, std::sqrt((9.0 + 16.0) / 2.0), 1e-12);
  EXPECT_NEAR(c.max_overshoot_percent, 20.0, 1e-12);
  EXPECT_EQ(c.worst_overshoot, 3);
  EXPECT_NE(describe(c, 100.0).find("+20.00 %"), std::string::npos);
}

// The largest peak leads the description wherever it is — here in air for the plan (the plan has no
// engagement there, the machine cut): 250 N, +150 %, at s = 2.5 mm, placed at the plan's sample 2 or 3.
TEST(PeakComparison, TheLargestPeakAnywhereLeadsTheDescription) {
  PlanResult plan = hand_made_plan();
  for (auto& s : plan.samples) s.position = {s.s_mm, -1.0, -4.0};
  const PeakComparison c = compare_peaks(plan, 100.0, {{1.0, 4.0, 250.0}, {22.0, 26.0, 120.0}});
  EXPECT_EQ(c.largest_peak, 0);
  EXPECT_EQ(c.worst_overshoot, 1);
  const std::string text = describe(c, 100.0);
  EXPECT_EQ(text.rfind("largest per-revolution peak: 250.0 N at s = 2.5 mm, x 3.00 y -1.00 z -4.00 (+150.0 % vs the "
                       "target 100 N; outside the plan's cut",
                       0),
            0u)
      << text;
}

TEST(PeakComparison, ARevolutionAcrossAChangingEngagementIsHeldButNotSteady) {
  PlanResult plan = hand_made_plan();
  for (auto& s : plan.samples) {
    if (s.s_mm > 20) s.limit_reason = FeedLimitReason::kForce;
  }
  const PeakComparison c = compare_peaks(plan, 100.0, {{22.0, 26.0, 110.0}});
  EXPECT_EQ(c.held, 1);
  EXPECT_EQ(c.steady, 0);
  EXPECT_EQ(c.worst_steady, -1);
}

// Where the axes cannot bring the speed up to the force limit in time, the plan itself predicts less than
// the target: the revolution is in cut, its overshoot counts, but it is neither force-limited nor held. One
// that reaches the limit at one sample (within the F words' merge tolerance: a block's F at the smallest
// limit it spans) is force-limited — a faster plan would run it faster — but held only when every engaged
// sample runs at its limit: otherwise its peak depends on where the teeth pass.
TEST(PeakComparison, ARevolutionTheMachineRunsBelowItsForceLimitIsNotHeld) {
  PlanResult plan = hand_made_plan();
  for (auto& s : plan.samples) {
    if (s.s_mm >= 11 && s.s_mm <= 14) s.feed_mm_per_min = 0.95 * s.feed_limit_mm_per_min;  // accelerating
    if (s.s_mm >= 15 && s.s_mm <= 17) s.feed_mm_per_min = (s.s_mm == 16 ? 0.98 : 0.9) * s.feed_limit_mm_per_min;
    if (s.s_mm >= 18 && s.s_mm <= 20) s.feed_mm_per_min = (s.s_mm == 19 ? 0.98 : 0.976) * s.feed_limit_mm_per_min;
  }
  const PeakComparison c =
      compare_peaks(plan, 100.0, {{11.0, 14.0, 93.0}, {15.0, 17.0, 95.0}, {18.0, 20.0, 99.0}});
  EXPECT_EQ(c.in_cut, 3);
  EXPECT_FALSE(c.revolutions[0].force_limited);
  EXPECT_FALSE(c.revolutions[0].held);
  EXPECT_TRUE(c.revolutions[1].force_limited) << "one sample at 98 % of its limit: within the merge tolerance";
  EXPECT_FALSE(c.revolutions[1].held) << "two at 90 %";
  EXPECT_TRUE(c.revolutions[2].force_limited);
  EXPECT_TRUE(c.revolutions[2].held) << "every sample within 2.5 % of its limit";
  EXPECT_EQ(c.held, 1);
  EXPECT_NEAR(c.max_abs_error_percent, 1.0, 1e-12);
  EXPECT_NEAR(c.max_overshoot_percent, -1.0, 1e-12);
}

}  // namespace
}  // namespace feedplan::planner
