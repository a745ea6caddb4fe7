// Seeded random property test of the planner over many random cycles, models and machines (STYLE.md
// kind 2): every block F inside the machine's feed range and on the resolution grid; every change of F
// between neighbouring blocks feasible inside the faster block at the acceleration limit (the
// controller behaviour documented in feed_plan.hpp); and the force the model predicts at the speed the
// virtual machine's own motion planner (sim::plan_motion, independent of the planner's controller
// model) runs never above the target in the default mode, wherever the target is reachable (the model
// evaluated at max(L, L_min), the rule of feed_limit.hpp).
//
// Reproduce a run with FEEDPLAN_TEST_SEED and FEEDPLAN_TEST_COUNT (printed at the start).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>
#include <sstream>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/sim/motion_profile.hpp"
#include "random_cases.hpp"

namespace feedplan::planner {
namespace {

using testing::env_or;
using testing::random_case;
using testing::RandomCase;

TEST(RandomPlans, FeedsAccelerationsAndForcesWithinLimits) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 20261123u);
  const unsigned count = env_or("FEEDPLAN_TEST_COUNT", 2000u);
  std::cout << "random plans: FEEDPLAN_TEST_SEED=" << seed << " FEEDPLAN_TEST_COUNT=" << count << "\n";
  std::mt19937_64 rng(seed);
  long long blocks_checked = 0;
  long long steps_checked = 0;
  long long samples_checked = 0;
  int not_met = 0;
  int unsafe = 0;
  int failures = 0;
  for (unsigned n = 0; n < count && failures < 5; ++n) {
    const RandomCase c = random_case(rng);
    cycles::Cycle cycle;
    try {
      cycle = cycles::generate(c.spec);
    } catch (const InputError&) {
      continue;  // a random combination the generator refuses (validated elsewhere)
    }
    const PlanGeometry geometry = analyse(cycle.path, cycle.stock, c.spec.tool, 0.02 * c.spec.tool.diameter_mm);
    const PlanResult result = plan(geometry, c.settings);
    const geometry::MachineLimits& m = c.settings.machine;
    const double resolution = c.settings.options.feed_resolution_mm_per_min;
    const std::string where = "case " + std::to_string(n) + ": " + c.description;

    // 1. F inside the machine's range, on the resolution grid (or the minimum feed).
    for (const PlannedBlock& block : result.blocks) {
      if (geometry.path.moves[static_cast<std::size_t>(block.move_index)].kind == geometry::MoveKind::kRapid) continue;
      ++blocks_checked;
      const double f = block.feed_mm_per_min;
      const double on_grid = std::abs(f / resolution - std::round(f / resolution));
      if (!(f >= m.min_feed_mm_per_min && f <= m.max_feed_mm_per_min && (on_grid < 1e-6 || f == m.min_feed_mm_per_min))) {
        ADD_FAILURE() << where << ": block F " << f << " outside [" << m.min_feed_mm_per_min << ", "
                      << m.max_feed_mm_per_min << "] or off the " << resolution << " grid";
        ++failures;
      }
    }
    // 2. Changes of F between neighbouring feed blocks fit inside the faster one.
    for (std::size_t k = 0; k + 1 < result.blocks.size(); ++k) {
      const PlannedBlock& a = result.blocks[k];
      const PlannedBlock& b = result.blocks[k + 1];
      if (a.feed_mm_per_min <= 0.0 || b.feed_mm_per_min <= 0.0) continue;
      ++steps_checked;
      const double va = a.feed_mm_per_min / 60.0;
      const double vb = b.feed_mm_per_min / 60.0;
      const double faster_length = va > vb ? a.length_mm : b.length_mm;
      const double needed = std::abs(vb * vb - va * va) / (2.0 * faster_length);
      if (needed > result.summary.accel_used_mm_per_s2 * (1.0 + 1e-9) + 1e-9) {
        ADD_FAILURE() << where << ": blocks " << k << "→" << k + 1 << " F " << a.feed_mm_per_min << "→"
                      << b.feed_mm_per_min << " need " << needed << " mm/s² > " << m.max_accel_mm_per_s2;
        ++failures;
      }
    }
    // 3. The force at the virtual machine's speeds: never above the target; where the target is not
    // reachable (status kTargetNotMet), above it only where the planner says the minimum feed binds.
    // (A plan the safety check refuses is also reported unsafe, which outranks target not met: the
    // summary's count says whether the minimum feed binds somewhere.)
    const bool reachable = result.summary.over_target_samples == 0;
    unsafe += result.status == PlanStatus::kUnsafe ? 1 : 0;
    not_met += reachable ? 0 : 1;
    geometry::MachineLimits limits = sim::kVirtualMachineLimits;
    limits.max_accel_mm_per_s2 = m.max_accel_mm_per_s2;
    limits.rapid_feed_mm_per_min = m.rapid_feed_mm_per_min;
    limits.max_feed_mm_per_min = m.max_feed_mm_per_min;
    limits.junction_deviation_mm = 0.0;
    const sim::MotionProfile motion = sim::plan_motion(result.program, limits);
    const auto& model = c.settings.model;
    for (std::size_t i = 0; i < geometry.engagement.samples.size(); ++i) {
      const auto& sample = geometry.engagement.samples[i];
      if (!sample.cutting || sample.engagement_rad <= 0.0) continue;
      if (!reachable && result.samples[i].limit_reason == FeedLimitReason::kMinFeed) continue;
      ++samples_checked;
      const double feed = motion.speed_cap_at(sample.s_mm) * 60.0;
      const double chip = sample.chip_factor * sample.xy_speed_ratio * feed / (c.spec.tool.flutes * c.spec.spindle_rpm);
      double force = model::predict(model, chip, std::max(sample.contact_length_mm, model.range.contact_length_min_mm)).force_n;
      if (model.axial_depth_mm > 0.0 && sample.axial_depth_mm > 0.0) force *= sample.axial_depth_mm / model.axial_depth_mm;
      if (force > c.settings.target_force_n * (1.0 + 1e-6)) {
        ADD_FAILURE() << where << ": at s = " << sample.s_mm << " the machine runs " << feed << " mm/min and the model predicts "
                      << force << " N > target " << c.settings.target_force_n << " N (planner: limit "
                      << result.samples[i].feed_limit_mm_per_min << " " << to_string(result.samples[i].limit_reason)
                      << ", block F " << result.samples[i].block_feed_mm_per_min << ", runs "
                      << result.samples[i].feed_mm_per_min << ", predicts " << result.samples[i].predicted_force_n
                      << " N, status " << to_string(result.status) << ")"
                      << ::testing::PrintToString(result.messages);
        ++failures;
        break;
      }
    }
  }
  std::cout << "checked " << blocks_checked << " blocks, " << steps_checked << " block changes, " << samples_checked
            << " engaged samples; " << not_met << " cases with the target not reachable everywhere; " << unsafe
            << " plans refused by the safety check\n";
  EXPECT_GT(samples_checked, 10LL * count);
}

}  // namespace
}  // namespace feedplan::planner
