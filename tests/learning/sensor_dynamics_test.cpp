// The factor a sensor's first mode puts on a periodic force's peak (learning/sensor_dynamics.hpp), against
// the closed form for one harmonic over a mean, and on real engagement: a sensor far above the tooth
// harmonics reads the peak as it is, a resonant one does not, and no factor exceeds the cap.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/chip_load.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/learning/sensor_dynamics.hpp"

namespace feedplan::learning {
namespace {

// |H| at f: 1 / sqrt((1 − r²)² + (2ζr)²), r = f / f_n.
double magnitude(double f_hz, const SensorDynamics& s) {
  const double r = f_hz / s.natural_frequency_hz;
  return 1.0 / std::sqrt((1 - r * r) * (1 - r * r) + 4 * s.damping_ratio * s.damping_ratio * r * r);
}

TEST(SensorDynamics, OneHarmonicOverAMeanIsScaledByTheResponseAtItsFrequency) {
  // w = 1 + a cos(2πk/N): the reading is 1 + a|H(f0)| cos(… − phase), its peak 1 + a|H(f0)|.
  for (const SensorDynamics sensor : {SensorDynamics{500.0, 0.38}, SensorDynamics{2000.0, 0.6}, SensorDynamics{150.0, 0.1}}) {
    for (const double f0 : {170.0, 340.0, 900.0}) {
      const double a = 0.5;
      std::vector<double> w(128);
      for (std::size_t k = 0; k < w.size(); ++k) w[k] = 1.0 + a * std::cos(kTwoPi * static_cast<double>(k) / 128.0);
      const double expected = (1.0 + a * magnitude(f0, sensor)) / (1.0 + a);
      EXPECT_NEAR(periodic_peak_gain(w, f0, sensor), expected, 1e-3 * expected)
          << "f_n " << sensor.natural_frequency_hz << " ζ " << sensor.damping_ratio << " f0 " << f0;
    }
  }
  EXPECT_EQ(periodic_peak_gain(std::vector<double>(64, 0.0), 170.0, {500.0, 0.4}), 1.0);
}

// A half-immersion straight cut with the sample tool at 2546 rpm (tooth frequency 170 Hz).
struct Cut {
  geometry::EngagementProfile profile;
  geometry::Tool tool;
};

Cut half_immersion() {
  Cut c;
  c.tool.diameter_mm = 10.0;
  c.tool.flutes = 4;
  c.tool.helix_deg = 35.0;
  geometry::Stock stock;
  stock.z_bottom_mm = -30;
  stock.regions.push_back({geometry::Contour::rectangle({0, -60}, {100, 0}), {}});
  geometry::ToolPath path;
  geometry::Move m;
  m.kind = geometry::MoveKind::kLine;
  m.start = {-10, 0, -10};
  m.end = {60, 0, -10};
  m.cutting = true;
  m.axial_depth_mm = 10;
  path.moves.push_back(m);
  c.profile = geometry::compute_engagement(path, stock, 5.0, {.ds_mm = 0.5});
  return c;
}

TEST(SensorDynamics, AStiffSensorReadsThePeakAsItIsAResonantOneDoesNotAndNoFactorExceedsTheCap) {
  const Cut cut = half_immersion();
  const auto stiff = sensor_peak_gains(cut.profile, cut.tool, 2546.0, {100000.0, 0.7});
  const auto resonant = sensor_peak_gains(cut.profile, cut.tool, 2546.0, {435.0, 0.38});
  int engaged = 0;
  for (std::size_t i = 0; i < cut.profile.samples.size(); ++i) {
    const auto& sample = cut.profile.samples[i];
    if (sample.layer_count == 0) {
      EXPECT_EQ(stiff[i], 1.0);
      EXPECT_EQ(resonant[i], 1.0);
      continue;
    }
    ++engaged;
    EXPECT_NEAR(stiff[i], 1.0, 2e-3) << "s " << sample.s_mm;
    EXPECT_GT(std::abs(resonant[i] - 1.0), 1e-3) << "s " << sample.s_mm;
    EXPECT_LE(resonant[i], kMaxSensorPeakGain) << "s " << sample.s_mm;
    const double uncapped = periodic_peak_gain(geometry::chip_load_waveform_mm(cut.profile, sample, cut.tool), 2546.0 * 4 / 60,
                                               {435.0, 0.38});
    EXPECT_DOUBLE_EQ(resonant[i], std::min(uncapped, kMaxSensorPeakGain));
  }
  EXPECT_GT(engaged, 80);
}

TEST(SensorDynamics, AModeThatIsNoModeIsNamed) {
  try {
    check_sensor_dynamics({-5.0, 3.0}, "--sensor-hz", "--sensor-damping");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.problems().size(), 2u);
    EXPECT_EQ(e.problems()[0].field, "--sensor-hz");
    EXPECT_EQ(e.problems()[1].field, "--sensor-damping");
    EXPECT_NE(e.problems()[1].message.find("(0, 2]"), std::string::npos);
  }
  EXPECT_NO_THROW(check_sensor_dynamics({435.0, 0.38}, "a", "b"));
}

}  // namespace
}  // namespace feedplan::learning
