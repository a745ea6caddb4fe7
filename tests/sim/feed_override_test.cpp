// The override channel against the closed-form responses of 14 e^(−0.08 s)/(s + 14) (docs/method.md §6.3):
// a step is 1 − e^(−14 (t − 0.08)) after the dead time and 0 before it; a staircase ramp is the sum
// of such steps.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "feedplan/sim/feed_override.hpp"

namespace feedplan::sim {
namespace {

constexpr double kTau = 1.0 / 14.0;
constexpr double kDead = 0.08;

// Unit step response of e^(−T_d s)/(τ s + 1), step applied at t = 0.
double unit_step_response(double t_s) {
  if (t_s <= kDead) return 0.0;
  return 1.0 - std::exp(-(t_s - kDead) / kTau);
}

bool has_field(const std::vector<InputProblem>& problems, const std::string& field) {
  for (const auto& p : problems) {
    if (p.field == field) return true;
  }
  return false;
}

void expect_step_response(double step_s, int steps) {
  FeedOverrideOptions options;
  options.initial_ratio = 0.0;
  FeedOverride channel(options, step_s);
  channel.command(1.0);
  double worst = 0.0;
  for (int k = 1; k <= steps; ++k) {
    const double actual = channel.step();
    const double t_s = k * step_s;
    EXPECT_NEAR(actual, unit_step_response(t_s), 1e-9) << "t = " << t_s << " s, step " << step_s << " s";
    if (t_s <= kDead) {
      EXPECT_EQ(actual, 0.0) << "moved before the dead time, t = " << t_s;
    }
    worst = std::max(worst, std::abs(actual - unit_step_response(t_s)));
  }
  std::cout << "step " << step_s << " s: worst deviation from the closed form " << worst << "\n";
}

TEST(FeedOverride, StepResponseMatchesClosedFormWhenDeadTimeIsWholeSteps) { expect_step_response(0.001, 1000); }

TEST(FeedOverride, StepResponseMatchesClosedFormWhenDeadTimeIsFractionalSteps) {
  expect_step_response(0.003, 400);  // T_d = 26 steps + 2 ms
  expect_step_response(0.0125, 80);  // T_d = 6 steps + 5 ms
  expect_step_response(0.2, 10);     // step longer than the dead time
}

TEST(FeedOverride, StepDownFromDefaultFullOverride) {
  FeedOverride channel({}, 0.002);
  EXPECT_EQ(channel.actual(), 1.0);
  channel.command(0.5);
  for (int k = 1; k <= 500; ++k) {
    const double actual = channel.step();
    EXPECT_NEAR(actual, 1.0 - 0.5 * unit_step_response(k * 0.002), 1e-9) << "step " << k;
  }
  EXPECT_NEAR(channel.time_s(), 1.0, 1e-12);
}

TEST(FeedOverride, StaircaseRampIsTheSumOfStepResponses) {
  const double step_s = 0.004;  // T_d = 20 steps
  const double rate_per_s = 0.9;
  FeedOverrideOptions options;
  options.initial_ratio = 0.0;
  FeedOverride channel(options, step_s);
  std::vector<double> commands;
  for (int k = 0; k < 300; ++k) {
    commands.push_back(std::min(1.5, rate_per_s * k * step_s));
    channel.command(commands.back());
    const double actual = channel.step();
    const double t_s = (k + 1) * step_s;
    double expected = 0.0;  // superposition of the command increments, each a delayed step
    for (int i = 0; i <= k; ++i) {
      const double increment = commands[i] - (i > 0 ? commands[i - 1] : 0.0);
      expected += increment * unit_step_response(t_s - i * step_s);
    }
    EXPECT_NEAR(actual, expected, 1e-9) << "t = " << t_s;
    // The continuous ramp response r (t − T_d − τ(1 − e^(−(t−T_d)/τ))) lies within one step's worth.
    if (t_s > kDead && t_s < 1.5 / rate_per_s) {
      const double lag_s = t_s - kDead;
      const double continuous = rate_per_s * (lag_s - kTau * (1.0 - std::exp(-lag_s / kTau)));
      EXPECT_NEAR(actual, continuous, rate_per_s * step_s) << "t = " << t_s;
    }
  }
}

TEST(FeedOverride, CommandsAreClampedToTheOverrideRange) {
  FeedOverride channel({}, 0.001);
  channel.command(2.0);
  EXPECT_EQ(channel.commanded(), 1.5);
  for (int k = 0; k < 3000; ++k) channel.step();
  EXPECT_NEAR(channel.actual(), 1.5, 1e-9);
  channel.command(-0.3);
  EXPECT_EQ(channel.commanded(), 0.0);
  for (int k = 0; k < 3000; ++k) channel.step();
  EXPECT_NEAR(channel.actual(), 0.0, 1e-9);
}

TEST(FeedOverride, PureDeadTimeDelaysTheCommandByWholeSteps) {
  FeedOverrideOptions options;
  options.time_constant_s = 0.0;
  options.dead_time_s = 0.01;
  FeedOverride channel(options, 0.0025);  // 4 steps
  const std::vector<double> commands = {0.2, 0.7, 1.1, 0.4, 0.9, 1.3, 0.0, 0.5, 0.6, 0.8};
  for (std::size_t k = 0; k < commands.size(); ++k) {
    channel.command(commands[k]);
    const double actual = channel.step();
    // y((k+1)Δt) is the command held just before (k + 1 − 4)Δt, i.e. u_{k−4}, or the initial 1.0.
    const double expected = k >= 4 ? commands[k - 4] : 1.0;
    EXPECT_DOUBLE_EQ(actual, expected) << "step " << k;
  }
}

TEST(FeedOverride, ValidateNamesEveryBadField) {
  EXPECT_TRUE(validate(FeedOverrideOptions{}, 0.001).empty());
  FeedOverrideOptions bad;
  bad.time_constant_s = -1.0;
  bad.dead_time_s = std::nan("");
  bad.max_ratio = 0.0;
  const auto problems = validate(bad, -0.001);
  EXPECT_TRUE(has_field(problems, "feed_override.time_constant_s"));
  EXPECT_TRUE(has_field(problems, "feed_override.dead_time_s"));
  EXPECT_TRUE(has_field(problems, "feed_override.max_ratio"));
  EXPECT_TRUE(has_field(problems, "feed_override.step_s"));
  EXPECT_EQ(problems.size(), 4u);

  FeedOverrideOptions high_initial;
  high_initial.initial_ratio = 1.6;
  const auto initial_problems = validate(high_initial, 0.001);
  ASSERT_EQ(initial_problems.size(), 1u);
  EXPECT_EQ(initial_problems[0].field, "feed_override.initial_ratio");
  EXPECT_NE(initial_problems[0].message.find("1.6"), std::string::npos);

  EXPECT_TRUE(has_field(validate(FeedOverrideOptions{}, 1e-12), "feed_override.step_s"));  // delay line too long
  EXPECT_THROW(FeedOverride(bad, 0.001), InputError);
}

}  // namespace
}  // namespace feedplan::sim
