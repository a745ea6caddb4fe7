// Cutting tests grouped by engagement (model_db/engagement_groups.hpp): one group per cut mode and radial depth,
// numbered in order of first appearance, radial depths within 1 µm counting as one.

#include <gtest/gtest.h>

#include <vector>

#include "feedplan/model_db/engagement_groups.hpp"

namespace feedplan::model_db {
namespace {

CuttingTestRecord test_at(CutMode mode, double radial_depth_mm) {
  CuttingTestRecord t;
  t.conditions.mode = mode;
  t.conditions.radial_depth_mm = radial_depth_mm;
  return t;
}

TEST(EngagementGroups, OnePerModeAndRadialDepth) {
  const std::vector<CuttingTestRecord> tests = {
      test_at(CutMode::kDown, 1.0), test_at(CutMode::kDown, 2.0), test_at(CutMode::kDown, 1.0000004),
      test_at(CutMode::kUp, 1.0),   test_at(CutMode::kDown, 2.0), test_at(CutMode::kSlot, 10.0)};
  std::vector<const CuttingTestRecord*> pointers;
  for (const auto& t : tests) pointers.push_back(&t);
  const EngagementGroups groups = engagement_groups(pointers);
  EXPECT_EQ(groups.count, 4);
  EXPECT_EQ(groups.group, (std::vector<int>{0, 1, 0, 2, 1, 3}));
  EXPECT_EQ(engagement_groups({}).count, 0);
}

}  // namespace
}  // namespace feedplan::model_db
