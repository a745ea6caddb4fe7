// Regression: a helical bore read back from G-code written with 3 decimals shares its re-cut layers.
// The bore's flat bottom circle re-cuts every helix turn, but its pieces' rounded end points lie up to
// 0.7 µm off the helix's circle, so a re-cut test on exact tracks never lets the layers above share
// the lowest layer's engagement: every layer of the bore is computed along the whole path (the pocket
// sample took 5 minutes so). With the tolerance from the program's number resolution (1.4 µm) the
// upper layers are computed only up to the bottom circle, and the per-revolution peaks are those of
// every layer computed along the whole path. Written with R instead of I J, the short pieces'
// centres — on the bisector of their rounded ends — lie up to 9 µm from the helix's: the re-cut test
// compares tracks, not centres.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "closed_form_forces.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::sim {
namespace {

constexpr double kPi = std::numbers::pi;

std::string xy_words(double x_mm, double y_mm) {
  char text[64];
  std::snprintf(text, sizeof text, "X%.3f Y%.3f", x_mm, y_mm);
  return text;
}

// A bore of radius 3 (tool centre) into a block, helically down 3 mm at 1 mm pitch in half turns; a
// flat bottom circle written as a planner writes it (end points rounded to 3 decimals, I J from the
// rounded start to the centre), as in the pocket sample: a piece to 77.35°, then pieces of 5°; then
// out to radius 6 and a half turn there, which opens the bore wall on every layer. With I J
// (`radius_words` false) the reader moves the long first piece's centre by 0.14 µm and keeps the short
// pieces on its circle, 0.17 µm inside the helix's; with R3 every piece has its own centre.
std::string bore_program(bool radius_words) {
  std::string text = "G21 G17 G90 G91.1 G94\nS3000 M3\nG0 X3.000 Y0.000 Z1.000\nG1 Z0.000 F600\n";
  for (int half = 1; half <= 6; ++half) {
    char block[96];
    std::snprintf(block, sizeof block, "G3 X%.3f Y0.000 Z%.3f I%.3f J0.000\n", half % 2 ? -3.0 : 3.0, -0.5 * half,
                  half % 2 ? -3.0 : 3.0);
    text += block;
  }
  double x = 3.0, y = 0.0;
  for (double angle_deg = 77.35; angle_deg <= 360.0; angle_deg = angle_deg < 80.0 ? 80.0 : angle_deg + 5.0) {
    const double angle = angle_deg * kPi / 180.0;
    const double to_x = std::round(3000.0 * std::cos(angle)) / 1000.0;
    const double to_y = std::round(3000.0 * std::sin(angle)) / 1000.0;
    char center[48];
    std::snprintf(center, sizeof center, " I%.3f J%.3f\n", -x, -y);
    text += "G3 " + xy_words(to_x, to_y) + (radius_words ? std::string(" R3.000\n") : std::string(center));
    x = to_x;
    y = to_y;
  }
  text += "G1 X6.000 Y0.000\nG3 X-6.000 Y0.000 I-6.000 J0.000\nG0 Z5.000\nM2\n";
  return text;
}

SimulationRequest bore_request(bool radius_words) {
  SimulationRequest request;
  request.program = gcode::read_program(bore_program(radius_words), "bore");
  request.tool = {"D10 Z4", 10.0, 4, 30.0};
  request.coefficients = al7075();
  request.stock.regions.push_back({geometry::Contour::rectangle({-20, -20}, {20, 20}), {}});
  request.stock.z_top_mm = 0;
  request.stock.z_bottom_mm = -10;
  request.machine.max_accel_mm_per_s2 = 2000;
  request.options.log_rate_hz = 1000;
  return request;
}

class ReadBackBore : public ::testing::TestWithParam<bool> {};

TEST_P(ReadBackBore, SharesTheRecutLayersWithThePeaksOfEveryLayerComputed) {
  SimulationRequest request = bore_request(GetParam());
  ASSERT_DOUBLE_EQ(request.program.coordinate_resolution_mm, 0.001);
  const SimulationResult shared = simulate(request);
  request.options.recut_tolerance_mm = 1e-9;  // exact tracks only: every layer along the whole path
  const SimulationResult computed = simulate(request);

  EXPECT_NEAR(shared.summary.recut_tolerance_mm, std::sqrt(2.0) * 0.001, 1e-12);
  EXPECT_EQ(computed.summary.engagement_bands, 60);  // 3 mm of helix in layers of 1/20 of its pitch
  EXPECT_EQ(shared.summary.engagement_bands, 60);
  // The line out and the opening half turn are a quarter of the path: the 59 upper layers skip them.
  EXPECT_LT(static_cast<double>(shared.summary.engagement_samples), 0.8 * computed.summary.engagement_samples);

  ASSERT_EQ(shared.revolutions.size(), computed.revolutions.size());
  double largest_peak_n = 0.0, largest_difference_n = 0.0;
  for (std::size_t i = 0; i < shared.revolutions.size(); ++i) {
    largest_peak_n = std::max(largest_peak_n, computed.revolutions[i].peak_xy_n);
    largest_difference_n =
        std::max(largest_difference_n, std::abs(shared.revolutions[i].peak_xy_n - computed.revolutions[i].peak_xy_n));
  }
  std::printf("read-back bore (%s): %lld vs %lld engagement samples; peaks up to %.1f N differ by at most %.2g N\n",
              GetParam() ? "R" : "I J", shared.summary.engagement_samples, computed.summary.engagement_samples,
              largest_peak_n, largest_difference_n);
  EXPECT_GT(largest_peak_n, 100.0);  // the opening turn cuts
  EXPECT_LE(largest_difference_n, 1e-3 * largest_peak_n);
}

INSTANTIATE_TEST_SUITE_P(CentreWords, ReadBackBore, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) { return info.param ? "R" : "IJ"; });

}  // namespace
}  // namespace feedplan::sim
