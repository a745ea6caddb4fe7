// Per-revolution peaks: synthetic signals with known answers, and real Kistler slot-milling data
// (tests/data/kistler: 6000 rpm at 10 kHz, 100 samples per revolution) checked against a
// brute-force maximum over index windows written here.

#include "feedplan/force_log/revolution_peaks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "feedplan/force_log/force_log.hpp"

namespace feedplan::force_log {
namespace {

const std::string kKistlerDir = std::string(FEEDPLAN_TEST_DATA_DIR) + "/kistler/";

struct Series {
  std::vector<double> t_s, fx_n, fy_n;
};

Series series_of(const ForceLog& log) {
  Series s;
  for (const auto& row : log.rows) {
    s.t_s.push_back(row.t_s);
    s.fx_n.push_back(row.fx_n);
    s.fy_n.push_back(row.fy_n);
  }
  return s;
}

TEST(RevolutionPeaks, SyntheticWindowsPeaksAndMeans) {
  // 6000 rpm, 10 kHz: 100 samples per revolution. In revolution k the force is 10 (k + 1) N along x,
  // with one spike of 100 (k + 1) N along y at sample 37 of the window.
  Series s;
  for (int i = 0; i < 1000; ++i) {
    const int k = i / 100;
    s.t_s.push_back(2.0 + i * 1e-4);
    s.fx_n.push_back(10.0 * (k + 1));
    s.fy_n.push_back(i % 100 == 37 ? 100.0 * (k + 1) : 0.0);
  }
  const auto peaks = revolution_peaks(s.t_s, s.fx_n, s.fy_n, 6000.0);
  ASSERT_EQ(peaks.size(), 10u);
  for (int k = 0; k < 10; ++k) {
    SCOPED_TRACE(k);
    EXPECT_EQ(peaks[k].revolution, k);
    EXPECT_EQ(peaks[k].samples, 100u);
    EXPECT_NEAR(peaks[k].t_start_s, 2.0 + 0.01 * k, 1e-12);
    EXPECT_NEAR(peaks[k].t_end_s, 2.0 + 0.01 * (k + 1), 1e-12);
    EXPECT_DOUBLE_EQ(peaks[k].peak_xy_n, std::hypot(10.0 * (k + 1), 100.0 * (k + 1)));
    EXPECT_NEAR(peaks[k].t_peak_s, s.t_s[100 * k + 37], 1e-12);
    EXPECT_NEAR(peaks[k].mean_xy_n, (99 * 10.0 * (k + 1) + std::hypot(10.0 * (k + 1), 100.0 * (k + 1))) / 100, 1e-9);
  }
}

TEST(RevolutionPeaks, IncompleteLastRevolutionIsDropped) {
  Series s;
  for (int i = 0; i < 1050; ++i) {
    s.t_s.push_back(i * 1e-4);
    s.fx_n.push_back(1.0);
    s.fy_n.push_back(0.0);
  }
  EXPECT_EQ(revolution_peaks(s.t_s, s.fx_n, s.fy_n, 6000.0).size(), 10u);  // 10.5 revolutions
  for (auto* v : {&s.t_s, &s.fx_n, &s.fy_n}) v->resize(999);
  EXPECT_EQ(revolution_peaks(s.t_s, s.fx_n, s.fy_n, 6000.0).size(), 9u);  // one sample short of 10
  for (auto* v : {&s.t_s, &s.fx_n, &s.fy_n}) v->resize(1);
  EXPECT_TRUE(revolution_peaks(s.t_s, s.fx_n, s.fy_n, 6000.0).empty());
}

TEST(RevolutionPeaks, GapsSkipRevolutionNumbers) {
  Series s;
  for (int i = 0; i < 600; ++i) {
    if (i >= 200 && i < 400) continue;  // revolutions 2 and 3 not recorded
    s.t_s.push_back(i * 1e-4);
    s.fx_n.push_back(i);
    s.fy_n.push_back(0.0);
  }
  const auto peaks = revolution_peaks(s.t_s, s.fx_n, s.fy_n, 6000.0);
  ASSERT_EQ(peaks.size(), 4u);
  EXPECT_EQ(peaks[2].revolution, 4);
  EXPECT_DOUBLE_EQ(peaks[2].peak_xy_n, 499.0);
}

TEST(RevolutionPeaks, PerSampleSpeedFollowsTheIntegratedAngle) {
  // rpm(t) = 3000 + 60000 t: angle(t) = (3000 t + 30000 t²) / 60 turns; revolution k starts at the
  // root of 500 t² + 50 t − k = 0.
  Series s;
  std::vector<double> rpm;
  for (int i = 0; i <= 5000; ++i) {
    const double t = i * 1e-4;
    s.t_s.push_back(t);
    s.fx_n.push_back(std::sin(2 * std::numbers::pi * 7.3 * t) + 2.0);
    s.fy_n.push_back(0.0);
    rpm.push_back(3000.0 + 60000.0 * t);
  }
  const auto peaks = revolution_peaks(s.t_s, s.fx_n, s.fy_n, rpm);
  ASSERT_GE(peaks.size(), 100u);
  for (const auto& p : peaks) {
    const double k = static_cast<double>(p.revolution);
    const double expected_start = (-50.0 + std::sqrt(2500.0 + 2000.0 * k)) / 1000.0;
    const double expected_end = (-50.0 + std::sqrt(2500.0 + 2000.0 * (k + 1))) / 1000.0;
    ASSERT_NEAR(p.t_start_s, expected_start, 1e-7) << "revolution " << k;
    ASSERT_NEAR(p.t_end_s, expected_end, 1e-7) << "revolution " << k;
  }
  // A constant per-sample speed gives what the scalar overload gives.
  const std::vector<double> constant(s.t_s.size(), 4500.0);
  const auto a = revolution_peaks(s.t_s, s.fx_n, s.fy_n, constant);
  const auto b = revolution_peaks(s.t_s, s.fx_n, s.fy_n, 4500.0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].samples, b[i].samples);
    EXPECT_EQ(a[i].peak_xy_n, b[i].peak_xy_n);
  }
}

