// path_correction on a hand-made plan and revolutions: the ratio measured / model lands on the plan
// samples of the revolution's span — whole the first time, then as the geometric mean with the previous
// correction — clamped.

#include <gtest/gtest.h>

#include <cmath>

#include "feedplan/learning/path_correction.hpp"

namespace feedplan::learning {
namespace {

TEST(PathCorrection, RatioOnTheRevolutionsSpanDampedAndClamped) {
  planner::PlanResult plan;
  for (int i = 0; i <= 10; ++i) {
    planner::PlannedSample s;
    s.s_mm = i;
    s.engaged = i >= 2;
    plan.samples.push_back(s);
  }
  model_db::ResponseSurfaceModel model;  // F̂ = 100 N everywhere
  model.beta = {100.0, 0, 0, 0, 0, 0};
  MeasuredRevolutions log;
  log.revolutions = {{1.5, 4.5, 0.0}, {4.5, 7.5, 0.0}, {7.5, 10.0, 0.0}};
  log.samples = {{0.05, 4.0, 144.0, 1.0, 3.0}, {0.05, 4.0, 100.0, 1.0, 6.0}, {0.05, 4.0, 900.0, 1.0, 9.0}};
  const std::vector<double> first = path_correction(plan, model, {log}, {});
  EXPECT_DOUBLE_EQ(first[0], 1.0);  // not engaged: unchanged
  EXPECT_DOUBLE_EQ(first[1], 1.0);
  EXPECT_NEAR(first[2], 1.44, 1e-12);  // the first measurement: the ratio itself
  EXPECT_NEAR(first[4], 1.44, 1e-12);
  EXPECT_NEAR(first[5], 1.0, 1e-12);
  EXPECT_NEAR(first[9], kMaxPathCorrection, 1e-12);  // 9 clamped to 2
  // A second cycle measuring ratio 1.21 there: √(1.44 · 1.21) = 1.32.
  log.samples[0].force_n = 121.0;
  const std::vector<double> second = path_correction(plan, model, {log}, first);
  EXPECT_NEAR(second[3], 1.32, 1e-12);
  EXPECT_NEAR(second[6], 1.0, 1e-12);
}

}  // namespace
}  // namespace feedplan::learning
