// Real data: two Kistler DynoWare recordings of slot milling (300 and 1500 mm/min,
// tests/data/kistler_full/) are treated as the logs of a straight-slot plan at those feeds; the refit
// must move the model's prediction at the third recording's feed (900 mm/min) toward its measured
// per-revolution peak, 495.4 N (worked out independently, tests/data/kistler_full/README.md).
//
// A full slot is engaged over 0°–180° everywhere, so every revolution of a straight slot at constant
// feed has the same model inputs: t_m = f_z (chip factor 1), L = r·π. The logs have no positions and
// no air/contact edge (the whole second is steady cutting), so they are placed on the plan by these
// known conditions, not by log_alignment (which needs a position or a contact edge to align by).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <unistd.h>

#include "feedplan/learning/batch_refit.hpp"
#include "feedplan/learning/prediction_errors.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::learning {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;
constexpr double kRpm = 6000.0;
constexpr int kFlutes = 2;
constexpr double kAxialDepthMm = 3.0;
constexpr double kToolRadiusMm = 5.0;  // assumed D10 (not stated in the source), as in the import tests
constexpr double kMeasuredPeak900N = 495.4;

// Per-revolution peaks of a recording as learning samples of a straight slot at `feed_mm_per_min`,
// forces scaled to the model's axial depth (the planner's convention, feed_limit.hpp).
std::vector<LearningSample> slot_samples(const std::string& file, double feed_mm_per_min, double model_axial_depth_mm) {
  const force_log::ForceLog log = force_log::load_force_log(std::string(FEEDPLAN_TEST_DATA_DIR) + "/kistler_full/" + file);
  std::vector<double> t, fx, fy;
  for (const auto& row : log.rows) {
    t.push_back(row.t_s);
    fx.push_back(row.fx_n);
    fy.push_back(row.fy_n);
  }
  std::vector<LearningSample> samples;
  for (const force_log::RevolutionPeak& peak : force_log::revolution_peaks(t, fx, fy, kRpm)) {
    samples.push_back({feed_mm_per_min / (kFlutes * kRpm), kToolRadiusMm * kPi,
                       peak.peak_xy_n * model_axial_depth_mm / kAxialDepthMm, 1.0, 0.0});
  }
  return samples;
}

TEST(KistlerLearning, RefitFromTwoFeedsMovesThePredictionAtTheThirdTowardItsMeasuredPeak) {
  // The starting model: the sample database's D10 4-flute model in S50C — another tool, probably another
  // material, fitted below 66° of engagement: a poor start, as a new tool/material would be.
  const fs::path dir = fs::temp_directory_path() / ("feedplan_kistler_learning_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  model::ResponseSurfaceModel start;
  {
    auto store = model_db::Store::open(dir / "t.db", model_db::OpenMode::kCreate);
    model_db::import_from_file(store, fs::path(FEEDPLAN_TEST_DATA_DIR) / "cli" / "s50c_d10_model.json");
    start = store.active_model("SC EM D10 Z4", "S50C")->model;
  }
  fs::remove_all(dir);

  std::vector<LearningSample> samples = slot_samples("n6000_f300_ap3.csv", 300.0, start.axial_depth_mm);
  const std::vector<LearningSample> fast = slot_samples("n6000_f1500_ap3.csv", 1500.0, start.axial_depth_mm);
  samples.insert(samples.end(), fast.begin(), fast.end());
  ASSERT_GE(samples.size(), 190u);

  const double scale = kAxialDepthMm / start.axial_depth_mm;  // back to the recordings' 3 mm
  const double chip_900 = 900.0 / (kFlutes * kRpm);
  const double length = kToolRadiusMm * kPi;
  const double before_n = model::predict(start, chip_900, length).force_n * scale;

  BatchRefitOptions options;
  options.loss = model::FitOptions::kHuber;
  options.loss_scale_n = 30.0;
  const BatchRefitResult refit = batch_refit(start, samples, options);
  ASSERT_EQ(refit.status, BatchRefitStatus::kOk) << refit.message;
  const double after_n = model::predict(refit.model, chip_900, length).force_n * scale;

  const double error_before = 100.0 * (before_n - kMeasuredPeak900N) / kMeasuredPeak900N;
  const double error_after = 100.0 * (after_n - kMeasuredPeak900N) / kMeasuredPeak900N;
  std::cout << "prediction at 900 mm/min: before " << before_n << " N (" << error_before << " %), after " << after_n
            << " N (" << error_after << " %), measured 495.4 N; refit on " << samples.size() << " revolutions\n";
  EXPECT_LT(std::abs(error_after), std::abs(error_before));
  EXPECT_LT(std::abs(error_after), 10.0);
}

}  // namespace
}  // namespace feedplan::learning
