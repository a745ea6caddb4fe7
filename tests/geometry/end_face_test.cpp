// The tool's end face on the way down: material inside the tool circle that the circle itself does not
// reach. Truths by construction: a round island of radius 1 mm under a Ø10 tool plunging at its centre
// (the circle is in the air, the end face comes down on the island from the island's top on); the same
// plunge beside the island (nothing under the face); inside a pre-drilled hole wider than the tool
// (nothing anywhere); and a tool climbing back up through its own plunge (it does not descend).

#include <gtest/gtest.h>

#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/stock.hpp"

namespace feedplan::geometry {
namespace {

ToolPath plunge(Point3 from, Point3 to) {
  ToolPath path;
  Move move;
  move.kind = MoveKind::kLine;
  move.start = from;
  move.end = to;
  move.cutting = true;
  move.axial_depth_mm = from.z_mm - to.z_mm;
  path.moves.push_back(move);
  path.part_names = {"plunge"};
  return path;
}

Stock island() {
  Stock stock;
  stock.z_bottom_mm = -10;
  stock.z_top_mm = 0;
  stock.regions.push_back({Contour::circle({0, 0}, 1.0), {}});
  return stock;
}

TEST(EndFace, APlungeOntoAnIslandUnderTheToolMeetsItWithTheFaceNotTheCircle) {
  const auto profile = compute_engagement(plunge({0, 0, 2}, {0, 0, -3}), island(), 5.0, {.ds_mm = 0.25});
  int on_island = 0;
  for (const auto& s : profile.samples) {
    EXPECT_EQ(s.engagement_rad, 0.0) << "z " << s.position.z_mm;  // the island is inside the circle
    const bool below_top = s.position.z_mm < -1e-3;
    EXPECT_EQ(s.end_face_in_material, below_top) << "z " << s.position.z_mm;
    on_island += s.end_face_in_material;
  }
  EXPECT_GT(on_island, 5);
}

TEST(EndFace, APlungeBesideTheIslandMeetsNothing) {
  const auto profile = compute_engagement(plunge({20, 0, 2}, {20, 0, -3}), island(), 5.0, {.ds_mm = 0.25});
  for (const auto& s : profile.samples) EXPECT_FALSE(s.end_face_in_material) << "z " << s.position.z_mm;
}

TEST(EndFace, APlungeInsideAWiderHoleMeetsNothing) {
  Stock stock;
  stock.z_bottom_mm = -10;
  stock.z_top_mm = 0;
  stock.regions.push_back({Contour::rectangle({-30, -30}, {30, 30}), {Contour::circle({0, 0}, 6.0)}});
  const auto profile = compute_engagement(plunge({0, 0, 2}, {0, 0, -3}), stock, 5.0, {.ds_mm = 0.25});
  for (const auto& s : profile.samples) {
    EXPECT_EQ(s.engagement_rad, 0.0);
    EXPECT_FALSE(s.end_face_in_material) << "z " << s.position.z_mm;
  }
}

TEST(EndFace, ClimbingBackUpIsNotAPlunge) {
  ToolPath path = plunge({0, 0, 2}, {0, 0, -3});
  Move up = path.moves.front();
  std::swap(up.start, up.end);
  path.moves.push_back(up);
  const auto profile = compute_engagement(path, island(), 5.0, {.ds_mm = 0.25});
  for (const auto& s : profile.samples) {
    if (s.move_index == 1) {
      EXPECT_FALSE(s.end_face_in_material) << "z " << s.position.z_mm;
    }
  }
}

}  // namespace
}  // namespace feedplan::geometry
