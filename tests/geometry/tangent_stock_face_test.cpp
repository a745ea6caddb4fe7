// Regression: a tool circle that only touches a polygon stock's boundary (no crossings) was
// classified by its point at θ = 0 — exactly the tangency point when the tool runs beside a block face
// on its +X side — and a tool wholly outside the block got a full circle of material. The sample
// trochoid showed it as a 27° engagement spike at the start of loop 5, in the air before the block.

#include <gtest/gtest.h>

#include <numbers>

#include "feedplan/geometry/engagement.hpp"

namespace feedplan::geometry {
namespace {

ToolPath single_line(Point3 from, Point3 to) {
  ToolPath path;
  Move move;
  move.kind = MoveKind::kLine;
  move.start = from;
  move.end = to;
  move.cutting = true;
  move.axial_depth_mm = 10;
  path.moves.push_back(move);
  path.part_names = {"line"};
  return path;
}

TEST(TangentStockFace, AToolBesideABlockFaceMeetsNoMaterial) {
  Stock stock;
  stock.z_bottom_mm = -15;
  stock.z_top_mm = 0;
  stock.regions.push_back({Contour::rectangle({9, -20}, {29, 20}), {}});
  // Tool centre on x = 4 with radius 5: its circle touches the face x = 9 at θ = 0 all the way.
  const auto profile = compute_engagement(single_line({4, -5, -10}, {4, 5, -10}), stock, 5.0, {.ds_mm = 0.5});
  ASSERT_FALSE(profile.samples.empty());
  for (const auto& s : profile.samples) EXPECT_EQ(s.engagement_rad, 0.0) << "at y " << s.position.y_mm;
}

TEST(TangentStockFace, AToolInscribedInASquareIsEngagedAllAround) {
  Stock stock;
  stock.z_bottom_mm = -15;
  stock.z_top_mm = 0;
  stock.regions.push_back({Contour::rectangle({-5, -5}, {5, 5}), {}});
  // The first sample (the tool at the origin, nothing cut yet) touches all four sides.
  const auto profile = compute_engagement(single_line({0, 0, -10}, {0, 1, -10}), stock, 5.0, {.ds_mm = 0.5});
  ASSERT_FALSE(profile.samples.empty());
  EXPECT_NEAR(profile.samples.front().engagement_rad, 2 * std::numbers::pi, 1e-9);
}

}  // namespace
}  // namespace feedplan::geometry
