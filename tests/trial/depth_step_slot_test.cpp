// The depth-step slot's geometry (trial/depth_step_slot.hpp), checked against positions worked out by
// hand for a Ø10 mm tool, depths 1, 3, 2 mm held 30 mm each: held x 0…30 at 1 mm; a ramp of
// max(2, 2 × 2) = 4 mm; 34…64 at 3 mm; a ramp of max(2, 2 × 1) = 2 mm; 66…96 at 2 mm; the block's end at
// 96 + 5 = 101, the exit at 101 + 5 + 1 = 107.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/trial/depth_step_slot.hpp"

namespace feedplan::trial {
namespace {

DepthStepSlotRequest request_132() {
  DepthStepSlotRequest request;
  request.tool.diameter_mm = 10.0;
  request.tool.flutes = 4;
  request.depths_mm = {1.0, 3.0, 2.0};
  request.step_length_mm = 30.0;
  request.feed_mm_per_min = 300.0;
  request.spindle_rpm = 2800.0;
  return request;
}

TEST(DepthStepSlot, EachDepthIsHeldOverItsLengthAndTheBlockEndsPastTheLast) {
  const DepthStepSlot slot = make_depth_step_slot(request_132());
  const double held[3][3] = {{0.0, 30.0, 1.0}, {34.0, 64.0, 3.0}, {66.0, 96.0, 2.0}};
  ASSERT_EQ(slot.segments.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(slot.segments[i].start_x_mm, held[i][0]);
    EXPECT_DOUBLE_EQ(slot.segments[i].end_x_mm, held[i][1]);
    EXPECT_DOUBLE_EQ(slot.segments[i].depth_mm, held[i][2]);
    EXPECT_DOUBLE_EQ(slot.segments[i].steady_from_x_mm, held[i][0] + 15.0);
  }
  // The program's z at every x, sampled along every move: −depth over each held length; in the ramps
  // between the two depths; y always 0.
  int held_points = 0;
  double x_max = -1e9;
  for (const geometry::Move& move : slot.program.path.moves) {
    for (int k = 0; k <= 20; ++k) {
      const geometry::Point3 p = geometry::point_at(move, k / 20.0);
      EXPECT_NEAR(p.y_mm, 0.0, 1e-9);
      x_max = std::max(x_max, p.x_mm);
      for (const auto& h : held) {
        if (p.x_mm >= h[0] && p.x_mm <= h[1] && p.z_mm < 0.0) {
          EXPECT_NEAR(p.z_mm, -h[2], 1e-9) << "x = " << p.x_mm;
          ++held_points;
        }
      }
      if (p.x_mm > 30.0 && p.x_mm < 34.0 && p.z_mm < 0.0) {
        EXPECT_GT(p.z_mm, -3.0 - 1e-9);
        EXPECT_LT(p.z_mm, -1.0 + 1e-9);
      }
    }
  }
  EXPECT_GT(held_points, 20);
  EXPECT_DOUBLE_EQ(x_max, 107.0);
  // The block: x 0…101, wider than the slot, deeper than the deepest cut.
  ASSERT_EQ(slot.stock.regions.size(), 1u);
  double bx_min = 1e9, bx_max = -1e9, by_max = -1e9;
  for (const auto& q : slot.stock.regions[0].outer.vertices) {
    bx_min = std::min(bx_min, q.x_mm);
    bx_max = std::max(bx_max, q.x_mm);
    by_max = std::max(by_max, q.y_mm);
  }
  EXPECT_DOUBLE_EQ(bx_min, 0.0);
  EXPECT_DOUBLE_EQ(bx_max, 101.0);
  EXPECT_GT(by_max, 5.0);
  EXPECT_LT(slot.stock.z_bottom_mm, -3.0);
  // The spindle speed and the feed are the ones asked for.
  bool feed_seen = false;
  for (const geometry::BlockCommand& block : slot.program.blocks) {
    if (block.feed_mm_per_min > 0.0) {
      EXPECT_DOUBLE_EQ(block.feed_mm_per_min, 300.0);
      feed_seen = true;
    }
    if (block.spindle_rpm > 0.0) {
      EXPECT_DOUBLE_EQ(block.spindle_rpm, 2800.0);
    }
  }
  EXPECT_TRUE(feed_seen);
}

TEST(DepthStepSlot, BadRequestsAreNamed) {
  DepthStepSlotRequest request = request_132();
  request.depths_mm = {1.0, 12.0, NAN};
  request.step_length_mm = 10.0;
  const std::vector<InputProblem> problems = validate(request);
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_EQ(problems[0].field, "depth_step.depths_mm[1]");
  EXPECT_NE(problems[0].message.find("12"), std::string::npos);
  EXPECT_NE(problems[0].message.find("(0, 10]"), std::string::npos);
  EXPECT_EQ(problems[1].field, "depth_step.depths_mm[2]");
  EXPECT_EQ(problems[2].field, "depth_step.step_length_mm");
  request = request_132();
  request.depths_mm = {2.0};
  ASSERT_EQ(validate(request).size(), 1u);
  EXPECT_EQ(validate(request)[0].field, "depth_step.depths_mm");
  EXPECT_THROW(make_depth_step_slot(request), InputError);
}

}  // namespace
}  // namespace feedplan::trial
