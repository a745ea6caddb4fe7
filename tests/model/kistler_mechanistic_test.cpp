// Real data: leave-one-feed-out prediction of the per-revolution peak with the mechanistic model on the
// three Kistler slot recordings (tests/data/kistler_full/README.md: 2 flutes, full slot, a_p 3 mm,
// 6000 rpm, f_z 0.025 / 0.075 / 0.125 mm; tool diameter, helix and material not stated). For each held-out
// feed the coefficients are identified (identify_mechanistic, with and without identify_runout, and in 6.
// with identify_sensor) from the other two recordings as the cutting-test import keeps them
// (model_db::import_cutting_test: the steady per-revolution peaks and the revolution-synchronous average),
// the held-out feed's peak is predicted with its mechanistic_peak_interval (in 6. the sensed peak's
// mechanistic_sensed_peak_interval; spread pooled from the two fitting recordings' per-revolution peaks),
// and both are compared with the held-out recording's measured mean per-revolution peak.
//
// The product owner's acceptance: within ±8 % for every held-out feed, and the interval covers the
// measured mean. It is met when the coefficients are fitted to the bins of the synchronous averages and the
// tests' mean per-revolution peaks together, with runout (match_peaks, as `feedplan db fit` identifies): +5.4,
// −1.4 and −2.0 % with the assumed tool, within ±6 % over the plausible tools (2.). From the bins alone it is
// met only for f_z 0.025 mm: the bins show how the force is shaped over the revolution, but the peaks a
// dynamometer reads at every revolution are not the peak of the average (3.); the tests' own peaks say by how
// much, and that carries from two feeds to the third. What the data show, each asserted below:
//   1. Frame. The recorded force turns the other way round than the kernel's (the tooth-frequency part
//      of Fx + iFy turns counter-clockwise, the kernel's clockwise): the dynamometer's XY frame is the
//      mirror image of the feed frame (x along the feed, y to its left, seen from above), e.g. Kistler's Z
//      pointing down. Fy is negated before import. Which axis is the feed does not matter for a peak of
//      |F_xy|: a rotation of the frame is a linear map of (K_tc, K_rc) and of (K_te, K_re), so the fit
//      absorbs it (the coefficients may then come out negative; only their combination is physical here).
//      Turned by 90° — x and y of the recording swapped, which is also a mirror — the in-band fits below
//      with runout give K_tc 810–1020, K_rc 240–410 N/mm², K_te 18–32, K_re 16–22 N/mm, all positive and of
//      textbook ratios, as do the mean forces (from 300 to 900 mm/min the recorded mean Fx grows 2.3× faster
//      than Fy, as the force across a slot does, ∝ K_tc): the recording's X looks to be across the feed, not
//      along it as the source says.
//   2. Tool. In a slot the force depends on the radius r and helix β only through the helix lag over the
//      depth, ψ = a_p·tan β / r: along a flute dz = r dφ / tan β, so F = (a_p/ψ)·∫ over an immersion span
//      ψ, and the chip f_z sin φ (+ runout) does not involve r. So one number is unknown; the tests assume
//      D10, 30° as the other Kistler tests do (ψ = 0.346 rad) and repeat everything over D16 20° … D6 45°
//      (ψ = 0.136 … 1.0 rad), where the conclusions hold (with bins, peaks and runout the f_z 0.025 mm
//      prediction moves from +5.6 % to −5.5 %, the others stay within −0.6 … −2.0 %).
//   3. Why 0.075 and 0.125 mm fail from the bins alone: the recordings ring. The recorded force has harmonics rising towards
//      800 Hz in Fx and 1 kHz in Fy (lateral modes of the dynamometer with the workpiece; a slot's cutting
//      force, and the kernel's, fall off above the 200 Hz tooth frequency; 6. and 7.). They ring at every
//      tooth pulse, and the
//      per-revolution peaks hold the ringing: they exceed the peaks of the same signals restricted to the
//      mean, once- and twice-per-revolution parts by 10, 31 and 53 % at the three feeds. The kernel has no
//      sensor dynamics: it comes out −27 % and −37 % under the measured mean peak with runout, −42 % and
//      −44 % without. With the ringing removed (all three recordings in band, and the kernel's force restricted
//      to the same harmonics) the same leave-one-out with runout is +3.5 %, −3.8 % and +10.4 %: 0.125 mm,
//      extrapolated from 0.025 and 0.075 mm, is over-predicted, the sign of a size effect (the cutting
//      coefficient falling with the chip), which identification does not fit and two feeds could not tell
//      from the edge terms. The 1500 mm/min run's unsteadiness is in the ringing too: its peaks scatter by
//      9.9 % measured, 1.2 % in band.
//   4. Runout. The teeth differ by 20–30 µm (as much as f_z at 300 mm/min, where one tooth does most of the
//      cutting): without identify_runout the in-band errors are −31 %, −24 % and 0 %.
//   5. Interval. From the bins alone the coefficient covariance measures the noise of the fit, not the bias
//      above (ringing, size effect); the spread is 1.3 % for the two steady recordings and 7 % with the
//      1500 mm/min one. So the interval covers 0.025 mm (its spread comes from the fitting pair with
//      1500 mm/min) and misses the others. With the peaks matched the bias is gone and every interval covers.
//   6. The dynamometer's modes (sensor_response.hpp), identified with the coefficients and runout
//      (identify_sensor), lie where the spectra ring — about 790 Hz along x and 1000 Hz along y — and where the
//      recordings vibrate between the revolution's harmonics; through them the held-out 0.075 mm is predicted
//      at −4 %, but 0.025 mm at +94 % and 0.125 mm at −34 %.
//   7. Why: what rings is not a linear response to the kernel's force. The harmonics that drive the modes grow
//      with the feed far faster than the force at the tooth frequency, while the kernel's grow not at all in a
//      slot (there only the edge terms and runout make them), and the modes vibrate at the larger feeds also
//      without the revolution's period: a structure with these modes looks to take part in the cut.
// 3. to 7. are about the bins alone (match_peaks off): what the shape of the force can and cannot tell.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model/prediction_interval.hpp"
#include "feedplan/model/revolution_spread.hpp"
#include "feedplan/model/sensor_response.hpp"
#include "feedplan/model_db/cutting_test_import.hpp"

