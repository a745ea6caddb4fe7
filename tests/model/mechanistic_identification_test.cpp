// Identifying the mechanistic coefficients (model/mechanistic_identification.hpp) from straight cutting
// tests run on the virtual machine with known coefficients (Al7075-T6, data/materials.yaml) and imported
// as a user would (model_db::import_cutting_test, which keeps the revolution-synchronous average). The
// truth is the simulator's coefficients; the log went through its dynamometer (3 kHz second-order low pass,
// 2 N noise) and the import's 2° bins, physics the identification does not model.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model_db/cutting_test_import.hpp"
#include "feedplan/sim/cutting_test.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::model {
namespace {

const geometry::Tool kTool{"SC EM D10 Z4", 10.0, 4, 30.0};
constexpr double kRpm = 2800;
constexpr double kAxialDepthMm = 5.0;

// Al7075-T6 (data/materials.yaml; Altintas, Manufacturing Automation, Table 2.1).
constexpr double kKtc = 796, kKrc = 169, kKac = 222, kKte = 27.7, kKre = 30.8, kKae = 1.4;

sim::CuttingCoefficients al7075() {
  sim::CuttingCoefficients k;
  k.ktc_n_per_mm2 = kKtc;
  k.krc_n_per_mm2 = kKrc;
  k.kac_n_per_mm2 = kKac;
  k.kte_n_per_mm = kKte;
  k.kre_n_per_mm = kKre;
  k.kae_n_per_mm = kKae;
  return k;
}

//! The dynamometer of the tests: a flat 3 kHz low pass with 2 N of noise.
const sim::DynamometerOptions kTwoNewtonNoise{3000.0, 0.7071067811865476, 2.0};

//! One down-milling test simulated with dynamometer noise and imported; as identification sees it.
MechanisticCuttingTest simulated_test(double radial_depth_mm, double feed_per_tooth_mm, unsigned seed,
                                      const std::vector<double>& runout_mm = {}, double true_helix_deg = kTool.helix_deg,
                                      double size_exponent = 0.0, sim::DynamometerOptions dynamometer = kTwoNewtonNoise,
                                      double* measured_mean_peak_n = nullptr) {
  geometry::Tool machine_tool = kTool;  // the flutes the machine cuts with; identification knows kTool only
  machine_tool.helix_deg = true_helix_deg;
  sim::CuttingTest test;
  test.radial_depth_mm = radial_depth_mm;
  test.axial_depth_mm = kAxialDepthMm;
  test.feed_mm_per_min = feed_per_tooth_mm * kTool.flutes * kRpm;
  test.spindle_rpm = kRpm;
  test.cut_length_mm = 200.0;
  test.mode = sim::MillingMode::kDown;
  const sim::CuttingTestSetup setup = sim::make_cutting_test(test, kTool);
  sim::SimulationRequest request;
  request.program = setup.program;
  request.stock = setup.stock;
  request.tool = machine_tool;
  request.coefficients = al7075();
  request.coefficients.size_exponent = size_exponent;
  request.coefficients.size_reference_chip_mm = 0.1;
  request.machine.max_accel_mm_per_s2 = 2000;
  request.sensors.dynamometer = dynamometer;
  request.sensors.seed = seed;
  request.options.runout_mm = runout_mm;
  const sim::SimulationResult result = sim::simulate(request);

  model_db::CuttingTestConditions c;
  c.tool_name = kTool.name;
  c.material_name = "Al7075-T6";
  c.spindle_rpm = kRpm;
  c.feed_mm_per_min = test.feed_mm_per_min;
  c.radial_depth_mm = radial_depth_mm;
  c.axial_depth_mm = kAxialDepthMm;
  c.mode = model_db::CutMode::kDown;
  const model_db::CuttingTestRecord record = model_db::import_cutting_test(result.log, c, kTool);

  MechanisticCuttingTest t;
  t.cutter = {kTool.diameter_mm / 2, kTool.flutes, kTool.helix_deg};
  t.arc = straight_cut_arc(StraightCutSide::kDown, radial_depth_mm, t.cutter.radius_mm);
  t.axial_depth_mm = kAxialDepthMm;
  t.feed_per_tooth_mm = record.feed_per_tooth_mm;
  t.synchronous_fx_n = record.synchronous_fx_n;
  t.synchronous_fy_n = record.synchronous_fy_n;
  if (measured_mean_peak_n) {
    t.revolution_peaks_n = record.steady_peaks_n;
    *measured_mean_peak_n = record.peak_mean_n;
  }
  t.name = "a_e " + std::to_string(radial_depth_mm).substr(0, 3) + " f_z " + std::to_string(feed_per_tooth_mm).substr(0, 4);
  return t;
}

void print(const MechanisticIdentification& r) {
  const double truth[4] = {kKtc, kKrc, kKte, kKre};
  const double fitted[4] = {r.model.ktc_n_per_mm2, r.model.krc_n_per_mm2, r.model.kte_n_per_mm, r.model.kre_n_per_mm};
  const char* names[4] = {"K_tc", "K_rc", "K_te", "K_re"};
  for (int i = 0; i < 4; ++i) {
    std::printf("  %s fitted %8.2f ± %6.2f  true %7.1f  (%+.2f %%)\n", names[i], fitted[i],
                std::sqrt(r.covariance[i][i]), truth[i], 100 * (fitted[i] - truth[i]) / truth[i]);
  }
  std::printf("  rms residual %.2f N, condition number %.1f\n", r.rms_residual_n, r.condition_number);
  for (std::size_t i = 0; i < r.phase_rad.size(); ++i) {
    std::printf("  test %zu: phase %.2f deg, rms %.2f N\n", i, r.phase_rad[i] * 180 / 3.14159265358979, r.test_rms_residual_n[i]);
  }
  for (double runout : r.model.runout_mm) std::printf("  runout %.2f µm\n", 1000 * runout);
  if (!r.runout_report.empty()) std::printf("  %s\n", r.runout_report.c_str());
  for (const auto& u : r.unidentifiable) std::printf("  cannot identify: %s\n", u.c_str());
}

// Two radial depths × two feeds (f_z 0.05 and 0.15 mm, 3× apart), 200 mm cuts. Tolerances: K_tc 1 %, the
// others 3 %. The largest error is not the dynamometer's low pass (a pure delay to the tooth harmonics,
// absorbed by the phase) nor the 3.4° bins (the kernel is averaged over the same bins), but the import's
// steady revolutions: a few of them still have the tool entering or leaving the block, which pulls the
// half-immersion tests' mean Fx 1-3 % low. The error halves from 100 mm to 200 mm cuts (K_rc +2.2 % →
// +1.1 %, K_te −2.2 % → −1.2 %); the 2 N noise, averaged over ~200 revolutions, adds little.
TEST(MechanisticIdentification, RecoversAl7075FromFourSimulatedTests) {
  const std::vector<MechanisticCuttingTest> tests = {simulated_test(2.0, 0.05, 1), simulated_test(2.0, 0.15, 2),
                                                     simulated_test(5.0, 0.05, 3), simulated_test(5.0, 0.15, 4)};
  const MechanisticIdentification r = identify_mechanistic(tests);
  print(r);
  EXPECT_EQ(r.status, IdentificationStatus::kIdentified);
  EXPECT_NEAR(r.model.ktc_n_per_mm2, kKtc, 0.01 * kKtc);
  EXPECT_NEAR(r.model.krc_n_per_mm2, kKrc, 0.03 * kKrc);
  EXPECT_NEAR(r.model.kte_n_per_mm, kKte, 0.03 * kKte);
  EXPECT_NEAR(r.model.kre_n_per_mm, kKre, 0.03 * kKre);
  EXPECT_LT(r.rms_residual_n, 3.0);  // of forces up to ~600 N
  EXPECT_EQ(r.model.kac_n_per_mm2, 0.0);
  ASSERT_EQ(r.unidentifiable.size(), 1u);
  EXPECT_NE(r.unidentifiable[0].find("K_ac, K_ae"), std::string::npos);
}

// Runout {6, 0, 0, 0} µm on the same four tests: the runout is recovered within 1.5 µm, up to the tooth
// numbering (no encoder: the fit numbers the teeth from its own phase, so the truth is compared at the best
// rotation of the tooth numbers), and the coefficients within 3 % as without runout.
TEST(MechanisticIdentification, RecoversRunoutWithTheCoefficients) {
  const std::vector<double> runout{0.006, 0.0, 0.0, 0.0};
  const std::vector<MechanisticCuttingTest> tests = {
      simulated_test(2.0, 0.05, 11, runout), simulated_test(2.0, 0.15, 12, runout),
      simulated_test(5.0, 0.05, 13, runout), simulated_test(5.0, 0.15, 14, runout)};
  MechanisticIdentificationOptions options;
  options.identify_runout = true;
  const MechanisticIdentification r = identify_mechanistic(tests, options);
  print(r);
  EXPECT_TRUE(r.runout_converged);
  ASSERT_EQ(r.model.runout_mm.size(), 4u);
  double best = 1e9;
  for (int shift = 0; shift < 4; ++shift) {
    double worst = 0.0;
    for (int j = 0; j < 4; ++j) worst = std::max(worst, std::abs(r.model.runout_mm[static_cast<std::size_t>((j + shift) % 4)] - runout[static_cast<std::size_t>(j)]));
    best = std::min(best, worst);
  }
  std::printf("  largest runout error at the best tooth numbering: %.2f µm\n", 1000 * best);
  EXPECT_LT(best, 0.0015);
  EXPECT_NEAR(r.model.ktc_n_per_mm2, kKtc, 0.01 * kKtc);
  EXPECT_NEAR(r.model.krc_n_per_mm2, kKrc, 0.03 * kKrc);
  EXPECT_NEAR(r.model.kte_n_per_mm, kKte, 0.03 * kKte);
  EXPECT_NEAR(r.model.kre_n_per_mm, kKre, 0.03 * kKre);
}

// A helix 5° shallower than the catalogue says (25° cut, 30° in the tool record), with 4 µm of runout on one
// tooth: the helix is recovered within 0.5° from the width of the teeth's pulses, the runout within 1.5 µm
// and the coefficients within 3 % as before. Kept at the catalogue's 30°, the fit is off: the check that
// identifying the helix is what recovers them.
TEST(MechanisticIdentification, RecoversAHelixOffTheCatalogueWithTheRunout) {
  const std::vector<double> runout{0.004, 0.0, 0.0, 0.0};
  const std::vector<MechanisticCuttingTest> tests = {
      simulated_test(1.0, 0.05, 21, runout, 25.0), simulated_test(1.0, 0.15, 22, runout, 25.0),
      simulated_test(5.0, 0.05, 23, runout, 25.0), simulated_test(5.0, 0.15, 24, runout, 25.0)};
  MechanisticIdentificationOptions options;
  options.identify_runout = true;
  options.identify_helix = true;
  const MechanisticIdentification r = identify_mechanistic(tests, options);
  print(r);
  EXPECT_TRUE(r.runout_converged);
  ASSERT_TRUE(r.model.helix_deg.has_value());
  std::printf("  helix %.2f deg (true 25, catalogue 30)\n", *r.model.helix_deg);
  EXPECT_NEAR(*r.model.helix_deg, 25.0, 0.5);
  double largest_runout = *std::max_element(r.model.runout_mm.begin(), r.model.runout_mm.end());
  EXPECT_NEAR(largest_runout, 0.004, 0.0015);
  EXPECT_NEAR(r.model.ktc_n_per_mm2, kKtc, 0.03 * kKtc);
  EXPECT_NEAR(r.model.krc_n_per_mm2, kKrc, 0.03 * kKrc);
  EXPECT_NEAR(r.model.kte_n_per_mm, kKte, 0.03 * kKte);
  EXPECT_NEAR(r.model.kre_n_per_mm, kKre, 0.03 * kKre);

  options.identify_helix = false;
  const MechanisticIdentification catalogue = identify_mechanistic(tests, options);
  std::printf("  with the catalogue helix: rms residual %.2f N (identified helix: %.2f N)\n", catalogue.rms_residual_n,
              r.rms_residual_n);
  EXPECT_FALSE(catalogue.model.helix_deg.has_value());
  EXPECT_GT(catalogue.rms_residual_n, 2.0 * r.rms_residual_n);
}

// A size effect m = 0.25 (Al7075's coefficients holding at a 0.1 mm chip), with 3 µm of runout on one tooth,
// on two radial depths × three feeds: the exponent is recovered within 0.04 and the cutting coefficients, taken
// to the fit's reference chip by the true exponent, within 3 % (the edge coefficients 10 %: they trade against
// the exponent at the thinnest chips). Without the size effect the fit's residual is at least twice as large.
TEST(MechanisticIdentification, RecoversASizeEffectWithTheRunout) {
  const std::vector<double> runout{0.003, 0.0, 0.0, 0.0};
  constexpr double kExponent = 0.25;
  std::vector<MechanisticCuttingTest> tests;
  unsigned seed = 31;
  for (double ae : {2.0, 5.0}) {
    for (double fz : {0.03, 0.08, 0.2}) tests.push_back(simulated_test(ae, fz, seed++, runout, kTool.helix_deg, kExponent));
  }
  MechanisticIdentificationOptions options;
  options.identify_runout = true;
  options.identify_size_effect = true;
  const MechanisticIdentification r = identify_mechanistic(tests, options);
  std::printf("  size effect m %.3f at h_ref %.4f mm (true %.2f at 0.1 mm)\n", r.model.size_exponent,
              r.model.size_reference_chip_mm, kExponent);
  EXPECT_NEAR(r.model.size_exponent, kExponent, 0.04);
  const double to_reference = std::pow(r.model.size_reference_chip_mm / 0.1, -kExponent);
  std::printf("  K_tc %.1f (true %.1f), K_rc %.1f (true %.1f), K_te %.2f (true %.2f), K_re %.2f (true %.2f)\n",
              r.model.ktc_n_per_mm2, kKtc * to_reference, r.model.krc_n_per_mm2, kKrc * to_reference,
              r.model.kte_n_per_mm, kKte, r.model.kre_n_per_mm, kKre);
  EXPECT_NEAR(r.model.ktc_n_per_mm2, kKtc * to_reference, 0.03 * kKtc * to_reference);
  EXPECT_NEAR(r.model.krc_n_per_mm2, kKrc * to_reference, 0.03 * kKrc * to_reference);
  EXPECT_NEAR(r.model.kte_n_per_mm, kKte, 0.1 * kKte);
  EXPECT_NEAR(r.model.kre_n_per_mm, kKre, 0.1 * kKre);

  options.identify_size_effect = false;
  const MechanisticIdentification plain = identify_mechanistic(tests, options);
  std::printf("  without the size effect: rms residual %.2f N (with: %.2f N)\n", plain.rms_residual_n, r.rms_residual_n);
  EXPECT_EQ(plain.model.size_exponent, 0.0);
  EXPECT_GT(plain.rms_residual_n, 2.0 * r.rms_residual_n);
}

// Both tests at f_z 0.1 mm: cutting and edge terms differ only in the pulse's shape. The fit still
// lands near the truth on this clean simulated data (K_rc +3 %), but nothing but the shape supports it,
// so the result must say so.
TEST(MechanisticIdentification, OneFeedCannotSeparateCuttingFromEdge) {
  const std::vector<MechanisticCuttingTest> tests = {simulated_test(2.0, 0.1, 5), simulated_test(5.0, 0.1, 6)};
  const MechanisticIdentification r = identify_mechanistic(tests);
  print(r);
  EXPECT_EQ(r.status, IdentificationStatus::kIllConditioned);
  bool said = false;
  for (const auto& u : r.unidentifiable) said = said || u.find("cannot be separated by the feed") != std::string::npos;
  EXPECT_TRUE(said);
}

// The kernel's own force, bin-averaged at a known phase (1.234 rad): recovered to the last digits, and
// the phase modulo the tooth period (the force repeats every tooth without runout).
TEST(MechanisticIdentification, KernelForcesAtAKnownPhaseAreRecovered) {
  MechanisticModel truth;
  truth.ktc_n_per_mm2 = kKtc;
  truth.krc_n_per_mm2 = kKrc;
  truth.kte_n_per_mm = kKte;
  truth.kre_n_per_mm = kKre;
  constexpr double kPhase = 1.234;
  constexpr int kBins = 107;
  constexpr int kSubSteps = 16;
  const double pi = 3.14159265358979323846;
  std::vector<MechanisticCuttingTest> tests;
  for (double ae : {2.0, 5.0}) {
    for (double fz : {0.05, 0.15}) {
      MechanisticCuttingTest t;
      t.cutter = {5.0, 4, 30.0};
      t.arc = straight_cut_arc(StraightCutSide::kDown, ae, 5.0);
      t.axial_depth_mm = 5;
      t.feed_per_tooth_mm = fz;
      const EngagedSection s{0.0, 5.0, std::span<const ImmersionArc>(&t.arc, 1)};
      for (int b = 0; b < kBins; ++b) {
        double fx = 0, fy = 0;
        for (int k = 0; k < kSubSteps; ++k) {
          const double angle = kPhase + 2 * pi * (b + (k + 0.5) / kSubSteps) / kBins;
          const auto f = predicted_force(truth, std::span<const EngagedSection>(&s, 1), t.cutter, fz, angle);
          fx += f.fx_n / kSubSteps;
          fy += f.fy_n / kSubSteps;
        }
        t.synchronous_fx_n.push_back(fx);
        t.synchronous_fy_n.push_back(fy);
      }
      tests.push_back(t);
    }
  }
  const MechanisticIdentification r = identify_mechanistic(tests);
  print(r);
  EXPECT_EQ(r.status, IdentificationStatus::kIdentified);
  // The identification averages 4 sub-steps per bin, the truth 16: a 1e-3 difference at most.
  EXPECT_NEAR(r.model.ktc_n_per_mm2, kKtc, 1e-3 * kKtc);
  EXPECT_NEAR(r.model.krc_n_per_mm2, kKrc, 1e-3 * kKrc);
  EXPECT_NEAR(r.model.kte_n_per_mm, kKte, 1e-3 * kKte);
  EXPECT_NEAR(r.model.kre_n_per_mm, kKre, 1e-3 * kKre);
  for (double phase : r.phase_rad) {
    const double tooth = pi / 2;
    const double off = std::remainder(phase - kPhase, tooth);
    EXPECT_NEAR(off, 0.0, 0.1 * pi / 180);
  }
}

//! Four tests (a_e 2 and 5 mm × f_z 0.05 and 0.15 mm) read by `dynamometer`, identified with their peaks matched
//! and from the bins alone, and a fifth between them (a_e 3.5 mm, f_z 0.1 mm) held out: the errors of both
//! predictions of its measured mean per-revolution peak — the simulator's reading, not the kernel's.
struct HeldOutReading {
  MechanisticIdentification matched, alone;
  double measured_n = 0.0, matched_error = 0.0, alone_error = 0.0, mean_fitted_peak_n = 0.0;
};
HeldOutReading held_out_reading(const sim::DynamometerOptions& dynamometer) {
  std::vector<MechanisticCuttingTest> tests;
  HeldOutReading r;
  unsigned seed = 11;
  for (double ae : {2.0, 5.0}) {
    for (double fz : {0.05, 0.15}) {
      double peak_n = 0.0;
      tests.push_back(simulated_test(ae, fz, seed++, {}, kTool.helix_deg, 0.0, dynamometer, &peak_n));
      r.mean_fitted_peak_n += peak_n / 4;
    }
  }
  simulated_test(3.5, 0.10, 21, {}, kTool.helix_deg, 0.0, dynamometer, &r.measured_n);
  MechanisticIdentificationOptions bins_alone;
  bins_alone.match_peaks = false;
  r.alone = identify_mechanistic(tests, bins_alone);
  r.matched = identify_mechanistic(tests);
  const CutterGeometry cutter{kTool.diameter_mm / 2, kTool.flutes, kTool.helix_deg};
  const ImmersionArc arc = straight_cut_arc(StraightCutSide::kDown, 3.5, cutter.radius_mm);
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
  const auto error = [&](const MechanisticModel& m) {
    return predicted_peak_force_n(m, std::span<const EngagedSection>(&section, 1), cutter, 0.10) / r.measured_n - 1;
  };
  r.matched_error = error(r.matched.model);
  r.alone_error = error(r.alone.model);
  std::printf("held out a_e 3.5 f_z 0.10: measured mean peak %.1f N; error %+.2f %% with the peaks matched, %+.2f %% "
              "from the bins alone; bins RMS residual %.2f N alone, %.2f N matched; peaks met within %.2f N RMS\n",
              r.measured_n, 100 * r.matched_error, 100 * r.alone_error, r.matched.rms_residual_n,
              r.matched.matched_rms_residual_n, r.matched.peak_rms_residual_n);
  return r;
}

// A dynamometer that rings (a 700 Hz mode, ζ 0.05, against tooth pulses at 187 Hz whose 4th harmonic lies
// near it): the reading's peaks hold the ringing, which the kernel does not model, and the bins show it as a
// large residual. The peaks then decide: the held-out reading is predicted within 4 %, and from the bins
// alone it comes out more than twice as far off.
TEST(MechanisticIdentification, MatchedPeaksPredictARingingSensorsReadings) {
  const HeldOutReading r = held_out_reading({700.0, 0.05, 2.0});
  EXPECT_EQ(r.matched.tests_peak_matched, 4);
  EXPECT_EQ(r.alone.tests_peak_matched, 0);
  EXPECT_LT(std::abs(r.matched_error), 0.04);
  EXPECT_GT(std::abs(r.alone_error), 2 * std::abs(r.matched_error));
}

// A dynamometer with 25 N of noise but no ringing: each revolution's peak is the largest of many noisy samples
// near the tooth's peak, so the mean per-revolution peak lies above the peak of the synchronous average. The
// kernel explains the bins to within their noise, so they outweigh the four peaks: the coefficients stay
// within 1 % of the bins' own (the noise's excess is the sensor's, not the force's), and both predictions of
// the held-out reading lie under it by the same excess.
TEST(MechanisticIdentification, PeaksDoNotOverruleBinsTheKernelExplains) {
  const HeldOutReading r = held_out_reading({3000.0, 0.7071067811865476, 25.0});
  EXPECT_EQ(r.matched.tests_peak_matched, 4);
  EXPECT_NEAR(r.matched.model.ktc_n_per_mm2, r.alone.model.ktc_n_per_mm2, 0.01 * r.alone.model.ktc_n_per_mm2);
  EXPECT_NEAR(r.matched_error, r.alone_error, 0.005);
  EXPECT_LT(r.alone_error, -0.02);
}

TEST(MechanisticIdentification, StraightCutArcs) {
  const double pi = 3.14159265358979323846;
  // a_e = r: a quarter of the circle; a_e = r/2: acos(1/2) = 60°.
  EXPECT_NEAR(straight_cut_arc(StraightCutSide::kDown, 5.0, 5.0).entry_rad, pi / 2, 1e-12);
  EXPECT_NEAR(straight_cut_arc(StraightCutSide::kDown, 5.0, 5.0).exit_rad, pi, 1e-12);
  EXPECT_NEAR(straight_cut_arc(StraightCutSide::kUp, 2.5, 5.0).exit_rad, pi / 3, 1e-12);
  EXPECT_NEAR(straight_cut_arc(StraightCutSide::kUp, 2.5, 5.0).entry_rad, 0.0, 1e-12);
  EXPECT_NEAR(straight_cut_arc(StraightCutSide::kSlot, 10.0, 5.0).exit_rad, pi, 1e-12);
}

TEST(MechanisticIdentification, BadTestsAreNamed) {
  MechanisticCuttingTest t;
  t.arc = {1.0, 0.5};
  t.axial_depth_mm = -1;
  t.feed_per_tooth_mm = 0.1;
  t.synchronous_fx_n = std::vector<double>(10, 1.0);
  t.synchronous_fy_n = std::vector<double>(9, 1.0);
  try {
    identify_mechanistic({t});
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("tests[0].arc"), std::string::npos) << text;
    EXPECT_NE(text.find("tests[0].axial_depth_mm"), std::string::npos) << text;
    EXPECT_NE(text.find("tests[0].synchronous_fy_n"), std::string::npos) << text;
  }
  EXPECT_THROW(identify_mechanistic({}), InputError);
  MechanisticCuttingTest bad_peak;
  bad_peak.arc = {2.0, 3.0};
  bad_peak.axial_depth_mm = 5;
  bad_peak.feed_per_tooth_mm = 0.1;
  bad_peak.synchronous_fx_n = bad_peak.synchronous_fy_n = std::vector<double>(16, 1.0);
  bad_peak.revolution_peaks_n = {300.0, -2.0};
  const auto peak_problems = validate({bad_peak});
  ASSERT_EQ(peak_problems.size(), 1u);
  EXPECT_EQ(peak_problems[0].field, "tests[0].revolution_peaks_n[1]");

  // Runout needs one cutter for all tests.
  MechanisticCuttingTest a;
  a.arc = {2.0, 3.0};
  a.axial_depth_mm = 5;
  a.feed_per_tooth_mm = 0.1;
  a.synchronous_fx_n = a.synchronous_fy_n = std::vector<double>(16, 1.0);
  MechanisticCuttingTest b = a;
  b.cutter.flutes = 3;
  const auto problems = validate({a, b}, true);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].field, "tests[1].cutter.flutes");
  EXPECT_NE(problems[0].message.find("one cutter for all tests, and the first has 4"), std::string::npos)
      << problems[0].message;
  EXPECT_TRUE(validate({a, b}, false).empty());
}

}  // namespace
}  // namespace feedplan::model