TEST(RevolutionPeaks, BadInputIsAnInputError) {
  const std::vector<double> t = {0, 0.1, 0.1}, f = {1, 2, 3};
  try {
    revolution_peaks(t, f, f, 6000.0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "t_s[2] = 0.1: must be after t_s[1] = 0.1 — times must increase");
  }
  try {
    revolution_peaks({0, 1}, {1, 2}, {1, 2}, 0.0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "spindle_rpm = 0: must be a finite number > 0 rev/min — the spindle speed");
  }
  EXPECT_THROW(revolution_peaks({0, 1}, {1, std::nan("")}, {1, 2}, 6000.0), InputError);
  EXPECT_THROW(revolution_peaks({0, 1}, {1, 2}, {1, 2}, std::vector<double>{6000.0, -1.0}), InputError);
}

// Real data. Each excerpt: 1000 samples at 10 kHz, 6000 rpm → exactly 10 revolutions of 100 samples.
struct RealRun {
  std::string file;
  double feed_mm_per_min;
  std::vector<RevolutionPeak> peaks;
  double mean_peak_n = 0.0;
};

std::vector<RealRun> real_runs() {
  std::vector<RealRun> runs = {{"n6000_f300_ap3", 300, {}}, {"n6000_f900_ap3", 900, {}}, {"n6000_f1500_ap3", 1500, {}}};
  for (auto& run : runs) {
    const Series s = series_of(load_force_log(kKistlerDir + run.file + "_excerpt.csv"));
    run.peaks = revolution_peaks(s.t_s, s.fx_n, s.fy_n, 6000.0);
    for (const auto& p : run.peaks) run.mean_peak_n += p.peak_xy_n / static_cast<double>(run.peaks.size());
  }
  return runs;
}

TEST(RevolutionPeaksKistler, CountsAndBruteForceMaxima) {
  for (const char* name : {"n6000_f300_ap3", "n6000_f900_ap3", "n6000_f1500_ap3"}) {
    SCOPED_TRACE(name);
    const Series s = series_of(load_force_log(kKistlerDir + name + "_excerpt.csv"));
    ASSERT_EQ(s.t_s.size(), 1000u);
    const auto peaks = revolution_peaks(s.t_s, s.fx_n, s.fy_n, 6000.0);
    ASSERT_EQ(peaks.size(), 10u);
    for (std::size_t k = 0; k < peaks.size(); ++k) {
      // Brute force over samples 100 k … 100 k + 99.
      double max_n = 0.0, sum_n = 0.0;
      for (std::size_t i = 100 * k; i < 100 * (k + 1); ++i) {
        const double f = std::sqrt(s.fx_n[i] * s.fx_n[i] + s.fy_n[i] * s.fy_n[i]);
        max_n = std::max(max_n, f);
        sum_n += f;
      }
      EXPECT_EQ(peaks[k].samples, 100u) << "revolution " << k;
      EXPECT_DOUBLE_EQ(peaks[k].peak_xy_n, max_n) << "revolution " << k;
      EXPECT_NEAR(peaks[k].mean_xy_n, sum_n / 100.0, 1e-9) << "revolution " << k;
      EXPECT_NEAR(peaks[k].t_start_s, s.t_s.front() + 0.01 * static_cast<double>(k), 1e-9);
    }
  }
}

TEST(RevolutionPeaksKistler, PeaksGrowWithFeed) {
  const auto runs = real_runs();
  for (const auto& run : runs) {
    std::cout << "[ info     ] " << run.file << ": mean per-revolution peak " << run.mean_peak_n << " N over "
              << run.peaks.size() << " revolutions\n";
    ::testing::Test::RecordProperty(run.file + "_mean_peak_n", std::to_string(run.mean_peak_n));
  }
  // Each feed's weakest revolution peaks above the previous feed's strongest.
  for (std::size_t r = 1; r < runs.size(); ++r) {
    double lower_max = 0.0, higher_min = 1e300;
    for (const auto& p : runs[r - 1].peaks) lower_max = std::max(lower_max, p.peak_xy_n);
    for (const auto& p : runs[r].peaks) higher_min = std::min(higher_min, p.peak_xy_n);
    EXPECT_GT(higher_min, lower_max) << runs[r].file << " vs " << runs[r - 1].file;
  }
  // The peak grows less than the feed: the edge (ploughing) force does not scale with the chip.
  const double ratio_900_300 = runs[1].mean_peak_n / runs[0].mean_peak_n;
  const double ratio_1500_900 = runs[2].mean_peak_n / runs[1].mean_peak_n;
  EXPECT_GT(ratio_900_300, 1.5);
  EXPECT_LT(ratio_900_300, 3.0);
  EXPECT_GT(ratio_1500_900, 1.2);
  EXPECT_LT(ratio_1500_900, 1500.0 / 900.0);
  // Measured on these excerpts when the test was written (mean of 10 revolutions).
  EXPECT_NEAR(runs[0].mean_peak_n, 247.1, 0.5);
  EXPECT_NEAR(runs[1].mean_peak_n, 491.5, 0.5);
  EXPECT_NEAR(runs[2].mean_peak_n, 741.1, 0.5);
}

}  // namespace
}  // namespace feedplan::force_log
