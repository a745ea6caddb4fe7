// The engagement is computed in stretches of the path on several threads; it must be exactly the one
// computed in one stretch on one thread: the same samples, intervals, layers and warnings, bit for bit.

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "threads_setting.hpp"

namespace feedplan::geometry {
namespace {

using test_support::ThreadsSetting;

void expect_same(const EngagementProfile& a, const EngagementProfile& b) {
  ASSERT_EQ(a.samples.size(), b.samples.size());
  ASSERT_EQ(a.intervals.size(), b.intervals.size());
  ASSERT_EQ(a.layers.size(), b.layers.size());
  EXPECT_EQ(a.warnings, b.warnings);
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    const EngagementSample& p = a.samples[i];
    const EngagementSample& q = b.samples[i];
    SCOPED_TRACE("sample " + std::to_string(i));
    ASSERT_EQ(p.s_mm, q.s_mm);
    ASSERT_EQ(p.position.x_mm, q.position.x_mm);
    ASSERT_EQ(p.position.y_mm, q.position.y_mm);
    ASSERT_EQ(p.position.z_mm, q.position.z_mm);
    ASSERT_EQ(p.feed_direction_rad, q.feed_direction_rad);
    ASSERT_EQ(p.xy_speed_ratio, q.xy_speed_ratio);
    ASSERT_EQ(p.move_index, q.move_index);
    ASSERT_EQ(p.part, q.part);
    ASSERT_EQ(p.cutting, q.cutting);
    ASSERT_EQ(p.engagement_rad, q.engagement_rad);
    ASSERT_EQ(p.entry_rad, q.entry_rad);
    ASSERT_EQ(p.exit_rad, q.exit_rad);
    ASSERT_EQ(p.chip_factor, q.chip_factor);
    ASSERT_EQ(p.contact_length_mm, q.contact_length_mm);
    ASSERT_EQ(p.chip_area_ratio, q.chip_area_ratio);
    ASSERT_EQ(p.axial_depth_mm, q.axial_depth_mm);
    ASSERT_EQ(p.interval_begin, q.interval_begin);
    ASSERT_EQ(p.interval_count, q.interval_count);
    ASSERT_EQ(p.material_height_mm, q.material_height_mm);
    ASSERT_EQ(p.end_face_in_material, q.end_face_in_material);
    ASSERT_EQ(p.layer_begin, q.layer_begin);
    ASSERT_EQ(p.layer_count, q.layer_count);
  }
  for (std::size_t k = 0; k < a.intervals.size(); ++k) {
    ASSERT_EQ(a.intervals[k].entry_rad, b.intervals[k].entry_rad) << "interval " << k;
    ASSERT_EQ(a.intervals[k].exit_rad, b.intervals[k].exit_rad) << "interval " << k;
  }
  for (std::size_t k = 0; k < a.layers.size(); ++k) {
    const EngagementLayer& p = a.layers[k];
    const EngagementLayer& q = b.layers[k];
    SCOPED_TRACE("layer " + std::to_string(k));
    ASSERT_EQ(p.bottom_z_mm, q.bottom_z_mm);
    ASSERT_EQ(p.top_z_mm, q.top_z_mm);
    ASSERT_EQ(p.interval_begin, q.interval_begin);
    ASSERT_EQ(p.interval_count, q.interval_count);
    ASSERT_EQ(p.engagement_rad, q.engagement_rad);
    ASSERT_EQ(p.chip_factor, q.chip_factor);
  }
}

EngagementProfile engagement_on(const char* threads, const cycles::Cycle& cycle, double ds_mm) {
  const ThreadsSetting setting(threads);
  EngagementOptions options;
  options.ds_mm = ds_mm;
  return compute_engagement(cycle.path, cycle.stock, cycle.tool.radius_mm(), options);
}

// A pocket (ramps, arcs, lines, retracts, several depths: stretches start on moves of every kind) and a
// trochoid (a loop's air half and its cutting half in different stretches).
TEST(EngagementStretches, ThreadsChangeNothing) {
  for (const char* yaml : {
           "cycle: pocket\n"
           "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30, name: D10}\n"
           "pocket: {center: [0, 0], width_mm: 60, height_mm: 40, depth_mm: 10, corner_radius_mm: 8}\n",
           "cycle: trochoid\n"
           "tool: {diameter_mm: 10, flutes: 4, helix_deg: 30, name: D10}\n"
           "axial_depth_mm: 10\n"
           "trochoid: {start: [0, 0], end: [9, 0], loop_radius_mm: 5, pitch_mm: 1, direction: ccw}\n",
       }) {
    const cycles::Cycle cycle = cycles::generate(cycles::read_cycle_spec(yaml, "test"));
    const EngagementProfile one = engagement_on("1", cycle, 0.1);
    ASSERT_GT(one.samples.size(), 1000u) << "enough samples for several stretches";
    for (const char* threads : {"2", "3", "8"}) {
      SCOPED_TRACE(std::string(yaml).substr(0, 14) + " on " + threads + " threads");
      expect_same(one, engagement_on(threads, cycle, 0.1));
    }
  }
}

}  // namespace
}  // namespace feedplan::geometry
