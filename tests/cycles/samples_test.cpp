// Every bundled sample spec loads, generates a consistent path on a valid stock, starts and ends at
// the clearance height, and never meets material with a rapid or an air move.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/tool_path.hpp"

namespace feedplan::cycles {
namespace {

std::vector<std::filesystem::path> sample_specs() {
  std::vector<std::filesystem::path> specs;
  for (const auto& entry : std::filesystem::directory_iterator(FEEDPLAN_SAMPLES_DIR)) {
    if (entry.path().extension() == ".yaml") specs.push_back(entry.path());
  }
  std::sort(specs.begin(), specs.end());
  return specs;
}

TEST(Samples, OneSpecPerCycle) {
  std::vector<std::string> names;
  for (const auto& path : sample_specs()) names.push_back(path.stem().string());
  for (const char* cycle : {"corner", "trochoid", "spiral", "helical_boring", "pocket"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), cycle), names.end()) << cycle;
  }
}

TEST(Samples, EveryYamlLoadsAndGeneratesACleanCycle) {
  const auto specs = sample_specs();
  ASSERT_GE(specs.size(), 5u);
  for (const auto& path : specs) {
    SCOPED_TRACE(path.string());
    const CycleSpec spec = load_cycle_spec(path);
    // Named after the cycle, with an optional suffix for a variant (trochoid_r15).
    EXPECT_EQ(path.stem().string().rfind(spec.cycle, 0), 0u);
    // Seed 003 Table 1 conditions.
    EXPECT_EQ(spec.tool.diameter_mm, 10.0);
    EXPECT_EQ(spec.tool.flutes, 4);
    EXPECT_EQ(spec.material, "S50C");
    EXPECT_EQ(spec.spindle_rpm, 2800.0);
    EXPECT_GT(spec.target_force_n, 0.0);
    const Cycle cycle = generate(spec);
    EXPECT_TRUE(geometry::consistency_defects(cycle.path).empty());
    EXPECT_TRUE(geometry::validate(cycle.stock).empty());
    ASSERT_FALSE(cycle.path.moves.empty());
    EXPECT_EQ(cycle.path.moves.front().kind, geometry::MoveKind::kRapid);
    EXPECT_DOUBLE_EQ(cycle.path.moves.front().start.z_mm, 5.0);
    EXPECT_DOUBLE_EQ(cycle.path.moves.back().end.z_mm, 5.0);
    const auto profile = geometry::compute_engagement(cycle.path, cycle.stock, spec.tool.radius_mm(), {.ds_mm = 0.2});
    EXPECT_TRUE(profile.warnings.empty()) << profile.warnings.front();
    double max_engagement = 0;
    for (const auto& s : profile.samples) max_engagement = std::max(max_engagement, s.engagement_rad);
    EXPECT_GT(max_engagement, 0.0) << "the cycle cuts nothing";
  }
}

}  // namespace
}  // namespace feedplan::cycles
