// The factor a sensor's first mode puts on a periodic force's peak (learning/sensor_dynamics.hpp), against
// the closed form for one harmonic over a mean, and on real engagement: a sensor far above the tooth
// harmonics reads the peak as it is, a resonant one does not, and no factor from the chip's shape exceeds
// the cap; in a steady cut on a soft dynamometer, the mechanistic kernel's factor against what the virtual
// machine's dynamometer (a second-order filter stepped in time on first-principles forces) reads.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/chip_load.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/learning/sensor_dynamics.hpp"
#include "feedplan/sim/cutting_test.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"

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

// A straight cut a_e deep into the side of a block with the sample tool (down milling, a_p 10 mm).
Cut straight_cut(double radial_depth_mm, double helix_deg = 35.0) {
  Cut c;
  c.tool.diameter_mm = 10.0;
  c.tool.flutes = 4;
  c.tool.helix_deg = helix_deg;
  geometry::Stock stock;
  stock.z_bottom_mm = -30;
  stock.regions.push_back({geometry::Contour::rectangle({0, -60}, {100, radial_depth_mm - 5.0}), {}});
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

Cut half_immersion() { return straight_cut(5.0); }

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

// The median over the middle third of a cutting test's revolutions of the peak a dynamometer of bandwidth
// `bandwidth_hz` and damping ζ reads, over the true force's peak (the simulator's own, noise-free).
double simulated_peak_factor(const Cut& cut, double radial_depth_mm, double bandwidth_hz, double zeta, double rpm,
                             double feed_mm_per_min) {
  sim::SimulationRequest request;
  const sim::CuttingTest test{.radial_depth_mm = radial_depth_mm, .axial_depth_mm = 10.0, .feed_mm_per_min = feed_mm_per_min,
                              .spindle_rpm = rpm, .cut_length_mm = 40.0};
  const sim::CuttingTestSetup setup = sim::make_cutting_test(test, cut.tool);
  request.program = setup.program;
  request.stock = setup.stock;
  request.tool = cut.tool;
  request.coefficients = sim::load_materials(FEEDPLAN_SAMPLES_DIR "/../data/materials.yaml").get("S50C").coefficients;
  request.sensors.dynamometer = {bandwidth_hz, zeta, 0.0};
  const sim::SimulationResult run = sim::simulate(request);
  std::vector<double> t, fx, fy;
  for (const auto& row : run.log.rows) {
    t.push_back(row.t_s);
    fx.push_back(row.fx_n);
    fy.push_back(row.fy_n);
  }
  const std::vector<force_log::RevolutionPeak> read = force_log::revolution_peaks(t, fx, fy, rpm);
  const double largest = run.summary.max_revolution_peak_n;
  std::vector<double> ratios;
  for (const force_log::RevolutionPeak& truth : run.revolutions) {
    if (!(truth.peak_xy_n > 0.95 * largest)) continue;  // in the steady cut
    for (const force_log::RevolutionPeak& r : read) {
      if (std::abs(r.t_start_s - truth.t_start_s) < 1e-4) ratios.push_back(r.peak_xy_n / truth.peak_xy_n);
    }
  }
  if (ratios.size() < 6) return 0.0;
  std::sort(ratios.begin(), ratios.end());
  return ratios[ratios.size() / 2];
}

// A dynamometer of 400 Hz bandwidth, ζ 0.3 (its mode at 275 Hz), under a tooth frequency of 187 Hz, on cuts
// 1 and 1.5 mm deep (37° and 46° of engagement) with a 30° helix: the steady cut's true factor is far above
// the cap (1.24, 1.16), and the chip's shape overestimates it (1.29, 1.21), which would run the cut over the
// target. With the kernel the steady cut takes off more than the capped chip's shape, and less than the truth
// (1.12, 1.08: the smallest over the kernel's variants).
TEST(SensorDynamics, InTheSteadyCutTheKernelTakesOffMoreThanTheCapOnlyWhereItIsSure) {
  const double rpm = 2800.0, feed_mm_per_min = 336.0;  // f_z 0.03 mm
  const double bandwidth_hz = 400.0, zeta = 0.3;
  const double shape = 1.0 - 2.0 * zeta * zeta;
  const SensorDynamics sensor{bandwidth_hz / std::sqrt(shape + std::sqrt(shape * shape + 1.0)), zeta};
  const sim::CuttingCoefficients k = sim::load_materials(FEEDPLAN_SAMPLES_DIR "/../data/materials.yaml").get("S50C").coefficients;
  model::MechanisticModel kernel;
  kernel.ktc_n_per_mm2 = k.ktc_n_per_mm2;
  kernel.krc_n_per_mm2 = k.krc_n_per_mm2;
  kernel.kte_n_per_mm = k.kte_n_per_mm;
  kernel.kre_n_per_mm = k.kre_n_per_mm;
  for (const double radial_depth_mm : {1.0, 1.5}) {
    const Cut cut = straight_cut(radial_depth_mm, 30.0);
    const double truth = simulated_peak_factor(cut, radial_depth_mm, bandwidth_hz, zeta, rpm, feed_mm_per_min);
    ASSERT_GT(truth, 1.1) << "a_e " << radial_depth_mm;
    const std::vector<double> feeds(cut.profile.samples.size(), feed_mm_per_min);
    const std::vector<double> with_kernel = sensor_peak_gains(cut.profile, cut.tool, rpm, sensor, {&kernel, feeds});
    const std::vector<double> without = sensor_peak_gains(cut.profile, cut.tool, rpm, sensor);
    const std::vector<bool> steady =
        steady_engagement(cut.profile, std::vector<double>(cut.profile.samples.size(), kSteadySensorToothPeriods * 0.03));
    int steady_samples = 0;
    for (std::size_t i = 0; i < cut.profile.samples.size(); ++i) {
      const auto& sample = cut.profile.samples[i];
      if (sample.layer_count == 0) continue;
      const double chip_shape = periodic_peak_gain(geometry::chip_load_waveform_mm(cut.profile, sample, cut.tool),
                                                   rpm * 4 / 60, sensor);
      EXPECT_DOUBLE_EQ(without[i], std::min(chip_shape, kMaxSensorPeakGain)) << "s " << sample.s_mm;
      if (!steady[i]) {
        EXPECT_DOUBLE_EQ(with_kernel[i], without[i]) << "s " << sample.s_mm;
        continue;
      }
      ++steady_samples;
      EXPECT_GT(chip_shape, truth) << "a_e " << radial_depth_mm << " s " << sample.s_mm;
      EXPECT_GE(with_kernel[i], without[i]) << "a_e " << radial_depth_mm << " s " << sample.s_mm;
      EXPECT_LE(with_kernel[i], truth) << "a_e " << radial_depth_mm << " s " << sample.s_mm;
      EXPECT_GT(with_kernel[i], kMaxSensorPeakGain + 0.02) << "a_e " << radial_depth_mm << " s " << sample.s_mm;
    }
    EXPECT_GT(steady_samples, 60) << "a_e " << radial_depth_mm;
  }
}

// Steady: the engagement alike over the window and at both neighbours — not at the entry, and not anywhere
// when the window asked for is of another size than the profile.
TEST(SensorDynamics, TheEntryIsNotSteadyTheCutBehindItIs) {
  const Cut cut = half_immersion();
  const std::vector<bool> steady =
      steady_engagement(cut.profile, std::vector<double>(cut.profile.samples.size(), 0.06));
  for (std::size_t i = 0; i < cut.profile.samples.size(); ++i) {
    const auto& sample = cut.profile.samples[i];
    if (sample.s_mm < 10.0) {  // the tool enters the block at s = 5 mm, its engagement full at 10 mm
      EXPECT_FALSE(steady[i]) << "s " << sample.s_mm;
    } else if (sample.s_mm > 15.0 && sample.s_mm < 60.0) {
      EXPECT_TRUE(steady[i]) << "s " << sample.s_mm;
    }
  }
  EXPECT_TRUE(std::none_of(steady.begin(), steady.begin() + 5, [](bool b) { return b; }));
  const std::vector<bool> none = steady_engagement(cut.profile, {0.06});
  EXPECT_TRUE(std::none_of(none.begin(), none.end(), [](bool b) { return b; }));
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
