// prediction_errors against hand-computed errors of a constant model.

#include <gtest/gtest.h>

#include <cmath>

#include "feedplan/learning/prediction_errors.hpp"

namespace feedplan::learning {
namespace {

TEST(PredictionErrors, HandComputedPercentiles) {
  model::ResponseSurfaceModel model;  // F̂ = 100 N everywhere
  model.beta = {100.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  std::vector<LearningSample> samples;
  for (double force : {100.0, 125.0, 80.0, 50.0, 0.0}) samples.push_back({0.05, 4.0, force, 1.0, 0.0});
  const PredictionErrors e = prediction_errors(model, samples);
  ASSERT_EQ(e.n, 4);  // the zero force is skipped
  // errors: 0 %, −20 %, +25 %, +100 %
  EXPECT_DOUBLE_EQ(e.max_abs_percent, 100.0);
  EXPECT_DOUBLE_EQ(e.median_abs_percent, 20.0);
  EXPECT_DOUBLE_EQ(e.p90_abs_percent, 100.0);
  EXPECT_DOUBLE_EQ(e.mean_percent, (0.0 - 20.0 + 25.0 + 100.0) / 4.0);
  EXPECT_NEAR(e.rms_n, std::sqrt((0.0 + 625.0 + 400.0 + 2500.0) / 4.0), 1e-12);
}

}  // namespace
}  // namespace feedplan::learning
