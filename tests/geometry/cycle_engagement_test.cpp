// Oracle tests of the engagement on the generated cycles: trochoid (seed 003 Table 2 and loop radii
// 10 and 15 mm), spiral (Table 3) and the pocket, against the brute-force oracle of
// brute_force_oracle.hpp, which the library's kernels do not share.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <map>
#include <string>

#include "brute_force_oracle.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/geometry/analytic_engagement.hpp"
#include "feedplan/geometry/engagement.hpp"

namespace feedplan::geometry {
namespace {

const double kOracleToleranceRad = deg_to_rad(0.2);

struct Profiled {
  cycles::Cycle cycle;
  EngagementProfile profile;
  std::vector<double> move_start_s;
};

Profiled profile_spec(const std::string& yaml, double ds_mm = 0.05) {
  const auto spec = cycles::read_cycle_spec(yaml, "test");
  Profiled p{cycles::generate(spec), {}, {}};
  p.profile = compute_engagement(p.cycle.path, p.cycle.stock, spec.tool.radius_mm(), {.ds_mm = ds_mm});
  double s = 0;
  for (const auto& m : p.cycle.path.moves) {
    p.move_start_s.push_back(s);
    s += length_mm(m);
  }
  return p;
}

double fraction_of(const Profiled& p, const EngagementSample& s) {
  const double len = length_mm(p.cycle.path.moves[s.move_index]);
  return len > 0 ? std::clamp((s.s_mm - p.move_start_s[s.move_index]) / len, 0.0, 1.0) : 0.0;
}

std::string trochoid_yaml(double loop_radius_mm) {
  return "cycle: trochoid\n"
         "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30, name: D10}\n"
         "axial_depth_mm: 10\n"
         "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: " +
         std::to_string(loop_radius_mm) + ", pitch_mm: 1, direction: ccw}\n";
}

class TrochoidEngagement : public ::testing::TestWithParam<double> {};

// Per-loop maximum engagement against the oracle, and no engagement over the back of each loop.
TEST_P(TrochoidEngagement, LoopMaximaMatchOracleAndBackIsFree) {
  const double loop_radius = GetParam();
  const Profiled p = profile_spec(trochoid_yaml(loop_radius));
  oracle::EngagementOracle truth(p.cycle.path, p.cycle.stock, 5.0);

  // Group the cutting samples on the loop circles by their circle (move).
  std::map<int, std::vector<std::size_t>> loops;
  for (std::size_t i = 0; i < p.profile.samples.size(); ++i) {
    const auto& s = p.profile.samples[i];
    const Move& m = p.cycle.path.moves[s.move_index];
    if (s.cutting && m.kind == MoveKind::kArc && m.sweep_rad > 6.28) loops[s.move_index].push_back(i);
  }
  ASSERT_EQ(loops.size(), 10u);
  int loop_number = 0;
  for (const auto& [move_index, indices] : loops) {
    ++loop_number;
    const Move& circle = p.cycle.path.moves[move_index];
    std::size_t argmax = indices.front();
    for (auto i : indices) {
      if (p.profile.samples[i].engagement_rad > p.profile.samples[argmax].engagement_rad) argmax = i;
    }
    // Oracle maximum: every 10th sample of the loop and every sample near the profile's maximum.
    double oracle_max = 0;
    for (std::size_t k = 0; k < indices.size(); ++k) {
      const std::size_t i = indices[k];
      const bool near_max = i + 12 >= argmax && i <= argmax + 12;
      if (k % 10 != 0 && !near_max) continue;
      const auto& s = p.profile.samples[i];
      oracle_max = std::max(oracle_max, truth.engagement_rad(s.move_index, fraction_of(p, s), 7200));
    }
    const double profile_max = p.profile.samples[argmax].engagement_rad;
    EXPECT_NEAR(profile_max, oracle_max, kOracleToleranceRad)
        << "loop radius " << loop_radius << ", loop " << loop_number;
    std::printf("trochoid R_t %4.1f mm loop %2d: max engagement %.3f deg, oracle %.3f deg\n", loop_radius, loop_number,
                rad_to_deg(profile_max), rad_to_deg(oracle_max));
    if (loop_number > 1) {
      // Steady loops cut one pitch into the previous loop's wall: the internal-arc closed form with
      // the wall radius R_t + r and R_d = p bounds the maximum from below (docs/method.md §5.2).
      EXPECT_GE(profile_max + 1e-6, internal_arc_engagement_rad(5.0, loop_radius + 5.0, 1.0));
    }
    // Back of the loop: angle about the loop centre between 100° and 260° from the slot direction.
    for (auto i : indices) {
      const auto& s = p.profile.samples[i];
      double angle = rad_to_deg(std::atan2(s.position.y_mm - circle.center.y_mm, s.position.x_mm - circle.center.x_mm));
      if (angle < 0) angle += 360;
      if (angle < 100 || angle > 260) continue;
      ASSERT_EQ(s.engagement_rad, 0.0) << "loop " << loop_number << " at " << angle << " deg";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(LoopRadii, TrochoidEngagement, ::testing::Values(5.0, 10.0, 15.0));

// Spiral (seed 003 Table 3): every turn against the oracle; the first turn rises from the
// pre-drilled bore.
TEST(SpiralEngagement, TurnsMatchOracleAndFirstTurnRisesFromTheBore) {
  const Profiled p = profile_spec(
      "cycle: spiral\n"
      "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30, name: D10}\n"
      "axial_depth_mm: 10\n"
      "spiral: {center: [0, 0], initial_radius_mm: 8, final_radius_mm: 16, pitch_mm: 1, direction: ccw}\n");
  oracle::EngagementOracle truth(p.cycle.path, p.cycle.stock, 5.0);
  std::map<int, std::vector<std::size_t>> parts;
  for (std::size_t i = 0; i < p.profile.samples.size(); ++i) {
    if (p.profile.samples[i].cutting) parts[p.profile.samples[i].part].push_back(i);
  }
  ASSERT_GE(parts.size(), 8u);  // 8 turns and the finishing circle
  double worst = 0;
  for (const auto& [part, indices] : parts) {
    double part_worst = 0, part_max = 0, oracle_part_max = 0;
    for (std::size_t k = 0; k < indices.size(); k += 15) {
      const auto& s = p.profile.samples[indices[k]];
      const double expected = truth.engagement_rad(s.move_index, fraction_of(p, s));
      worst = std::max(worst, std::abs(s.engagement_rad - expected));
      part_worst = std::max(part_worst, std::abs(s.engagement_rad - expected));
      part_max = std::max(part_max, s.engagement_rad);
      oracle_part_max = std::max(oracle_part_max, expected);
      ASSERT_NEAR(s.engagement_rad, expected, kOracleToleranceRad)
          << "part " << p.cycle.path.part_names[part] << " s " << s.s_mm;
    }
    std::printf("spiral %-18s: %3zu oracle points, max engagement %.3f deg (oracle %.3f), worst deviation %.4f deg\n",
                p.cycle.path.part_names[part].c_str(), (indices.size() + 14) / 15, rad_to_deg(part_max),
                rad_to_deg(oracle_part_max), rad_to_deg(part_worst));
  }
  RecordProperty("worst_deviation_deg", std::to_string(rad_to_deg(worst)));
  // First turn: starts at the bore wall with (almost) no engagement and ends near the steady value.
  const auto& first = parts.begin()->second;
  const double start_engagement = p.profile.samples[first.front()].engagement_rad;
  const double end_engagement = p.profile.samples[first.back()].engagement_rad;
  EXPECT_LT(start_engagement, deg_to_rad(5));
  EXPECT_GT(end_engagement, deg_to_rad(30));
  double running_max = 0;
  int rises = 0;
  for (auto i : first) {
    if (p.profile.samples[i].engagement_rad > running_max + deg_to_rad(1)) {
      running_max = p.profile.samples[i].engagement_rad;
      ++rises;
    }
  }
  EXPECT_GT(rises, 10) << "the first turn should show a gradual transition from the bore";
}

// Pocket: no sample is engaged where an earlier cycle already removed material.
TEST(PocketEngagement, NothingEngagedWhereEarlierCyclesCut) {
  const Profiled p = profile_spec(
      "cycle: pocket\n"
      "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30, name: D10}\n"
      "pocket: {center: [0, 0], width_mm: 60, height_mm: 40, depth_mm: 10, corner_radius_mm: 8}\n",
      0.1);
  oracle::EngagementOracle truth(p.cycle.path, p.cycle.stock, 5.0);
  const double r = 5.0;
  std::size_t checked_points = 0;
  for (std::size_t i = 0; i < p.profile.samples.size(); i += 3) {
    const auto& s = p.profile.samples[i];
    if (s.interval_count == 0) continue;
    truth.prepare(s.move_index, fraction_of(p, s));
    for (int k = 0; k < s.interval_count; ++k) {
      const auto& iv = p.profile.intervals[s.interval_begin + k];
      // Points inside the engaged interval (immersion φ → world θ = ψ + π/2 − φ), away from its ends.
      for (double t : {0.1, 0.5, 0.9}) {
        const double phi = iv.entry_rad + t * (iv.exit_rad - iv.entry_rad);
        if (iv.exit_rad - iv.entry_rad < deg_to_rad(0.05)) continue;
        const double theta = s.feed_direction_rad + 0.5 * kPi - phi;
        ++checked_points;
        ASSERT_TRUE(truth.engaged(theta)) << "sample " << i << " (part " << p.cycle.path.part_names[s.part]
                                          << ") engaged at phi " << rad_to_deg(phi)
                                          << " deg where material was already removed; r " << r;
      }
    }
  }
  EXPECT_GT(checked_points, 1000u);
  std::printf("pocket: %zu engaged tool-circle points checked against the oracle, none in removed material\n",
              checked_points);
  // And the totals agree with the oracle on a subset of samples.
  for (std::size_t i = 0; i < p.profile.samples.size(); i += 97) {
    const auto& s = p.profile.samples[i];
    ASSERT_NEAR(s.engagement_rad, truth.engagement_rad(s.move_index, fraction_of(p, s)), kOracleToleranceRad)
        << "sample " << i << " part " << p.cycle.path.part_names[s.part];
  }
}

}  // namespace
}  // namespace feedplan::geometry
