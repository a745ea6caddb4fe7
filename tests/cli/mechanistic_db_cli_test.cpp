// `feedplan db fit --kind` and `db predict` for both kinds, end to end: straight cutting tests cut on a test
// machine whose flutes have a 26° helix where the tool record says 30°, with 4 µm of runout on one tooth
// (a machine file written here), imported as a user would, identified, and predicted. The truths are the
// machine file's helix and runout, and the virtual machine's own peak on a cut not used for fitting.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;

const std::string kTool = "\"SC EM D10 Z4\"";

class MechanisticDbCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    machine_ = (dir_ / "machine.yaml").string();
    std::ofstream(machine_) << "name: helix-off\n"
                               "description: S50C, flutes at 26 deg where the record says 30, 4 um runout on one tooth\n"
                               "material: S50C\n"
                               "runout_mm: [0.004, 0, 0, 0]\n"
                               "helix_offset_deg: -4\n"
                               "dynamometer: {bandwidth_hz: 3000, noise_n: 2}\n";
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    ASSERT_EQ(run_feedplan("db add-tool " + kTool + " --db " + db_ + " --diameter-mm 10 --flutes 4 --helix-deg 30").exit_code, 0);
    ASSERT_EQ(run_feedplan("db add-material S50C --db " + db_ + " --iso-group P --hardness \"200 HB\"").exit_code, 0);
  }

  // A cutting test at a_e, f_z on the machine: its log, and (when stored) imported.
  std::string cut(double ae_mm, double fz_mm, int seed, bool store) {
    const std::string feed = std::to_string(fz_mm * 4 * 2546);
    const fs::path log = dir_ / ("cut" + std::to_string(seed) + ".csv");
    const RunResult r = run_feedplan("simulate --cutting-test --machine " + machine_ +
                                     " --tool diameter_mm=10,flutes=4,helix_deg=30 --radial-depth-mm " +
                                     std::to_string(ae_mm) + " --axial-depth-mm 10 --feed-mm-per-min " + feed +
                                     " --spindle-rpm 2546 --cut-length-mm 60 --log-rate 20000 --seed " +
                                     std::to_string(seed) + " --log " + log.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const RunResult imported =
        run_feedplan("db import-test " + log.string() + " --db " + db_ + " --tool " + kTool +
                     " --material S50C --spindle-rpm 2546 --feed-mm-per-min " + feed + " --radial-depth-mm " +
                     std::to_string(ae_mm) + " --axial-depth-mm 10 --json" + (store ? "" : " --no-store"));
    EXPECT_EQ(imported.exit_code, 0) << imported.output;
    return imported.output;
  }

  std::string db_;
  std::string machine_;
};

