// Seeded random property test: random line/arc paths over random stock. Every sample must satisfy
// the invariants of a single pass (engagement in [0, π], chip factor in [0, 1], L = r·α_en, ordered
// disjoint intervals), and random samples must match the brute-force oracle within 0.2°.
// Reproduce a run with FEEDPLAN_TEST_SEED and FEEDPLAN_TEST_COUNT.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

#include "brute_force_oracle.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/engagement.hpp"

namespace feedplan::geometry {
namespace {

unsigned env_or(const char* name, unsigned fallback) {
  const char* text = std::getenv(name);
  return text ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : fallback;
}

struct RandomCase {
  ToolPath path;
  Stock stock;
  double tool_radius_mm = 5;
};

RandomCase make_case(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  RandomCase c;
  c.tool_radius_mm = uniform(1.0, 8.0);
  c.stock.z_top_mm = 0;
  c.stock.z_bottom_mm = -40;
  StockRegion region;
  region.outer = Contour::rectangle({uniform(-60, -30), uniform(-60, -30)}, {uniform(30, 60), uniform(30, 60)});
  if (unit(rng) < 0.6) region.holes.push_back(Contour::circle({uniform(-10, 10), uniform(-10, 10)}, uniform(2, 15)));
  if (unit(rng) < 0.4) {
    region.holes.push_back(Contour::polygon({{20, -25}, {27, -22}, {25, -12}, {18, -15}}));
  }
  c.stock.regions.push_back(region);

  // Start outside the stock, then wander through it with lines and arcs at one depth.
  const double z = -uniform(1, 20);
  const double depth = -z;
  Point3 at{-90, uniform(-20, 20), z};
  double heading = uniform(-0.3, 0.3);
  const int moves = 4 + static_cast<int>(unit(rng) * 10);
  for (int i = 0; i < moves; ++i) {
    Move m;
    m.start = at;
    m.cutting = true;
    m.axial_depth_mm = depth;
    if (i == 0 || unit(rng) < 0.5) {
      const double length = i == 0 ? uniform(60, 90) : uniform(2, 25);
      if (i > 0) heading += uniform(-2.0, 2.0);
      m.kind = MoveKind::kLine;
      m.end = {at.x_mm + length * std::cos(heading), at.y_mm + length * std::sin(heading), z};
    } else {
      const double radius = uniform(1, 30);
      const bool ccw = unit(rng) < 0.5;
      const double sweep = uniform(0.2, 5.5);
      const double to_center = heading + (ccw ? 0.5 : -0.5) * kPi;
      m.kind = MoveKind::kArc;
      m.ccw = ccw;
      m.sweep_rad = sweep;
      m.center = {at.x_mm + radius * std::cos(to_center), at.y_mm + radius * std::sin(to_center)};
      const double a0 = to_center + kPi;
      const double a1 = a0 + (ccw ? sweep : -sweep);
      m.end = {m.center.x_mm + radius * std::cos(a1), m.center.y_mm + radius * std::sin(a1), z};
      heading += ccw ? sweep : -sweep;
    }
    at = m.end;
    c.path.moves.push_back(m);
  }
  return c;
}

TEST(RandomPaths, SinglePassInvariantsAndOracle) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 20261122u);
  const unsigned count = env_or("FEEDPLAN_TEST_COUNT", 300u);
  std::cout << "random paths: FEEDPLAN_TEST_SEED=" << seed << " FEEDPLAN_TEST_COUNT=" << count << "\n";
  std::mt19937_64 rng(seed);
  std::size_t samples_checked = 0;
  std::size_t oracle_checks = 0;
  double worst_deviation_rad = 0.0;
  for (unsigned n = 0; n < count; ++n) {
    RandomCase c = make_case(rng);
    ASSERT_TRUE(consistency_defects(c.path).empty()) << "case " << n;
    const auto profile = compute_engagement(c.path, c.stock, c.tool_radius_mm, {.ds_mm = 0.2});
    for (const auto& s : profile.samples) {
      ++samples_checked;
      ASSERT_GE(s.engagement_rad, 0.0) << "case " << n;
      ASSERT_LE(s.engagement_rad, kPi + 1e-9) << "case " << n << " s " << s.s_mm;
      ASSERT_GE(s.chip_factor, 0.0);
      ASSERT_LE(s.chip_factor, 1.0);
      ASSERT_NEAR(s.contact_length_mm, c.tool_radius_mm * s.engagement_rad, 1e-12);
      double previous_exit = -0.5 * kPi;
      for (int k = 0; k < s.interval_count; ++k) {
        const auto& iv = profile.intervals[s.interval_begin + k];
        ASSERT_LT(iv.entry_rad, iv.exit_rad);
        ASSERT_GE(iv.entry_rad, previous_exit);
        ASSERT_LE(iv.exit_rad, 1.5 * kPi + 1e-12);
        previous_exit = iv.exit_rad;
      }
    }
    // Differential check against the brute-force oracle at a few random samples.
    oracle::EngagementOracle truth(c.path, c.stock, c.tool_radius_mm);
    std::uniform_int_distribution<std::size_t> pick(0, profile.samples.size() - 1);
    for (int k = 0; k < 3; ++k) {
      const auto& s = profile.samples[pick(rng)];
      const Move& move = c.path.moves[s.move_index];
      const double f = std::clamp((s.s_mm - [&] {
        double start = 0;
        for (int i = 0; i < s.move_index; ++i) start += length_mm(c.path.moves[i]);
        return start;
      }()) / length_mm(move), 0.0, 1.0);
      const double expected = truth.engagement_rad(s.move_index, f);
      ++oracle_checks;
      worst_deviation_rad = std::max(worst_deviation_rad, std::abs(s.engagement_rad - expected));
      ASSERT_NEAR(s.engagement_rad, expected, deg_to_rad(0.2))
          << "case " << n << " move " << s.move_index << " f " << f << " (seed " << seed << ")";
    }
  }
  std::cout << "random paths: " << count << " paths, " << samples_checked << " samples, " << oracle_checks
            << " oracle comparisons, largest deviation " << rad_to_deg(worst_deviation_rad) << " deg\n";
}

}  // namespace
}  // namespace feedplan::geometry
