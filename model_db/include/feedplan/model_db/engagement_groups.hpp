#pragma once
// Cutting tests grouped by engagement — cut mode and radial depth — for cross-validating a model kind on
// engagements it was not fitted on (docs/method.md §5.7). A cycle cuts at engagements the straight tests never
// had, so what decides between the kinds is how a model fitted on some engagements predicts another, not how it
// interpolates between neighbouring points of one grid (leave-one-out).

#include <vector>

#include "feedplan/model_db/cutting_test.hpp"

namespace feedplan::model_db {

//! Fewest engagements for which the leave-one-engagement-out error is computed: with two, each fit would
//! see a single engagement.
inline constexpr int kMinCrossValidationEngagements = 3;

//! The tests' groups.
struct EngagementGroups {
  int count = 0;           //!< distinct engagements
  std::vector<int> group;  //!< per test, its engagement in 0 … count − 1 (in order of first appearance)
};

//! The engagement of each of `tests` (radial depths equal within 1 µm count as one).
EngagementGroups engagement_groups(const std::vector<const CuttingTestRecord*>& tests);

}  // namespace feedplan::model_db