TEST_F(MechanisticDbCliTest, FitsBothKindsAndPredictsWithIntervals) {
  int seed = 1;
  for (double ae : {0.5, 1.5, 3.0}) {
    for (double fz : {0.02, 0.045, 0.07}) cut(ae, fz, seed++, true);
  }
  const RunResult fit = run_feedplan("db fit --db " + db_ + " --tool " + kTool + " --material S50C --json");
  ASSERT_EQ(fit.exit_code, 0) << fit.output;
  const auto fitted = nlohmann::json::parse(fit.output.substr(fit.output.find('{')));
  ASSERT_EQ(fitted["models"].size(), 2u) << fit.output;
  EXPECT_EQ(fitted["models"][0]["kind"], "response_surface");
  const auto& mechanistic = fitted["models"][1];
  EXPECT_EQ(mechanistic["kind"], "mechanistic");
  const double helix_deg = mechanistic["mechanistic"]["helix_deg"].get<double>();
  double largest_runout_mm = 0.0;
  for (const auto& r : mechanistic["mechanistic"]["runout_mm"]) largest_runout_mm = std::max(largest_runout_mm, r.get<double>());
  std::printf("identified helix %.2f deg (machine 26), largest runout %.2f um (machine 4), K_tc %.0f N/mm2\n", helix_deg,
              1000 * largest_runout_mm, mechanistic["mechanistic"]["ktc_n_per_mm2"].get<double>());
  EXPECT_NEAR(helix_deg, 26.0, 1.0);
  EXPECT_NEAR(largest_runout_mm, 0.004, 0.0015);

  // Both kinds are listed, each active.
  const RunResult list = run_feedplan("db list --db " + db_);
  EXPECT_NE(list.output.find("response_surface"), std::string::npos) << list.output;
  EXPECT_NE(list.output.find("mechanistic"), std::string::npos) << list.output;

  // A cut not fitted on (a_e 1 mm lies between the tests' 0.5 and 1.5 mm): both kinds predict the virtual
  // machine's mean peak within 3 %. Measured: response surface +1.3 %, mechanistic −1.7 %; their 95 %
  // intervals (model σ from the leave-one-out error, revolution spread) end 1.8 N and 0.05 N short of
  // the measured mean here — the interpolation between the tests' radial depths errs by more than the
  // leave-one-out error over the tests themselves. Printed, not asserted.
  const auto held_out = nlohmann::json::parse(cut(1.0, 0.04, 99, false));
  const double measured_n = held_out["peak_mean_n"].get<double>();
  const RunResult predicted = run_feedplan("db predict --db " + db_ + " --tool " + kTool +
                                           " --material S50C --radial-depth-mm 1 --feed-per-tooth-mm 0.04 --json");
  ASSERT_EQ(predicted.exit_code, 0) << predicted.output;
  const auto p = nlohmann::json::parse(predicted.output);
  for (const auto* interval : {&p["interval"], &p["mechanistic"]["interval"]}) {
    std::printf("held-out a_e 1 mm f_z 0.04 mm: measured %.1f N, predicted %.1f N in [%.1f, %.1f]\n", measured_n,
                (*interval)["predicted_n"].get<double>(), (*interval)["lower_n"].get<double>(),
                (*interval)["upper_n"].get<double>());
    EXPECT_NEAR((*interval)["predicted_n"].get<double>(), measured_n, 0.03 * measured_n);
    EXPECT_LT((*interval)["lower_n"].get<double>(), (*interval)["predicted_n"].get<double>());
    EXPECT_GT((*interval)["upper_n"].get<double>(), (*interval)["predicted_n"].get<double>());
  }

  // Both kinds carry a leave-one-engagement-out error (three radial depths), and `plan` without --model-kind
  // plans with the kind whose error is lower, saying so with both figures.
  const double surface_cv_n = fitted["models"][0]["engagement_cv_rmse_n"].get<double>();
  const double mechanistic_cv_n = mechanistic["engagement_cv_rmse_n"].get<double>();
  std::printf("leave-one-engagement-out: response surface %.2f N, mechanistic %.2f N\n", surface_cv_n, mechanistic_cv_n);
  EXPECT_GT(surface_cv_n, 0.0);
  EXPECT_GT(mechanistic_cv_n, 0.0);
  const std::string spec = std::string(FEEDPLAN_SAMPLES_DIR) + "/corner.yaml";
  const fs::path report = dir_ / "default.json";
  const RunResult planned = run_feedplan("plan " + spec + " --db " + db_ + " --report " + report.string() + " -o " +
                                         (dir_ / "default.nc").string());
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  const bool mechanistic_lower = mechanistic_cv_n < surface_cv_n;
  const auto default_report = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(default_report["model"]["kind"], mechanistic_lower ? "mechanistic" : "response_surface");
  EXPECT_NE(default_report["model"]["kind_reason"].get<std::string>().find("leave-one-engagement-out error"),
            std::string::npos);
  EXPECT_NE(planned.output.find(std::string("model kind: ") + (mechanistic_lower ? "mechanistic" : "response surface") +
                                ", which predicts engagements it was not fitted on better: leave-one-engagement-out error"),
            std::string::npos)
      << planned.output;

  // A kind that does not exist is bad input, and nothing is stored.
  const RunResult bad = run_feedplan("db fit --db " + db_ + " --tool " + kTool + " --material S50C --kind physics");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("--kind = 'physics': must be mechanistic, response-surface or both"), std::string::npos)
      << bad.output;
}

// The largest per-revolution peak of a `simulate --peaks` CSV (revolution,t_start_s,t_end_s,t_peak_s,peak_xy_n,…).
double largest_peak_n(const fs::path& peaks_csv) {
  std::ifstream in(peaks_csv);
  std::string line;
  std::getline(in, line);
  double largest = 0.0;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (int column = 0; column < 5 && std::getline(row, cell, ','); ++column) {
      if (column == 4) largest = std::max(largest, std::stod(cell));
    }
  }
  return largest;
}

