#include "feedplan/model_db/engagement_groups.hpp"

#include <cmath>

namespace feedplan::model_db {
namespace {

constexpr double kSameRadialDepthMm = 1e-3;

}  // namespace

EngagementGroups engagement_groups(const std::vector<const CuttingTestRecord*>& tests) {
  EngagementGroups groups;
  std::vector<const CuttingTestConditions*> firsts;
  for (const CuttingTestRecord* test : tests) {
    int found = -1;
    for (int g = 0; g < groups.count && found < 0; ++g) {
      if (firsts[g]->mode == test->conditions.mode &&
          std::abs(firsts[g]->radial_depth_mm - test->conditions.radial_depth_mm) <= kSameRadialDepthMm) {
        found = g;
      }
    }
    if (found < 0) {
      found = groups.count++;
      firsts.push_back(&test->conditions);
    }
    groups.group.push_back(found);
  }
  return groups;
}

}  // namespace feedplan::model_db
