// The layered stock's sharing of re-cut layers (layered_engagement.hpp): a helical bore crosses every
// layer, so each layer is computed on its own until the bore's flat bottom circle has re-cut every
// turn; from there on the upper layers take the lowest layer's engagement. The truth is every layer
// computed along the whole path (share_recut_layers = false): the arcs must be the same at every
// sample, on every layer.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/sim/layered_engagement.hpp"

namespace feedplan::sim {
namespace {

constexpr double kPi = std::numbers::pi;

geometry::Move line(geometry::Point3 from, geometry::Point3 to) {
  geometry::Move move;
  move.kind = geometry::MoveKind::kLine;
  move.start = from;
  move.end = to;
  move.cutting = true;
  move.axial_depth_mm = 3.0;
  return move;
}

// A counter-clockwise arc about (0, 0) from angle a0 over `sweep`, z from z0 to z1.
geometry::Move arc(double radius, double a0, double sweep, double z0, double z1) {
  geometry::Move move;
  move.kind = geometry::MoveKind::kArc;
  move.center = {0.0, 0.0};
  move.start = {radius * std::cos(a0), radius * std::sin(a0), z0};
  move.end = {radius * std::cos(a0 + sweep), radius * std::sin(a0 + sweep), z1};
  move.sweep_rad = sweep;
  move.ccw = true;
  move.cutting = true;
  move.axial_depth_mm = 1.0;
  return move;
}

// A bore of radius 2 (tool centre circle) helically down 3 mm at 1 mm pitch, in half turns; then,
// when `bottom_circle`, a full flat circle at the bottom in two halves; then out along +x and a
// half turn of radius 6 that opens the bore.
geometry::ToolPath bore(bool bottom_circle) {
  geometry::ToolPath path;
  path.part_names = {"bore"};
  path.moves.push_back(line({2.0, 0.0, 1.0}, {2.0, 0.0, 0.0}));
  for (int half = 0; half < 6; ++half) path.moves.push_back(arc(2.0, half * kPi, kPi, -0.5 * half, -0.5 * (half + 1)));
  if (bottom_circle) {
    path.moves.push_back(arc(2.0, 0.0, kPi, -3.0, -3.0));
    path.moves.push_back(arc(2.0, kPi, kPi, -3.0, -3.0));
  }
  path.moves.push_back(line({2.0, 0.0, -3.0}, {6.0, 0.0, -3.0}));
  path.moves.push_back(arc(6.0, 0.0, kPi, -3.0, -3.0));
  return path;
}

geometry::Stock block() {
  geometry::Stock stock;
  stock.regions.push_back({geometry::Contour::rectangle({-20.0, -20.0}, {20.0, 20.0}), {}});
  stock.z_bottom_mm = -10.0;
  stock.z_top_mm = 0.0;
  return stock;
}

LayerOptions options_of(double layer_mm, double ds_mm, bool share) {
  LayerOptions options;
  options.layer_thickness_mm = layer_mm;
  options.ds_mm = ds_mm;
  options.share_recut_layers = share;
  return options;
}

// Every layer's arcs at every engagement sample spacing along the path, shared against computed.
void expect_same_engagement(const geometry::ToolPath& path) {
  const LayeredEngagement shared(path, block(), 5.0, options_of(0.05, 0.05, true));
  const LayeredEngagement computed(path, block(), 5.0, options_of(0.05, 0.05, false));
  ASSERT_EQ(shared.layer_count(), computed.layer_count());
  ASSERT_EQ(shared.layer_count(), 60);
  const double length = geometry::length_mm(path);
  int compared = 0;
  for (int layer = 0; layer < shared.layer_count(); ++layer) {
    LayeredEngagement::Cursor a, b;
    for (double s = 0.0; s <= length; s += 0.05) {
      const auto x = shared.intervals_at(layer, s, a);
      const auto y = computed.intervals_at(layer, s, b);
      ASSERT_EQ(x.size(), y.size()) << "layer " << layer << " s " << s;
      for (std::size_t i = 0; i < x.size(); ++i) {
        ASSERT_NEAR(x[i].entry_rad, y[i].entry_rad, 1e-12) << "layer " << layer << " s " << s;
        ASSERT_NEAR(x[i].exit_rad, y[i].exit_rad, 1e-12) << "layer " << layer << " s " << s;
      }
      compared += x.empty() ? 0 : 1;
    }
  }
  EXPECT_GT(compared, 10000);  // the bore and the opening turn are in the material
}

TEST(LayeredEngagement, RecutLayersShareTheLowestLayersEngagementExactly) {
  const geometry::ToolPath path = bore(true);
  expect_same_engagement(path);
  // The 59 upper layers were computed only up to the end of the bottom circle (moves 0–8 of 11).
  const LayeredEngagement shared(path, block(), 5.0, options_of(0.05, 0.05, true));
  const LayeredEngagement computed(path, block(), 5.0, options_of(0.05, 0.05, false));
  EXPECT_EQ(shared.band_count(), computed.band_count());
  double before_opening_mm = 0.0;
  for (std::size_t i = 0; i + 2 < path.moves.size(); ++i) before_opening_mm += geometry::length_mm(path.moves[i]);
  const double fraction = before_opening_mm / geometry::length_mm(path);
  const double expected = computed.samples_computed() * (1.0 + (computed.band_count() - 1) * fraction) / computed.band_count();
  EXPECT_NEAR(static_cast<double>(shared.samples_computed()), expected, 0.02 * expected);
}

TEST(LayeredEngagement, LayersWhoseHelixIsNeverRecutAreComputedAlongTheWholePath) {
  const geometry::ToolPath path = bore(false);
  expect_same_engagement(path);
  const LayeredEngagement shared(path, block(), 5.0, options_of(0.05, 0.05, true));
  const LayeredEngagement computed(path, block(), 5.0, options_of(0.05, 0.05, false));
  EXPECT_EQ(shared.samples_computed(), computed.samples_computed());
}

TEST(LayeredEngagement, ReportsThePathLengthSampledOverAllBands) {
  std::vector<double> reported;
  LayerOptions options = options_of(0.05, 0.05, true);
  double total_reported_mm = 0.0;
  options.progress = [&](double done_mm, double total_mm) {
    reported.push_back(done_mm);
    total_reported_mm = total_mm;
  };
  const geometry::ToolPath path = bore(true);
  const LayeredEngagement layers(path, block(), 5.0, options);
  ASSERT_EQ(static_cast<int>(reported.size()), layers.band_count());
  for (std::size_t i = 1; i < reported.size(); ++i) EXPECT_GT(reported[i], reported[i - 1]);
  EXPECT_DOUBLE_EQ(reported.back(), total_reported_mm);
  // The lowest layer along the whole path, the 59 others up to the end of the bottom circle.
  double before_opening_mm = 0.0;
  for (std::size_t i = 0; i + 2 < path.moves.size(); ++i) before_opening_mm += geometry::length_mm(path.moves[i]);
  EXPECT_NEAR(total_reported_mm, geometry::length_mm(path) + 59 * before_opening_mm, 1e-9);
}

}  // namespace
}  // namespace feedplan::sim
