// Instantaneous mechanistic forces against the closed-form mean forces of a straight cut (Altintas,
// Manufacturing Automation ch. 2; docs/method.md §6.1), written independently of the code in
// closed_form_forces.hpp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "closed_form_forces.hpp"
#include "feedplan/sim/milling_forces.hpp"

namespace feedplan::sim {
namespace {

constexpr double kPi = std::numbers::pi;

// Mean of milling_force over one revolution of a straight cut along `feed_direction`, the tool
// advancing f_z per tooth, engaged over [φ_st, φ_ex] on every slice.
MeanForce simulated_mean(const CutterGeometry& cutter, const CuttingCoefficients& k, double axial_depth_mm, double fz_mm,
                         double phi_st, double phi_ex, double feed_direction_rad, int steps_per_rev, double slice_mm) {
  const std::vector<geometry::EngagedInterval> engaged{{phi_st, phi_ex}};
  std::vector<ForceSlice> slices;
  const int count = static_cast<int>(std::round(axial_depth_mm / slice_mm));
  for (int i = 0; i < count; ++i) slices.push_back({(i + 0.5) * slice_mm, slice_mm, engaged});
  const geometry::Point2 d{fz_mm * std::cos(feed_direction_rad), fz_mm * std::sin(feed_direction_rad)};
  const std::vector<geometry::Point2> displacement(cutter.flutes, d);
  MeanForce mean;
  for (int step = 0; step < steps_per_rev; ++step) {
    CutterState state;
    state.spindle_angle_rad = 2 * kPi * step / steps_per_rev;
    state.feed_direction_rad = feed_direction_rad;
    state.displacement_since_tooth_mm = displacement;
    const Force3 f = milling_force(cutter, k, state, slices);
    // Back into the feed frame (x along the feed) for comparison with the closed form.
    const double c = std::cos(feed_direction_rad);
    const double s = std::sin(feed_direction_rad);
    mean.fx_n += (c * f.fx_n + s * f.fy_n) / steps_per_rev;
    mean.fy_n += (-s * f.fx_n + c * f.fy_n) / steps_per_rev;
  }
  return mean;
}

TEST(MillingForces, Al7075DownMillingMatchesDesignCheck) {
  // docs/method.md §6.1: N 4, a 10, c 0.1, a_e 1.5 on r 5, down milling → F̄x 180.5 N, F̄y 295.2 N.
  const CutterGeometry cutter{5.0, 4, 30.0, {}};
  const double phi_st = kPi - std::acos(1 - 1.5 / 5.0);
  const MeanForce truth = closed_form_mean(4, 10, 0.1, phi_st, kPi, al7075());
  // The closed form gives 180.44 N; docs/method.md §6.1 quotes it rounded up to 180.5.
  EXPECT_NEAR(truth.fx_n, 180.5, 0.1);
  EXPECT_NEAR(truth.fy_n, 295.2, 0.1);
  const MeanForce sim = simulated_mean(cutter, al7075(), 10, 0.1, phi_st, kPi, 0.0, 7200, 0.1);
  std::printf("Al7075 down milling a_e 1.5: simulated Fx %.2f N Fy %.2f N, closed form %.2f / %.2f N\n", sim.fx_n,
              sim.fy_n, truth.fx_n, truth.fy_n);
  EXPECT_NEAR(sim.fx_n, truth.fx_n, 0.01 * std::abs(truth.fx_n));
  EXPECT_NEAR(sim.fy_n, truth.fy_n, 0.01 * std::abs(truth.fy_n));
}

TEST(MillingForces, SlotUpAndDownMillingMatchClosedFormsInAnyFeedDirection) {
  const CuttingCoefficients k = al7075();
  struct Case {
    const char* name;
    double ae_mm;
    bool down;
  };
  const Case cases[] = {{"slot", 10, true}, {"down a_e 0.5", 0.5, true}, {"down a_e 3", 3, true},
                        {"up a_e 1.5", 1.5, false}, {"up a_e 4", 4, false}, {"up a_e 7", 7, false}};
  for (double helix : {0.0, 30.0, 45.0}) {
    for (double feed_dir : {0.0, 2.1}) {
      for (const auto& c : cases) {
        const CutterGeometry cutter{5.0, 3, helix, {}};
        const double alpha = std::acos(1 - c.ae_mm / 5.0);
        const double st = c.down ? kPi - alpha : 0.0;
        const double ex = c.down ? kPi : alpha;
        const MeanForce truth = closed_form_mean(3, 6, 0.08, st, ex, k);
        const MeanForce sim = simulated_mean(cutter, k, 6, 0.08, st, ex, feed_dir, 7200, 0.1);
        const double scale = std::hypot(truth.fx_n, truth.fy_n);
        EXPECT_NEAR(sim.fx_n, truth.fx_n, 0.01 * scale) << c.name << " helix " << helix << " feed " << feed_dir;
        EXPECT_NEAR(sim.fy_n, truth.fy_n, 0.01 * scale) << c.name << " helix " << helix << " feed " << feed_dir;
      }
    }
  }
}

TEST(MillingForces, SingleToothElementHasTheTextbookComponents) {
  // One straight flute, one thin slice, the tooth at the front (φ = 90°): F_x = −F_r, F_y = F_t.
  CuttingCoefficients k = al7075();
  const CutterGeometry cutter{5.0, 1, 0.0, {}};
  const std::vector<geometry::EngagedInterval> engaged{{0.0, kPi}};
  const std::vector<ForceSlice> slices{{0.5, 1.0, engaged}};
  const std::vector<geometry::Point2> d{{0.1, 0.0}};
  CutterState state;
  state.spindle_angle_rad = 0.0;  // tooth 0 at world angle 0 = +x = the front for feed along +x
  state.displacement_since_tooth_mm = d;
  const Force3 f = milling_force(cutter, k, state, slices);
  EXPECT_NEAR(f.fx_n, -(169 * 0.1 + 30.8), 1e-9);
  EXPECT_NEAR(f.fy_n, 796 * 0.1 + 27.7, 1e-9);
  EXPECT_NEAR(f.fz_n, 222 * 0.1 + 1.4, 1e-9);
}

TEST(MillingForces, RunoutLoadsTheLongToothMoreAndTheNextOneLess) {
  const CuttingCoefficients k = al7075();
  CutterGeometry cutter{5.0, 2, 0.0, {0.01, 0.0}};
  const std::vector<geometry::EngagedInterval> engaged{{0.0, kPi}};
  const std::vector<ForceSlice> slices{{0.5, 1.0, engaged}};
  const std::vector<geometry::Point2> d{{0.05, 0.0}, {0.10, 0.0}};
  CutterState state;
  state.displacement_since_tooth_mm = d;
  // Tooth 0 at the front (h = 0.05 + 0.01), then tooth 1 at the front (h = 0.05 − 0.01).
  state.spindle_angle_rad = 0.0;
  const double long_tooth = milling_force(cutter, k, state, slices).fy_n;
  state.spindle_angle_rad = kPi;
  const double short_tooth = milling_force(cutter, k, state, slices).fy_n;
  EXPECT_NEAR(long_tooth, 796 * 0.06 + 27.7, 1e-9);
  EXPECT_NEAR(short_tooth, 796 * 0.04 + 27.7, 1e-9);
  // A runout larger than the feed per tooth: the short tooth cuts nothing, the long one two feeds.
  cutter.runout_mm = {0.08, 0.0};
  state.spindle_angle_rad = kPi;
  EXPECT_EQ(milling_force(cutter, k, state, slices).fy_n, 0.0);
  state.spindle_angle_rad = 0.0;
  EXPECT_NEAR(milling_force(cutter, k, state, slices).fy_n, 796 * 0.10 + 27.7, 1e-9);
}

TEST(MillingForces, SizeEffectScalesTheCuttingTermsOnly) {
  CuttingCoefficients k = al7075();
  k.size_exponent = 0.2;
  k.size_reference_chip_mm = 0.1;
  const CutterGeometry cutter{5.0, 1, 0.0, {}};
  const std::vector<geometry::EngagedInterval> engaged{{0.0, kPi}};
  const std::vector<ForceSlice> slices{{0.5, 1.0, engaged}};
  const std::vector<geometry::Point2> d{{0.05, 0.0}};
  CutterState state;
  state.displacement_since_tooth_mm = d;
  const double factor = std::pow(0.05 / 0.1, -0.2);
  EXPECT_NEAR(milling_force(cutter, k, state, slices).fy_n, 796 * factor * 0.05 + 27.7, 1e-9);
}

}  // namespace
}  // namespace feedplan::sim