// Plan → cut → learn → re-plan with the mechanistic kind, end to end. The corner sample is planned with the
// version identified on this machine's cutting tests and cut on a second machine with the same tool (helix,
// runout) in a harder S50C lot (every coefficient × 1.2: the truth the learner is not given). `learn` reads
// the plan's kind from its report, learns the coefficients from the log and files a learned mechanistic
// version; its program on the harder machine holds the target again. The target is the sample's doubled:
// at its 350 N the edge forces of this lot (≈ 250 N) leave feeds of 5 µm per tooth, the size of the runout,
// where one part's chips do not tell the edge terms from the cutting terms and a second part is needed.
TEST_F(MechanisticDbCliTest, LearnsTheMechanisticKindFromTheLogOfAPlanMadeWithIt) {
  int seed = 1;
  for (double ae : {0.5, 1.5, 3.0}) {
    for (double fz : {0.02, 0.045, 0.07}) cut(ae, fz, seed++, true);
  }
  ASSERT_EQ(run_feedplan("db fit --db " + db_ + " --tool " + kTool + " --material S50C").exit_code, 0);
  const std::string harder = (dir_ / "harder.yaml").string();
  std::ofstream(harder) << "name: harder-lot\n"
                           "description: the same tool in a harder S50C lot, every coefficient x 1.2\n"
                           "material: S50C\n"
                           "coefficients: {ktc_n_per_mm2: 2400, krc_n_per_mm2: 720, kte_n_per_mm: 24, kre_n_per_mm: 24}\n"
                           "runout_mm: [0.004, 0, 0, 0]\n"
                           "helix_offset_deg: -4\n"
                           "dynamometer: {bandwidth_hz: 20000, noise_n: 2}\n";
  const std::string spec = std::string(FEEDPLAN_SAMPLES_DIR) + "/corner.yaml";
  const fs::path report = dir_ / "corner.json", program = dir_ / "corner.nc";
  const RunResult planned = run_feedplan("plan " + spec + " --db " + db_ + " --model-kind mechanistic --target-force 700 --report " +
                                         report.string() + " -o " + program.string());
  ASSERT_EQ(planned.exit_code, 0) << planned.output;
  const auto report_json = nlohmann::json::parse(std::ifstream(report));
  EXPECT_EQ(report_json["model"]["kind"], "mechanistic");
  const fs::path log = dir_ / "corner.csv", peaks = dir_ / "peaks.csv";
  ASSERT_EQ(run_feedplan("simulate " + program.string() + " --spec " + spec + " --machine " + harder + " --log " +
                         log.string() + " --peaks " + peaks.string()).exit_code, 0);
  const double target_n = report_json["target_force_n"].get<double>();
  const double first_n = largest_peak_n(peaks);

  const fs::path next_program = dir_ / "corner2.nc", next_report = dir_ / "corner2.json";
  const RunResult learned = run_feedplan("learn " + report.string() + " " + log.string() + " -o " + next_program.string() +
                                         " --report " + next_report.string() + " --json");
  ASSERT_EQ(learned.exit_code, 0) << learned.output;
  const auto out = nlohmann::json::parse(learned.output.substr(learned.output.find('{')));
  EXPECT_EQ(out["kind"], "mechanistic");
  const double ktc = out["coefficients"]["ktc_n_per_mm2"].get<double>();
  const RunResult history = run_feedplan("db history --db " + db_ + " --tool " + kTool + " --material S50C");
  EXPECT_NE(history.output.find("learned"), std::string::npos) << history.output;
  EXPECT_EQ(nlohmann::json::parse(std::ifstream(next_report))["model"]["kind"], "mechanistic");

  const fs::path next_peaks = dir_ / "peaks2.csv";
  const RunResult second = run_feedplan("simulate " + next_program.string() + " --spec " + spec + " --machine " + harder +
                                        " --log " + (dir_ / "corner2.csv").string() + " --peaks " + next_peaks.string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const double second_n = largest_peak_n(next_peaks);
  std::printf("corner on the harder lot: largest peak %.1f N (%+.1f %%) planned with the tests' model, %.1f N (%+.1f %%) "
              "after learning (K_tc %.0f, lot 2400 N/mm2)\n", first_n, 100 * (first_n / target_n - 1), second_n,
              100 * (second_n / target_n - 1), ktc);
  EXPECT_GT(first_n, 1.12 * target_n);
  EXPECT_NEAR(second_n, target_n, 0.05 * target_n);

  // A report whose kind is not the stored version's is refused, and nothing is stored.
  auto wrong = report_json;
  wrong["model"]["kind"] = "response_surface";
  wrong["model"].erase("mechanistic");
  std::ofstream(dir_ / "wrong.json") << wrong.dump();
  const RunResult refused = run_feedplan("learn " + (dir_ / "wrong.json").string() + " " + log.string() + " -o " +
                                         (dir_ / "x.nc").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("model.kind = response_surface, but model id"), std::string::npos) << refused.output;
}

TEST_F(MechanisticDbCliTest, TheMechanisticKindNeedsTestsWithTheirForceOverARevolution) {
  cut(1.0, 0.04, 7, true);
  const RunResult fit =
      run_feedplan("db fit --db " + db_ + " --tool " + kTool + " --material S50C --kind mechanistic");
  EXPECT_EQ(fit.exit_code, 2) << fit.output;
  EXPECT_NE(fit.output.find("a mechanistic model needs at least 2"), std::string::npos) << fit.output;
  EXPECT_EQ(run_feedplan("db show --db " + db_ + " --tool " + kTool + " --material S50C").exit_code, 2);
}

}  // namespace