namespace feedplan::model {
namespace {

using Complex = std::complex<double>;
constexpr double kPi = 3.14159265358979323846;
constexpr double kRpm = 6000;
constexpr double kAxialDepthMm = 3.0;
constexpr int kFlutes = 2;
//! The recordings' spectra resolve the revolution frequency (100 Hz); the tooth frequency is its 2nd
//! harmonic. In band: the mean, once- and twice-per-revolution parts — at most a quarter of the lowest
//! mode (800 Hz), where a second-order sensor amplifies by at most 1/(1 − 1/16) = 1.07.
constexpr int kInBandHarmonics = 2;
constexpr double kAcceptance = 0.08;

struct Recording {
  const char* file;
  double feed_mm_per_min;
  double feed_per_tooth_mm;
  double mean_peak_n;  //!< over all 100 revolutions, worked out independently (tests/data/kistler_full/README.md)
};
const Recording kRecordings[3] = {{"n6000_f300_ap3.csv", 300, 0.025, 245.4},
                                  {"n6000_f900_ap3.csv", 900, 0.075, 495.4},
                                  {"n6000_f1500_ap3.csv", 1500, 0.125, 761.2}};

//! Assumed tools: D10 30° (ψ = 0.346 rad, as the other Kistler tests), and the ends of a plausible range.
const CutterGeometry kAssumedTool{5.0, kFlutes, 30.0};
const CutterGeometry kTools[3] = {{8.0, kFlutes, 20.0}, kAssumedTool, {3.0, kFlutes, 45.0}};

double helix_lag_rad(const CutterGeometry& c) { return kAxialDepthMm * std::tan(c.helix_deg * kPi / 180) / c.radius_mm; }

force_log::ForceLog as_recorded(const Recording& r) {
  return force_log::load_force_log(std::string(FEEDPLAN_TEST_DATA_DIR) + "/kistler_full/" + r.file);
}

//! The log in the feed frame: Fy mirrored (see 1. above).
force_log::ForceLog in_feed_frame(force_log::ForceLog log) {
  for (auto& row : log.rows) row.fy_n = -row.fy_n;
  return log;
}

std::vector<Complex> complex_force(const force_log::ForceLog& log) {
  std::vector<Complex> z;
  for (const auto& row : log.rows) z.emplace_back(row.fx_n, row.fy_n);
  return z;
}

std::vector<force_log::RevolutionPeak> revolutions(const force_log::ForceLog& log) {
  std::vector<double> t, fx, fy;
  for (const auto& row : log.rows) {
    t.push_back(row.t_s);
    fx.push_back(row.fx_n);
    fy.push_back(row.fy_n);
  }
  return force_log::revolution_peaks(t, fx, fy, kRpm);
}

//! The log with each complete revolution's force reduced to its harmonics |k| ≤ kInBandHarmonics of the
//! revolution (a Fourier series over that revolution's samples); samples outside complete revolutions are
//! dropped.
force_log::ForceLog in_band(const force_log::ForceLog& log) {
  force_log::ForceLog out = log;
  out.rows.clear();
  std::size_t i = 0;
  for (const force_log::RevolutionPeak& rev : revolutions(log)) {
    while (i < log.rows.size() && log.rows[i].t_s < rev.t_start_s) ++i;
    std::size_t end = i;
    while (end < log.rows.size() && log.rows[end].t_s < rev.t_end_s) ++end;
    const double period_s = rev.t_end_s - rev.t_start_s;
    std::vector<Complex> c(2 * kInBandHarmonics + 1);
    for (int k = -kInBandHarmonics; k <= kInBandHarmonics; ++k) {
      for (std::size_t j = i; j < end; ++j) {
        c[k + kInBandHarmonics] += Complex(log.rows[j].fx_n, log.rows[j].fy_n) *
                                   std::polar(1.0, -2 * kPi * k * (log.rows[j].t_s - rev.t_start_s) / period_s);
      }
      c[k + kInBandHarmonics] /= static_cast<double>(end - i);
    }
    for (std::size_t j = i; j < end; ++j) {
      Complex z = 0;
      for (int k = -kInBandHarmonics; k <= kInBandHarmonics; ++k) {
        z += c[k + kInBandHarmonics] * std::polar(1.0, 2 * kPi * k * (log.rows[j].t_s - rev.t_start_s) / period_s);
      }
      force_log::ForceLogRow row = log.rows[j];
      row.fx_n = z.real();
      row.fy_n = z.imag();
      out.rows.push_back(row);
    }
    i = end;
  }
  return out;
}

//! Harmonic k of the revolution (k > 0: turning counter-clockwise in the log's XY frame) of a periodic
//! signal sampled at n equal steps over one revolution, N.
Complex harmonic(const std::vector<Complex>& z, int k) {
  Complex sum = 0;
  for (std::size_t b = 0; b < z.size(); ++b) sum += z[b] * std::polar(1.0, -2 * kPi * k * static_cast<double>(b) / z.size());
  return sum / static_cast<double>(z.size());
}

//! Amplitude of harmonic k (> 0) of one real channel.
double channel_amplitude(const std::vector<double>& x, int k) {
  std::vector<Complex> z(x.begin(), x.end());
  return 2 * std::abs(harmonic(z, k));
}

model_db::CuttingTestRecord import(const force_log::ForceLog& log, const Recording& r, const CutterGeometry& cutter) {
  const geometry::Tool tool{"assumed (not stated in the source)", 2 * cutter.radius_mm, cutter.flutes, cutter.helix_deg};
  model_db::CuttingTestConditions c;
  c.tool_name = tool.name;
  c.material_name = "not stated";
  c.spindle_rpm = kRpm;
  c.feed_mm_per_min = r.feed_mm_per_min;
  c.radial_depth_mm = tool.diameter_mm;
  c.axial_depth_mm = kAxialDepthMm;
  c.mode = model_db::CutMode::kSlot;
  model_db::CuttingTestImportOptions options;
  options.source_name = r.file;
  return model_db::import_cutting_test(log, c, tool, options);
}

MechanisticCuttingTest cutting_test(const model_db::CuttingTestRecord& record, const CutterGeometry& cutter,
                                    const std::string& name) {
  MechanisticCuttingTest t;
  t.cutter = cutter;
  t.arc = straight_cut_arc(StraightCutSide::kSlot, 2 * cutter.radius_mm, cutter.radius_mm);
  t.axial_depth_mm = kAxialDepthMm;
  t.feed_per_tooth_mm = record.feed_per_tooth_mm;
  t.synchronous_fx_n = record.synchronous_fx_n;
  t.synchronous_fy_n = record.synchronous_fy_n;
  t.name = name;
  t.spindle_rpm = kRpm;
  t.revolution_peaks_n = record.steady_peaks_n;
  return t;
}

//! Which signal the peaks are taken of.
enum class Band { kMeasured, kInBand };

//! One held-out feed's prediction.
struct HeldOut {
  MechanisticIdentification identification;
  PredictionInterval interval;
  double measured_n = 0.0;  //!< the held-out recording's mean per-revolution peak
  double error() const { return (interval.predicted_n - measured_n) / measured_n; }
  bool covered() const { return measured_n >= interval.lower_n && measured_n <= interval.upper_n; }
};

const force_log::ForceLog& feed_frame_log(int recording, Band band) {
  static std::map<std::pair<int, Band>, force_log::ForceLog> logs;
  const auto key = std::make_pair(recording, band);
  if (!logs.count(key)) {
    const force_log::ForceLog log = in_feed_frame(as_recorded(kRecordings[recording]));
    logs[key] = band == Band::kMeasured ? log : in_band(log);
  }
  return logs[key];
}

const model_db::CuttingTestRecord& record(int recording, Band band, int tool) {
  static std::map<std::tuple<int, Band, int>, model_db::CuttingTestRecord> records;
  const auto key = std::make_tuple(recording, band, tool);
  if (!records.count(key)) records[key] = import(feed_frame_log(recording, band), kRecordings[recording], kTools[tool]);
  return records[key];
}

//! What the coefficients are fitted to: the bins of the synchronous averages alone, or also the tests' mean
//! per-revolution peaks (MechanisticIdentificationOptions::match_peaks, as `feedplan db fit` identifies).
enum class Fit { kBinsAlone, kPeaksMatched };

//! The leave-one-feed-out prediction of recording `held`, identified from the other two (cached: each
//! identification takes about half a second).
const HeldOut& held_out(int held, Band band, int tool, bool runout, Fit fit = Fit::kBinsAlone) {
  static std::map<std::tuple<int, Band, int, bool, Fit>, HeldOut> cache;
  const auto key = std::make_tuple(held, band, tool, runout, fit);
  if (cache.count(key)) return cache[key];
  const CutterGeometry& cutter = kTools[tool];
  std::vector<MechanisticCuttingTest> tests;
  std::vector<std::vector<double>> peaks;
  for (int i = 0; i < 3; ++i) {
    if (i == held) continue;
    tests.push_back(cutting_test(record(i, band, tool), cutter, kRecordings[i].file));
    peaks.push_back(record(i, band, tool).steady_peaks_n);
  }
  MechanisticIdentificationOptions options;
  options.identify_runout = runout;
  options.match_peaks = fit == Fit::kPeaksMatched;
  HeldOut h;
  h.identification = identify_mechanistic(tests, options);
  const ImmersionArc arc = straight_cut_arc(StraightCutSide::kSlot, 2 * cutter.radius_mm, cutter.radius_mm);
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
  h.interval = mechanistic_peak_interval(h.identification.model, h.identification.covariance,
                                         std::span<const EngagedSection>(&section, 1), cutter,
                                         kRecordings[held].feed_per_tooth_mm, pooled_revolution_spread_rel(peaks));
  h.measured_n = record(held, band, tool).peak_mean_n;
  return cache[key] = h;
}

void print(const char* what, int held, Band band, int tool, bool runout, Fit fit = Fit::kBinsAlone) {
  const HeldOut& h = held_out(held, band, tool, runout, fit);
  const MechanisticIdentification& id = h.identification;
  std::printf("%s %s ψ %.3f rad (D%.0f %2.0f°) %-7s runout %-3s held out f_z %.3f mm: predicted %6.1f N, measured mean peak "
              "%6.1f N, error %+6.2f %%, interval [%6.1f, %6.1f] N %s (fit σ %.1f N, spread %.2f %%) | K_tc %.0f K_rc %.0f "
              "K_te %.1f K_re %.1f",
              what, fit == Fit::kPeaksMatched ? "bins and peaks" : "bins alone", helix_lag_rad(kTools[tool]), 2 * kTools[tool].radius_mm, kTools[tool].helix_deg,
              band == Band::kMeasured ? "raw" : "in-band", runout ? "yes" : "no", kRecordings[held].feed_per_tooth_mm,
              h.interval.predicted_n, h.measured_n, 100 * h.error(), h.interval.lower_n, h.interval.upper_n,
              h.covered() ? "covers" : "misses", h.interval.fit_sd_n,
              100 * h.interval.spread_sd_n / h.interval.predicted_n, id.model.ktc_n_per_mm2, id.model.krc_n_per_mm2,
              id.model.kte_n_per_mm, id.model.kre_n_per_mm);
  if (runout) std::printf(" runout %.1f/%.1f µm", 1000 * id.model.runout_mm[0], 1000 * id.model.runout_mm[1]);
  std::printf(", RMS residual %.1f N, peaks matched %d (RMS %.1f N, scatter %.1f N)\n", id.rms_residual_n,
              id.tests_peak_matched, id.peak_rms_residual_n, id.peak_scatter_n);
}

constexpr int kAssumed = 1;  // index of kAssumedTool in kTools

// 1. The tooth-frequency part of the force turns counter-clockwise in the dynamometer's frame, as recorded;
// the kernel's turns clockwise in the feed frame (for any positive coefficients: the chip follows the
// tooth). Hence the mirror.
TEST(KistlerMechanistic, RecordedForceTurnsOppositeToTheKernels) {
  MechanisticModel al7075;
  al7075.ktc_n_per_mm2 = 796;
  al7075.krc_n_per_mm2 = 169;
  al7075.kte_n_per_mm = 27.7;
  al7075.kre_n_per_mm = 30.8;
  const ImmersionArc arc{0.0, kPi};
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
  std::vector<Complex> kernel;
  for (int b = 0; b < 100; ++b) {
    const MechanisticForce f = predicted_force(al7075, std::span<const EngagedSection>(&section, 1), kAssumedTool, 0.075, 2 * kPi * b / 100);
    kernel.emplace_back(f.fx_n, f.fy_n);
  }
  const double kernel_ccw = std::abs(harmonic(kernel, 2)), kernel_cw = std::abs(harmonic(kernel, -2));
  std::printf("kernel (Al7075, f_z 0.075 mm): tooth-frequency force %.1f N clockwise, %.1f N counter-clockwise\n", kernel_cw, kernel_ccw);
  EXPECT_GT(kernel_cw, 3 * kernel_ccw);
  for (const Recording& r : kRecordings) {
    const force_log::ForceLog log = as_recorded(r);
    const auto revs = revolutions(log);
    // The synchronous average at 100 bins (one sample each at 10 kHz and 6000 rpm).
    std::vector<Complex> average(100);
    const std::vector<Complex> z = complex_force(log);
    for (std::size_t i = 0; i < revs.size() * 100; ++i) average[i % 100] += z[i] / static_cast<double>(revs.size());
    const double ccw = std::abs(harmonic(average, 2)), cw = std::abs(harmonic(average, -2));
    std::printf("%s as recorded: tooth-frequency force %.1f N counter-clockwise, %.1f N clockwise\n", r.file, ccw, cw);
    EXPECT_GT(ccw, 3 * cw) << r.file;
  }
}

// 2. For a slot the kernel sees the tool only through ψ = a_p tan β / r: three tools with the same ψ give
// the same force and peak, with runout too. (A tool with another ψ does not.)
TEST(KistlerMechanistic, SlotForceDependsOnTheToolOnlyThroughTheHelixLag) {
  MechanisticModel model;
  model.ktc_n_per_mm2 = 900;
  model.krc_n_per_mm2 = 300;
  model.kte_n_per_mm = 30;
  model.kre_n_per_mm = 25;
  model.runout_mm = {0.02, 0.0};
  const ImmersionArc arc{0.0, kPi};
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
  const std::span<const EngagedSection> sections(&section, 1);
  const double lag = helix_lag_rad(kAssumedTool);
  const double reference = predicted_peak_force_n(model, sections, kAssumedTool, 0.075);
  for (double radius_mm : {3.0, 8.0}) {
    const CutterGeometry same_lag{radius_mm, kFlutes, std::atan(lag * radius_mm / kAxialDepthMm) * 180 / kPi};
    EXPECT_NEAR(predicted_peak_force_n(model, sections, same_lag, 0.075), reference, 1e-9 * reference) << radius_mm;
    for (double angle : {0.3, 1.9, 4.0}) {
      const MechanisticForce a = predicted_force(model, sections, same_lag, 0.075, angle);
      const MechanisticForce b = predicted_force(model, sections, kAssumedTool, 0.075, angle);
      EXPECT_NEAR(a.fx_n, b.fx_n, 1e-9 * reference);
      EXPECT_NEAR(a.fy_n, b.fy_n, 1e-9 * reference);
    }
  }
  EXPECT_GT(std::abs(predicted_peak_force_n(model, sections, kTools[2], 0.075) - reference), 0.01 * reference);
}

// The acceptance, with the coefficients and runout identified as `feedplan db fit` does (bins and peaks) and
// the assumed tool (D10 30°): every held-out feed within ±8 %, and the interval covers its measured mean
// peak. From the bins alone 0.075 and 0.125 mm come out far under (3. above), less so with runout (4.).
TEST(KistlerMechanistic, LeaveOneFeedOutOnTheMeasuredPeaks) {
  for (Fit fit : {Fit::kBinsAlone, Fit::kPeaksMatched}) {
    for (bool runout : {false, true}) {
      for (int held = 0; held < 3; ++held) print("measured peaks:", held, Band::kMeasured, kAssumed, runout, fit);
    }
  }
  for (int held = 0; held < 3; ++held) {
    const HeldOut& h = held_out(held, Band::kMeasured, kAssumed, true, Fit::kPeaksMatched);
    EXPECT_LE(std::abs(h.error()), kAcceptance) << kRecordings[held].file;
    EXPECT_TRUE(h.covered()) << kRecordings[held].file;
    EXPECT_EQ(h.identification.tests_peak_matched, 2);
  }
  for (bool runout : {false, true}) {
    SCOPED_TRACE(runout ? "bins alone, with runout" : "bins alone, without runout");
    for (int held : {1, 2}) {
      EXPECT_LT(held_out(held, Band::kMeasured, kAssumed, runout).error(), -kAcceptance);
      EXPECT_FALSE(held_out(held, Band::kMeasured, kAssumed, runout).covered());
    }
  }
  for (int held : {1, 2}) {
    EXPECT_GT(held_out(held, Band::kMeasured, kAssumed, true).error(), held_out(held, Band::kMeasured, kAssumed, false).error());
  }
}

// The acceptance does not rest on the assumed tool: over ψ = 0.136 … 1.0 rad, with runout and peaks matched,
// every held-out feed within ±8 % and covered. From the bins alone 0.075 and 0.125 mm are under-predicted by
// more than 20 % with and without runout.
TEST(KistlerMechanistic, AcceptanceHoldsOverPlausibleTools) {
  for (int tool = 0; tool < 3; ++tool) {
    for (Fit fit : {Fit::kBinsAlone, Fit::kPeaksMatched}) {
      for (bool runout : {false, true}) {
        for (int held = 0; held < 3; ++held) print("tool range:", held, Band::kMeasured, tool, runout, fit);
      }
    }
  }
  for (int tool = 0; tool < 3; ++tool) {
    SCOPED_TRACE(kTools[tool].helix_deg);
    for (int held = 0; held < 3; ++held) {
      const HeldOut& h = held_out(held, Band::kMeasured, tool, true, Fit::kPeaksMatched);
      EXPECT_LE(std::abs(h.error()), kAcceptance) << kRecordings[held].file;
      EXPECT_TRUE(h.covered()) << kRecordings[held].file;
    }
    for (bool runout : {false, true}) {
      for (int held : {1, 2}) EXPECT_LT(held_out(held, Band::kMeasured, tool, runout).error(), -0.2);
    }
  }
}

// 3. The recorded force rings at the dynamometer's lateral modes, and the measured peaks hold the ringing.
TEST(KistlerMechanistic, MeasuredPeaksHoldTheDynamometersRinging) {
  const HeldOut& model_of_900 = held_out(1, Band::kMeasured, kAssumed, true);
  for (int i = 0; i < 3; ++i) {
    const Recording& r = kRecordings[i];
    const model_db::CuttingTestRecord& measured = record(i, Band::kMeasured, kAssumed);
    // Harmonics of the revolution per channel: 2 (400 Hz would be 4), 6, 8, 10 — from the import's
    // synchronous average, and from the kernel identified without this feed, at the same 50 bins.
    const ImmersionArc arc{0.0, kPi};
    const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
    std::vector<double> kx, ky;
    const std::size_t bins = measured.synchronous_fx_n.size();
    for (std::size_t b = 0; b < bins; ++b) {
      const MechanisticForce f = predicted_force(model_of_900.identification.model, std::span<const EngagedSection>(&section, 1),
                                                 kAssumedTool, r.feed_per_tooth_mm, 2 * kPi * (b + 0.5) / bins);
      kx.push_back(f.fx_n);
      ky.push_back(f.fy_n);
    }
    std::printf("%s harmonics (N) measured Fx / Fy | kernel Fx / Fy:", r.file);
    for (int k : {2, 4, 6, 8, 10}) {
      std::printf("  %d: %.1f / %.1f | %.1f / %.1f", 100 * k, channel_amplitude(measured.synchronous_fx_n, k),
                  channel_amplitude(measured.synchronous_fy_n, k), channel_amplitude(kx, k), channel_amplitude(ky, k));
    }
    std::printf(" Hz\n");
    EXPECT_GT(channel_amplitude(measured.synchronous_fx_n, 8), channel_amplitude(measured.synchronous_fx_n, 6)) << r.file;
    EXPECT_GT(channel_amplitude(measured.synchronous_fy_n, 10), channel_amplitude(measured.synchronous_fy_n, 8)) << r.file;
    EXPECT_LT(channel_amplitude(kx, 8), channel_amplitude(kx, 6)) << r.file;
    EXPECT_LT(channel_amplitude(ky, 10), channel_amplitude(ky, 8)) << r.file;

    const model_db::CuttingTestRecord& band = record(i, Band::kInBand, kAssumed);
    std::vector<std::vector<double>> raw_peaks{measured.steady_peaks_n}, band_peaks{band.steady_peaks_n};
    std::printf("%s mean per-revolution peak %.1f N measured, %.1f N in band (%+.1f %%); spread %.2f %% measured, %.2f %% "
                "in band; %d and %d steady revolutions\n",
                r.file, measured.peak_mean_n, band.peak_mean_n, 100 * (measured.peak_mean_n / band.peak_mean_n - 1),
                100 * pooled_revolution_spread_rel(raw_peaks), 100 * pooled_revolution_spread_rel(band_peaks),
                measured.revolutions_used, band.revolutions_used);
    EXPECT_NEAR(measured.peak_mean_n, r.mean_peak_n, 0.05) << r.file;  // every revolution is steady
    if (i > 0) {
      EXPECT_GT(measured.peak_mean_n / band.peak_mean_n - 1, 0.2) << r.file;
    }
  }
}

//! The peak of the kernel's force restricted to the same harmonics as the in-band logs (|k| ≤
//! kInBandHarmonics of the revolution), from 720 samples over a revolution, N.
double kernel_in_band_peak_n(const MechanisticModel& model, const CutterGeometry& cutter, double feed_per_tooth_mm) {
  const ImmersionArc arc = straight_cut_arc(StraightCutSide::kSlot, 2 * cutter.radius_mm, cutter.radius_mm);
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
  constexpr int kSamples = 720;
  std::vector<Complex> z;
  for (int b = 0; b < kSamples; ++b) {
    const MechanisticForce f = predicted_force(model, std::span<const EngagedSection>(&section, 1), cutter,
                                               feed_per_tooth_mm, 2 * kPi * b / kSamples);
    z.emplace_back(f.fx_n, f.fy_n);
  }
  std::vector<Complex> c;
  for (int k = -kInBandHarmonics; k <= kInBandHarmonics; ++k) c.push_back(harmonic(z, k));
  double peak_n = 0.0;
  for (int b = 0; b < kSamples; ++b) {
    Complex sum = 0;
    for (int k = -kInBandHarmonics; k <= kInBandHarmonics; ++k) {
      sum += c[k + kInBandHarmonics] * std::polar(1.0, 2 * kPi * k * b / kSamples);
    }
    peak_n = std::max(peak_n, std::abs(sum));
  }
  return peak_n;
}

// 3. and 4. The same leave-one-out with the ringing removed: the three recordings in band, and the
// kernel's force restricted to the same harmonics (its runout pulses have some of their own above them).
// With runout: 0.025 and 0.075 mm within ±8 %, 0.125 mm over-predicted (the sign of a size effect).
// Without runout the kernel cannot follow the teeth's unequal load: 0.025 and 0.075 mm come out more than
// 20 % low. The runout found is 20–30 µm.
TEST(KistlerMechanistic, LeaveOneFeedOutOnTheInBandPeaks) {
  double error[2][3];
  for (bool runout : {false, true}) {
    for (int held = 0; held < 3; ++held) {
      const HeldOut& h = held_out(held, Band::kInBand, kAssumed, runout);
      const double predicted_n = kernel_in_band_peak_n(h.identification.model, kAssumedTool, kRecordings[held].feed_per_tooth_mm);
      error[runout][held] = (predicted_n - h.measured_n) / h.measured_n;
      std::printf("in-band peaks: runout %-3s held out f_z %.3f mm: kernel's in-band peak %6.1f N (whole peak %6.1f N), "
                  "measured in-band mean peak %6.1f N, error %+6.2f %%",
                  runout ? "yes" : "no", kRecordings[held].feed_per_tooth_mm, predicted_n, h.interval.predicted_n,
                  h.measured_n, 100 * error[runout][held]);
      if (runout) {
        std::printf(", runout %.1f/%.1f µm", 1000 * h.identification.model.runout_mm[0], 1000 * h.identification.model.runout_mm[1]);
      }
      // The force turned by 90° (F' = F_t e_r − F_r e_t): K_tc' = −K_rc, K_rc' = K_tc, likewise for the edge.
      const MechanisticModel& m = h.identification.model;
      std::printf(", coefficients with x and y swapped: K_tc %.0f K_rc %.0f K_te %.1f K_re %.1f", -m.krc_n_per_mm2,
                  m.ktc_n_per_mm2, -m.kre_n_per_mm, m.kte_n_per_mm);
      std::printf(", RMS residual %.1f N\n", h.identification.rms_residual_n);
    }
  }
  EXPECT_LE(std::abs(error[1][0]), kAcceptance);
  EXPECT_LE(std::abs(error[1][1]), kAcceptance);
  EXPECT_GT(error[1][2], 0.0);
  EXPECT_LT(error[0][0], -0.2);
  EXPECT_LT(error[0][1], -0.2);
  for (int held = 0; held < 3; ++held) {
    const auto& runout = held_out(held, Band::kInBand, kAssumed, true).identification.model.runout_mm;
    EXPECT_GT(std::abs(runout[0] - runout[1]), 0.015);
    EXPECT_LT(std::abs(runout[0] - runout[1]), 0.035);
  }
}

//! The leave-one-feed-out prediction of the measured peak through the identified sensor (6. above).
struct SensedHeldOut {
  MechanisticIdentification identification;
  PredictionInterval interval;
  double force_peak_n = 0.0;  //!< the kernel's own peak (the force on the tool), N
  double measured_n = 0.0;
  double error() const { return (interval.predicted_n - measured_n) / measured_n; }
  bool covered() const { return measured_n >= interval.lower_n && measured_n <= interval.upper_n; }
};

//! Identified from the other two recordings with runout, the sensor and, with `helix`, the helix (cached:
//! each identification takes 2–15 s).
const SensedHeldOut& sensed_held_out(int held, bool helix) {
  static std::map<std::pair<int, bool>, SensedHeldOut> cache;
  const auto key = std::make_pair(held, helix);
  if (cache.count(key)) return cache[key];
  std::vector<MechanisticCuttingTest> tests;
  std::vector<std::vector<double>> peaks;
  for (int i = 0; i < 3; ++i) {
    if (i == held) continue;
    tests.push_back(cutting_test(record(i, Band::kMeasured, kAssumed), kAssumedTool, kRecordings[i].file));
    peaks.push_back(record(i, Band::kMeasured, kAssumed).steady_peaks_n);
  }
  MechanisticIdentificationOptions options;
  options.identify_runout = true;
  options.identify_helix = helix;
  options.identify_sensor = true;
  options.match_peaks = false;
  SensedHeldOut h;
  h.identification = identify_mechanistic(tests, options);
  const ImmersionArc arc = straight_cut_arc(StraightCutSide::kSlot, 2 * kAssumedTool.radius_mm, kAssumedTool.radius_mm);
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
  const std::span<const EngagedSection> sections(&section, 1);
  h.interval = mechanistic_sensed_peak_interval(h.identification.model, h.identification.covariance, sections,
                                                kAssumedTool, kRecordings[held].feed_per_tooth_mm,
                                                *h.identification.sensor, kRpm, pooled_revolution_spread_rel(peaks));
  h.force_peak_n = predicted_peak_force_n(h.identification.model, sections, kAssumedTool, kRecordings[held].feed_per_tooth_mm);
  h.measured_n = record(held, Band::kMeasured, kAssumed).peak_mean_n;
  return cache[key] = h;
}

void print_sensed(int held, bool helix) {
  const SensedHeldOut& h = sensed_held_out(held, helix);
  const MechanisticIdentification& id = h.identification;
  const SensorResponse& s = *id.sensor;
  std::printf("through the identified sensor, runout%s, held out f_z %.3f mm: predicted %6.1f N, measured mean peak "
              "%6.1f N, error %+6.2f %%, interval [%6.1f, %6.1f] N %s (fit σ %.1f N, spread %.2f %%); force on the tool "
              "%6.1f N | modes %.0f Hz ζ %.3f, %.0f Hz ζ %.3f, θ %+.1f° | K_tc %.0f K_rc %.0f K_te %.1f K_re %.1f runout "
              "%.1f/%.1f µm",
              helix ? ", helix" : "", kRecordings[held].feed_per_tooth_mm, h.interval.predicted_n, h.measured_n,
              100 * h.error(), h.interval.lower_n, h.interval.upper_n, h.covered() ? "covers" : "misses",
              h.interval.fit_sd_n, 100 * h.interval.spread_sd_n / h.interval.predicted_n, h.force_peak_n,
              s.modes[0].natural_frequency_hz, s.modes[0].damping_ratio, s.modes[1].natural_frequency_hz,
              s.modes[1].damping_ratio, s.mode_angle_deg, id.model.ktc_n_per_mm2, id.model.krc_n_per_mm2,
              id.model.kte_n_per_mm, id.model.kre_n_per_mm, 1000 * id.model.runout_mm[0], 1000 * id.model.runout_mm[1]);
  if (id.model.helix_deg) std::printf(" helix %.1f°", *id.model.helix_deg);
  std::printf(", RMS residual %.1f N\n", id.rms_residual_n);
}

//! The frequency in [lo_hz, hi_hz] at which the part of a channel that does not repeat every revolution (the
//! log less its synchronous average, over the first 100 revolutions of 100 samples) is strongest: its
//! amplitude spectrum at 1 Hz steps, power summed over ±12 Hz. Also that part's RMS.
struct NonSynchronous {
  double rms_n = 0.0;
  double strongest_hz = 0.0;
};
NonSynchronous non_synchronous(const force_log::ForceLog& log, bool y, double lo_hz, double hi_hz) {
  constexpr int kRevolutions = 100, kPerRevolution = 100;  // 10 kHz at 6000 rpm
  constexpr int n = kRevolutions * kPerRevolution;
  std::vector<double> x(n), average(kPerRevolution, 0.0);
  for (int i = 0; i < n; ++i) {
    x[i] = y ? log.rows[i].fy_n : log.rows[i].fx_n;
    average[i % kPerRevolution] += x[i] / kRevolutions;
  }
  NonSynchronous result;
  for (int i = 0; i < n; ++i) {
    x[i] -= average[i % kPerRevolution];
    result.rms_n += x[i] * x[i] / n;
  }
  result.rms_n = std::sqrt(result.rms_n);
  const double rate_hz = 1.0 / (log.rows[1].t_s - log.rows[0].t_s);
  std::vector<double> power;
  for (int f = static_cast<int>(lo_hz) - 12; f <= static_cast<int>(hi_hz) + 12; ++f) {
    Complex sum = 0;
    for (int i = 0; i < n; ++i) sum += x[i] * std::polar(1.0, -2 * kPi * f * i / rate_hz);
    power.push_back(std::norm(2.0 * sum / static_cast<double>(n)));
  }
  double best = -1;
  for (std::size_t c = 12; c + 12 < power.size(); ++c) {
    double band = 0;
    for (std::size_t k = c - 12; k <= c + 12; ++k) band += power[k];
    if (band > best) best = band, result.strongest_hz = lo_hz - 12 + static_cast<double>(c);
  }
  return result;
}

// 6. The dynamometer's modes identified with the coefficients and runout, and each feed's measured mean peak
// predicted through them from the other two (identify_sensor, mechanistic_sensed_peak_interval). The modes
// come out where the spectra ring: from the two pairs with 1500 mm/min, one mode along x (θ within 10°) at
// 775–800 Hz and one along y at 985–1010 Hz, within 25 Hz of where the recordings' non-synchronous vibration is
// strongest (an independent look at the modes: the log less its synchronous average, between 600 and
// 1400 Hz, at 1500 mm/min). From 0.025 and 0.075 mm alone the y mode is not resolved (it runs to the
// top of the range, the residual hardly changing).
// The acceptance is met for 0.075 mm only (interpolated: −4 %, the interval covers); 0.025 mm comes out
// nearly twice its reading and 0.125 mm a third under, and identifying the helix as well (it runs to 10–11°,
// against its 10° bound, in two of the three fits) meets it for none. Why, in 7. and the test below.
TEST(KistlerMechanistic, LeaveOneFeedOutThroughTheIdentifiedSensor) {
  for (bool helix : {false, true}) {
    for (int held = 0; held < 3; ++held) print_sensed(held, helix);
  }
  const NonSynchronous x_vibration = non_synchronous(feed_frame_log(2, Band::kMeasured), false, 600, 1400);
  const NonSynchronous y_vibration = non_synchronous(feed_frame_log(2, Band::kMeasured), true, 600, 1400);
  std::printf("n6000_f1500_ap3.csv non-synchronous vibration strongest at %.0f Hz in Fx, %.0f Hz in Fy\n",
              x_vibration.strongest_hz, y_vibration.strongest_hz);
  // The import's bins: 50 per revolution (two 10 kHz samples each), which resolve harmonics below the 25th,
  // 2500 Hz: the modes' harmonics (8–10) are well inside, and the search for them stops at 2500 Hz, not 3 kHz.
  EXPECT_EQ(record(2, Band::kMeasured, kAssumed).synchronous_fx_n.size(), 50u);
  bool said = false;
  for (const std::string& u : sensed_held_out(0, false).identification.unidentifiable) {
    said = said || u.find("sensor modes above 2500 Hz") != std::string::npos;
  }
  EXPECT_TRUE(said);
  for (int held : {0, 1}) {
    const SensorResponse& s = *sensed_held_out(held, false).identification.sensor;
    EXPECT_LT(std::abs(s.mode_angle_deg), 10.0) << held;
    EXPECT_GT(s.modes[0].natural_frequency_hz, 775.0) << held;
    EXPECT_LT(s.modes[0].natural_frequency_hz, 800.0) << held;
    EXPECT_GT(s.modes[1].natural_frequency_hz, 985.0) << held;
    EXPECT_LT(s.modes[1].natural_frequency_hz, 1010.0) << held;
    EXPECT_NEAR(s.modes[0].natural_frequency_hz, x_vibration.strongest_hz, 25.0) << held;
    EXPECT_NEAR(s.modes[1].natural_frequency_hz, y_vibration.strongest_hz, 25.0) << held;
  }
  EXPECT_LE(std::abs(sensed_held_out(1, false).error()), kAcceptance);
  EXPECT_TRUE(sensed_held_out(1, false).covered());
  EXPECT_GT(sensed_held_out(0, false).error(), kAcceptance) << "acceptance now met? see 7.";
  EXPECT_FALSE(sensed_held_out(0, false).covered());
  EXPECT_LT(sensed_held_out(2, false).error(), -kAcceptance) << "acceptance now met? see 7.";
  EXPECT_FALSE(sensed_held_out(2, false).covered());
  for (int held = 0; held < 3; ++held) EXPECT_GT(std::abs(sensed_held_out(held, true).error()), kAcceptance) << held;
}

// 7. Why a sensor does not make the kernel predict the readings: what rings is not a linear response to the
// kernel's force.
//   a. In a 2-flute slot without runout the kernel's cutting force is a constant plus one sinusoid at the
//      tooth frequency, whatever the helix: one tooth is in the cut at every height, and its force,
//      K f_z sin φ (−cos φ, sin φ) and the like, holds only the harmonics 0 and 2 of the revolution. So above
//      the tooth frequency the kernel's force comes from its edge terms (the same at every feed) and runout.
//   b. The recordings' harmonics 4, 6 and 8 (400–800 Hz) grow 4.4–5.8× from f_z 0.025 to 0.125 mm, the tooth
//      frequency's 2.4×: what drives the modes grows with the chip, faster than the force at the tooth
//      frequency. A linear sensor multiplies each harmonic by a gain that does not depend on the feed.
//   c. So even fitted to all three recordings at once, the kernel through the identified sensor leaves an RMS
//      bin residual of about 70 N, against a noise of the synchronous averages of at most 5 N (the
//      non-synchronous part's RMS over √100 revolutions); the same fit in band leaves 20–30 N (4.).
//   d. The modes also vibrate without the revolution's period, more so the larger the feed: the
//      non-synchronous part's RMS |F_xy| grows from 6.6 N at 300 mm/min to 60 N at 1500 mm/min, strongest at
//      the modes (6.). This points to a structure with these modes (the workpiece on the dynamometer, or the
//      tool: force data alone cannot tell) taking part in the cut, its vibration changing the chip, rather than
//      a sensor reading a periodic force. Predicting what this dynamometer reads needs that dynamics of the cut.
TEST(KistlerMechanistic, RingingIsNotALinearResponseToTheKernelsForce) {
  // a.
  MechanisticModel cutting_only;
  cutting_only.ktc_n_per_mm2 = 900;
  cutting_only.krc_n_per_mm2 = 300;
  const ImmersionArc arc{0.0, kPi};
  const EngagedSection section{0.0, kAxialDepthMm, std::span<const ImmersionArc>(&arc, 1)};
  for (double helix_deg : {0.0, 30.0, 45.0}) {
    const CutterGeometry cutter{5.0, kFlutes, helix_deg};
    std::vector<double> fx, fy;
    for (int b = 0; b < 360; ++b) {
      const MechanisticForce f = predicted_force(cutting_only, std::span<const EngagedSection>(&section, 1), cutter, 0.075, 2 * kPi * b / 360);
      fx.push_back(f.fx_n);
      fy.push_back(f.fy_n);
    }
    for (int k : {1, 3, 4, 6, 8, 10}) {
      EXPECT_LT(channel_amplitude(fx, k), 1e-3 * channel_amplitude(fx, 2)) << helix_deg << " " << k;
      EXPECT_LT(channel_amplitude(fy, k), 1e-3 * channel_amplitude(fy, 2)) << helix_deg << " " << k;
    }
  }
  // b.
  const model_db::CuttingTestRecord& low = record(0, Band::kMeasured, kAssumed);
  const model_db::CuttingTestRecord& high = record(2, Band::kMeasured, kAssumed);
  const double tooth_growth = channel_amplitude(high.synchronous_fx_n, 2) / channel_amplitude(low.synchronous_fx_n, 2);
  std::printf("Fx harmonics from f_z 0.025 to 0.125 mm: 2 × %.2f", tooth_growth);
  for (int k : {4, 6, 8}) {
    const double growth = channel_amplitude(high.synchronous_fx_n, k) / channel_amplitude(low.synchronous_fx_n, k);
    std::printf(", %d × %.2f", k, growth);
    EXPECT_GT(growth, 1.5 * tooth_growth) << k;
  }
  std::printf("\n");
  // c.
  std::vector<MechanisticCuttingTest> tests;
  for (int i = 0; i < 3; ++i) tests.push_back(cutting_test(record(i, Band::kMeasured, kAssumed), kAssumedTool, kRecordings[i].file));
  MechanisticIdentificationOptions options;
  options.identify_runout = true;
  options.identify_sensor = true;
  options.match_peaks = false;
  const MechanisticIdentification all = identify_mechanistic(tests, options);
  double noise_n = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (bool y : {false, true}) {
      noise_n = std::max(noise_n, non_synchronous(feed_frame_log(i, Band::kMeasured), y, 700, 700).rms_n / std::sqrt(100.0));
    }
  }
  const SensorResponse& s = *all.sensor;
  std::printf("all three recordings through the identified sensor: RMS residual %.1f N (per recording %.1f, %.1f, %.1f N), "
              "noise of the synchronous averages at most %.1f N | modes %.0f Hz ζ %.3f, %.0f Hz ζ %.3f, θ %+.1f°\n",
              all.rms_residual_n, all.test_rms_residual_n[0], all.test_rms_residual_n[1], all.test_rms_residual_n[2],
              noise_n, s.modes[0].natural_frequency_hz, s.modes[0].damping_ratio, s.modes[1].natural_frequency_hz,
              s.modes[1].damping_ratio, s.mode_angle_deg);
  EXPECT_GT(all.rms_residual_n, 5 * noise_n);
  // d.
  double rms_n[3];
  for (int i = 0; i < 3; ++i) {
    rms_n[i] = std::hypot(non_synchronous(feed_frame_log(i, Band::kMeasured), false, 700, 700).rms_n,
                          non_synchronous(feed_frame_log(i, Band::kMeasured), true, 700, 700).rms_n);
    std::printf("%s non-synchronous vibration: RMS |F_xy| %.1f N\n", kRecordings[i].file, rms_n[i]);
  }
  EXPECT_LT(rms_n[0], rms_n[1]);
  EXPECT_GT(rms_n[2], 5 * rms_n[0]);
}

}  // namespace
}  // namespace feedplan::model
