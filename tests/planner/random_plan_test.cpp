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

namespace feedplan::planner {
namespace {

unsigned env_or(const char* name, unsigned fallback) {
  const char* text = std::getenv(name);
  return text && *text ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : fallback;
}

struct RandomCase {
  cycles::CycleSpec spec;
  PlanSettings settings;
  std::string description;
};

// A response-surface model that rises in t_m over [0, t_max] for every contact length up to
// `max_contact_mm` (a full turn of the tool circle, beyond the fitted L range too), as the physics does
// (redrawn until it does). A model falling somewhere would predict more force at a lower feed, and no
// feed schedule can hold a target then.
model::ResponseSurfaceModel random_model(std::mt19937_64& rng, double max_contact_mm) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (;;) {
    model::ResponseSurfaceModel model;
    model.chip_center_mm = 0.02 + 0.08 * u(rng);
    model.chip_scale_mm = 0.01 + 0.05 * u(rng);
    model.contact_length_center_mm = 1.0 + 6.0 * u(rng);
    model.contact_length_scale_mm = 0.5 + 3.0 * u(rng);
    model.beta = {100.0 + 400.0 * u(rng), 50.0 + 250.0 * u(rng), 100.0 * u(rng),
                  -10.0 + 20.0 * u(rng), -10.0 + 15.0 * u(rng),  -10.0 + 30.0 * u(rng)};
    model.range = {0.002 + 0.01 * u(rng), 0.1 + 0.2 * u(rng), 0.0, 4.0 + 12.0 * u(rng)};
    model.axial_depth_mm = 2.0 + 10.0 * u(rng);
    bool rising = true;
    for (int a = 0; a <= 20 && rising; ++a) {
      const double chip = model.range.chip_max_mm * a / 20.0;
      for (int b = 0; b <= 10 && rising; ++b) {
        const double length = max_contact_mm * b / 10.0;
        const double x1 = (chip - model.chip_center_mm) / model.chip_scale_mm;
        const double x2 = (length - model.contact_length_center_mm) / model.contact_length_scale_mm;
        rising = model.beta[1] + 2.0 * model.beta[3] * x1 + model.beta[5] * x2 > 0.0;
      }
    }
    if (rising) return model;
  }
}

RandomCase random_case(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 3);
  RandomCase c;
  cycles::CycleSpec& spec = c.spec;
  const double d = 4.0 + 16.0 * u(rng);
  spec.tool = {"random", d, 2 + static_cast<int>(4 * u(rng)), 30.0};
  spec.spindle_rpm = 1000.0 + 9000.0 * u(rng);
  spec.axial_depth_mm = 0.5 * d + d * u(rng);
  const double r = 0.5 * d;
  const cycles::Direction direction = u(rng) < 0.5 ? cycles::Direction::kCcw : cycles::Direction::kCw;
  std::ostringstream text;
  switch (pick(rng)) {
    case 0: {
      cycles::CornerSpec corner;
      corner.corner_radius_mm = r * (1.05 + 3.0 * u(rng));
      corner.radial_depth_mm = d * (0.05 + 0.5 * u(rng));
      corner.corner_angle_deg = 45.0 + 130.0 * u(rng);
      corner.entry_heading_deg = 360.0 * u(rng);
      corner.wall_length_mm = d * (0.5 + 2.0 * u(rng));
      corner.direction = direction;
      spec.cycle = "corner";
      spec.geometry = corner;
      text << "corner R " << corner.corner_radius_mm << " R_d " << corner.radial_depth_mm;
      break;
    }
    case 1: {
      cycles::TrochoidSpec trochoid;
      trochoid.pitch_mm = d * (0.02 + 0.2 * u(rng));
      trochoid.loop_radius_mm = std::max(trochoid.pitch_mm * 1.5, d * (0.3 + 1.2 * u(rng)));
      trochoid.start = {0.0, 0.0};
      trochoid.end = {trochoid.pitch_mm * (1 + static_cast<int>(3 * u(rng))), 0.0};
      trochoid.direction = direction;
      spec.cycle = "trochoid";
      spec.geometry = trochoid;
      text << "trochoid R_t " << trochoid.loop_radius_mm << " p " << trochoid.pitch_mm;
      break;
    }
    case 2: {
      cycles::SpiralSpec spiral;
      spiral.initial_radius_mm = r * (1.1 + 1.5 * u(rng));
      spiral.pitch_mm = d * (0.05 + 0.2 * u(rng));
      spiral.final_radius_mm = spiral.initial_radius_mm + spiral.pitch_mm * (1 + static_cast<int>(2 * u(rng)));
      spiral.direction = direction;
      spec.cycle = "spiral";
      spec.geometry = spiral;
      text << "spiral R " << spiral.initial_radius_mm << "→" << spiral.final_radius_mm;
      break;
    }
    default: {
      cycles::HelicalBoringSpec bore;
      bore.hole_diameter_mm = d * (1.1 + 0.85 * u(rng));
      bore.pitch_mm = d * (0.05 + 0.2 * u(rng));
      bore.depth_mm = bore.pitch_mm * (1.0 + 2.0 * u(rng));
      bore.direction = direction;
      spec.cycle = "helical_boring";
      spec.axial_depth_mm = 0.0;
      spec.geometry = bore;
      text << "helical boring D_h " << bore.hole_diameter_mm << " pitch " << bore.pitch_mm;
      break;
    }
  }
  geometry::MachineLimits& m = spec.machine;
  m.max_feed_mm_per_min = 2000.0 + 18000.0 * u(rng);
  m.min_feed_mm_per_min = 1.0 + 99.0 * u(rng);
  m.max_accel_mm_per_s2 = 200.0 + 9800.0 * u(rng);
  m.rapid_feed_mm_per_min = 10000.0 + 30000.0 * u(rng);
  m.block_time_min_s = 0.005 * u(rng);
  c.settings.model = random_model(rng, 3.14159265358979 * d);
  c.settings.target_force_n = c.settings.model.beta[0] * (0.9 + 1.1 * u(rng));
  c.settings.spindle_rpm = spec.spindle_rpm;
  c.settings.machine = m;
  const double resolutions[] = {0.1, 1.0, 5.0};
  c.settings.options.feed_resolution_mm_per_min = resolutions[static_cast<int>(3 * u(rng)) % 3];
  c.settings.options.merge_tolerance = 0.05 * u(rng);
  text << ", D " << d << ", target " << c.settings.target_force_n << " N, a " << m.max_accel_mm_per_s2;
  c.description = text.str();
  return c;
}

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
