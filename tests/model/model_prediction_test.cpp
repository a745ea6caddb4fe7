// Evaluating the response-surface model (seed 003 Eq. 1): hand-computed forces, the fitted-range flags
// with their tolerance, and validate()'s problems.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "feedplan/model/model_prediction.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::model {
namespace {

using ::testing::HasSubstr;

//! c1 = 0.05, s1 = 0.05 mm; c2 = 5, s2 = 5 mm; range t_m 0.02–0.12 mm, L 2–8 mm.
ResponseSurfaceModel hand_model() {
  ResponseSurfaceModel model;
  model.beta = {100.0, 20.0, 10.0, 5.0, -3.0, 2.0};
  model.chip_center_mm = 0.05;
  model.chip_scale_mm = 0.05;
  model.contact_length_center_mm = 5.0;
  model.contact_length_scale_mm = 5.0;
  model.range = {0.02, 0.12, 2.0, 8.0};
  return model;
}

TEST(ModelPrediction, HandComputedForce) {
  const ResponseSurfaceModel model = hand_model();
  // t_m = 0.1 → X1 = 1; L = 2.5 → X2 = −0.5:
  // 100 + 20·1 + 10·(−0.5) + 5·1 − 3·0.25 + 2·(−0.5) = 118.25
  EXPECT_NEAR(predict(model, 0.1, 2.5).force_n, 118.25, 1e-12);
  // At the centres every X is 0: β0.
  EXPECT_NEAR(predict(model, 0.05, 5.0).force_n, 100.0, 1e-12);
  // t_m = 0.02 → X1 = −0.6; L = 8 → X2 = 0.6:
  // 100 − 12 + 6 + 5·0.36 − 3·0.36 + 2·(−0.36) = 94.0
  EXPECT_NEAR(predict(model, 0.02, 8.0).force_n, 94.0, 1e-12);
}

TEST(ModelPrediction, RegressorsInBetaOrder) {
  const auto psi = regressors(hand_model(), 0.1, 2.5);  // X1 = 1, X2 = −0.5
  EXPECT_DOUBLE_EQ(psi[kBeta0], 1.0);
  EXPECT_DOUBLE_EQ(psi[kBeta1], 1.0);
  EXPECT_DOUBLE_EQ(psi[kBeta2], -0.5);
  EXPECT_DOUBLE_EQ(psi[kBeta11], 1.0);
  EXPECT_DOUBLE_EQ(psi[kBeta22], 0.25);
  EXPECT_DOUBLE_EQ(psi[kBeta12], -0.5);
}

TEST(ModelPrediction, RangeFlagsWithTinyRelativeTolerance) {
  const ResponseSurfaceModel model = hand_model();
  auto p = predict(model, 0.07, 5.0);
  EXPECT_FALSE(p.chip_outside);
  EXPECT_FALSE(p.contact_length_outside);
  // Exactly at the edges, and 1e-12 relative beyond them (below the 1e-9 tolerance): inside.
  p = predict(model, 0.12 * (1 + 1e-12), 2.0 * (1 - 1e-12));
  EXPECT_FALSE(p.chip_outside);
  EXPECT_FALSE(p.contact_length_outside);
  p = predict(model, 0.02, 8.0);
  EXPECT_FALSE(p.chip_outside);
  EXPECT_FALSE(p.contact_length_outside);
  // 1e-6 relative beyond: outside, each flag on its own.
  p = predict(model, 0.12 * (1 + 1e-6), 5.0);
  EXPECT_TRUE(p.chip_outside);
  EXPECT_FALSE(p.contact_length_outside);
  p = predict(model, 0.05, 2.0 * (1 - 1e-6));
  EXPECT_FALSE(p.chip_outside);
  EXPECT_TRUE(p.contact_length_outside);
  p = predict(model, 0.019, 9.0);
  EXPECT_TRUE(p.chip_outside);
  EXPECT_TRUE(p.contact_length_outside);
  // The force is still the polynomial outside (an extrapolation): t_m = 0 → X1 = −1, L = 5 → X2 = 0.
  EXPECT_NEAR(predict(model, 0.0, 5.0).force_n, 100.0 - 20.0 + 5.0, 1e-12);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  p = predict(model, nan, 5.0);
  EXPECT_TRUE(std::isnan(p.force_n));
  EXPECT_TRUE(p.chip_outside);
}

TEST(ModelValidate, UsableModelHasNoProblems) {
  EXPECT_TRUE(validate(hand_model()).empty());
}

TEST(ModelValidate, NamesEveryBadField) {
  ResponseSurfaceModel model = hand_model();
  model.beta[3] = std::numeric_limits<double>::quiet_NaN();
  model.beta[5] = std::numeric_limits<double>::infinity();
  model.chip_scale_mm = 0.0;
  model.contact_length_scale_mm = -1.0;
  model.chip_center_mm = std::numeric_limits<double>::infinity();
  model.range.contact_length_min_mm = 9.0;  // above the max 8
  model.quantity = "mean_force_n";
  const auto problems = validate(model);
  std::vector<std::string> fields;
  for (const auto& p : problems) fields.push_back(p.field);
  EXPECT_THAT(fields, ::testing::UnorderedElementsAre("model.beta[3]", "model.beta[5]", "model.chip_scale_mm",
                                                      "model.contact_length_scale_mm", "model.chip_center_mm",
                                                      "model.range.contact_length_min_mm", "model.quantity"));
  const auto message_of = [&](const std::string& field) {
    for (const auto& p : problems) {
      if (p.field == field) return p.message;
    }
    return std::string("(none)");
  };
  EXPECT_EQ(message_of("model.beta[3]"), "= nan: must be finite");
  EXPECT_EQ(message_of("model.chip_scale_mm"), "= 0: must be finite and > 0");
  EXPECT_EQ(message_of("model.range.contact_length_min_mm"), "= 9: must be ≤ model.range.contact_length_max_mm = 8");
  EXPECT_THAT(message_of("model.quantity"), HasSubstr("peak_xy_force_per_revolution_n"));
}

TEST(ModelValidate, RangeMustBeFiniteAndNonNegative) {
  ResponseSurfaceModel model = hand_model();
  model.range.chip_max_mm = std::numeric_limits<double>::infinity();
  model.range.chip_min_mm = -0.01;
  const auto problems = validate(model);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].field, "model.range.chip_min_mm");
  EXPECT_EQ(problems[1].field, "model.range.chip_max_mm");
}

}  // namespace
}  // namespace feedplan::model
