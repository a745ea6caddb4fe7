// The chip-area ratio ρ against closed forms, an independent quadrature, and the engagement of a tool
// entering a block head-on.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/chip_area_ratio.hpp"
#include "feedplan/geometry/engagement.hpp"

namespace feedplan::geometry {
namespace {

double ratio_of(const std::vector<EngagedInterval>& intervals) {
  return chip_area_ratio(intervals.data(), intervals.data() + intervals.size());
}

TEST(ChipAreaRatio, StraightCutsAreOne) {
  for (double alpha = 0.05; alpha <= kPi; alpha += 0.05) {
    EXPECT_NEAR(ratio_of({{kPi - alpha, kPi}}), 1.0, 1e-12) << "down milling, alpha " << alpha;
    EXPECT_NEAR(ratio_of({{0.0, alpha}}), 1.0, 1e-12) << "up milling, alpha " << alpha;
  }
  EXPECT_NEAR(ratio_of({{0.0, kPi}}), 1.0, 1e-12);  // slot
  EXPECT_DOUBLE_EQ(ratio_of({}), 1.0);             // nothing engaged
  EXPECT_DOUBLE_EQ(ratio_of({{-0.4, 0.0}}), 1.0);  // behind the feed: no chip
}

TEST(ChipAreaRatio, CentredFrontArcIsTwoCosHalfWidth) {
  for (double alpha = 0.02; alpha <= 0.5 * kPi; alpha += 0.02) {
    EXPECT_NEAR(ratio_of({{0.5 * kPi - 0.5 * alpha, 0.5 * kPi + 0.5 * alpha}}), 2.0 * std::cos(0.5 * alpha), 1e-12);
  }
}

// ρ from its definition by midpoint quadrature of the chip thickness (not the closed-form integral).
double quadrature_ratio(const std::vector<EngagedInterval>& intervals) {
  constexpr int kSteps = 20000;
  double area = 0.0, engaged = 0.0, k = 0.0;
  for (const auto& i : intervals) {
    const double h = (i.exit_rad - i.entry_rad) / kSteps;
    engaged += i.exit_rad - i.entry_rad;
    for (int j = 0; j <= kSteps; ++j) {
      const double sine = std::max(std::sin(i.entry_rad + j * h), 0.0);
      k = std::max(k, sine);
      if (j < kSteps) area += std::max(std::sin(i.entry_rad + (j + 0.5) * h), 0.0) * h;
    }
  }
  const double straight_k = std::sin(std::min(engaged, 0.5 * kPi));
  const double straight_area = 1.0 - std::cos(std::min(engaged, kPi));
  return std::max(1.0, area * straight_k / (k * straight_area));
}

TEST(ChipAreaRatio, MatchesQuadratureOnRandomIntervals) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> angle(-0.5 * kPi, 1.5 * kPi);
  int checked = 0;
  for (int n = 0; n < 300; ++n) {
    double a = angle(rng), b = angle(rng), c = angle(rng), d = angle(rng);
    if (a > b) std::swap(a, b);
    if (c > d) std::swap(c, d);
    std::vector<EngagedInterval> intervals{{a, b}};
    if (c > b) intervals.push_back({c, d});
    const double rho = ratio_of(intervals);
    const double oracle = quadrature_ratio(intervals);
    if (!std::isfinite(oracle)) continue;
    ++checked;
    ASSERT_NEAR(rho, oracle, 1e-4 * oracle) << a << " " << b << " " << c << " " << d;
    ASSERT_GE(rho, 1.0);
  }
  EXPECT_GT(checked, 200);
}

// A full-width slot started head-on into the block edge x = 0: with the tool centre at x ∈ (−r, 0) the
// engaged arc is centred at the front with half-width a, cos a = −x / r, so ρ = 2 sin a ·
// sin(min(2a, π/2)) / (1 − cos(min(2a, π))) — about 2 while only a thin cap is in; once the front half
// is in, the slot is a straight cut again (ρ = 1).
TEST(ChipAreaRatio, HeadOnEntryIntoABlock) {
  const double r = 5.0;
  Stock stock;
  stock.z_top_mm = 0;
  stock.z_bottom_mm = -30;
  stock.regions.push_back({Contour::rectangle({0, -50}, {100, 50}), {}});
  ToolPath path;
  Move m;
  m.kind = MoveKind::kLine;
  m.start = {-10, 0, -3};
  m.end = {40, 0, -3};
  m.cutting = true;
  m.axial_depth_mm = 3;
  path.moves.push_back(m);
  const auto profile = compute_engagement(path, stock, r, {.ds_mm = 0.05});
  int entering = 0;
  for (const auto& s : profile.samples) {
    const double x = s.position.x_mm;
    if (x > -r + 0.05 && x < -0.05) {
      const double a = std::acos(-x / r);
      const double expected = 2.0 * std::sin(a) * std::sin(std::min(2.0 * a, 0.5 * kPi)) / (1.0 - std::cos(std::min(2.0 * a, kPi)));
      EXPECT_NEAR(s.chip_area_ratio, std::max(expected, 1.0), 1e-6) << "x " << x;
      ++entering;
    }
    if (x > 1.0) {
      EXPECT_NEAR(s.chip_area_ratio, 1.0, 1e-9) << "x " << x;
    }
  }
  EXPECT_GT(entering, 90);
}

}  // namespace
}  // namespace feedplan::geometry
