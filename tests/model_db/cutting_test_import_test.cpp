// Cutting-test import (model_db/cutting_test_import.hpp): real Kistler slot-milling recordings against
// their per-revolution peaks worked out independently (tests/data/kistler_full/README.md), a virtual
// cutting test against the virtual machine's noise-free per-revolution peaks, the steady-state rule on
// a synthetic log with known transients, and bad input of every kind with its message.

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "has_problem.hpp"
#include "feedplan/model_db/cutting_test_import.hpp"
#include "feedplan/sim/cutting_test.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::model_db {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::string kKistlerDir = std::string(FEEDPLAN_TEST_DATA_DIR) + "/kistler_full/";

// ---------------------------------------------------------------------------------------------------
// Helpers

using test_support::has_problem;

//! The problems an import throws; a failure when it throws none.
template <typename Import>
std::vector<InputProblem> problems_of(const Import& import) {
  try {
    import();
  } catch (const InputError& e) {
    for (const auto& p : e.problems()) std::printf("    reported: %s\n", to_string(p).c_str());
    return e.problems();
  }
  ADD_FAILURE() << "the import accepted it";
  return {};
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

//! A scratch file removed when the test ends.
class ScratchFile {
 public:
  ScratchFile(const std::string& name, const std::string& text)
      : path_((std::filesystem::temp_directory_path() /
               ("feedplan_import_" + std::to_string(::getpid()) + "_" + name))
                  .string()) {
    std::ofstream(path_, std::ios::binary) << text;
  }
  ~ScratchFile() { std::filesystem::remove(path_); }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// The lines of a text (without their '\n').
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count && i < lines.size(); ++i) text += lines[i] + "\n";
  return text;
}

// ---------------------------------------------------------------------------------------------------
// (a) Real slot-milling forces, Kistler DynoWare exports (tests/data/kistler_full/README.md)

// The recordings' tool diameter is not stated in the source; 10 mm is assumed. It only enters
// L = r · π, the same for all three; f_z and t_m (= f_z in a slot) do not depend on it.
const geometry::Tool kKistlerTool{"assumed D10 Z2 (diameter not stated in the source)", 10.0, 2, 30.0};

CuttingTestConditions kistler_conditions(double feed_mm_per_min) {
  CuttingTestConditions c;
  c.tool_name = kKistlerTool.name;
  c.material_name = "not stated";
  c.spindle_rpm = 6000;
  c.feed_mm_per_min = feed_mm_per_min;
  c.radial_depth_mm = 10.0;
  c.axial_depth_mm = 3.0;
  c.mode = CutMode::kSlot;
  return c;
}

TEST(CuttingTestImport, KistlerSlotRecordingsGiveTheirSteadyPeaks) {
  struct Case {
    const char* file;
    double feed_mm_per_min;
    double fz_mm;
    double expected_mean_n;  // mean per-revolution peak over the whole second, worked out independently
  };
  const Case cases[] = {{"n6000_f300_ap3.csv", 300, 0.025, 245.4},
                        {"n6000_f900_ap3.csv", 900, 0.075, 495.4},
                        {"n6000_f1500_ap3.csv", 1500, 0.125, 761.2}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    const std::string path = kKistlerDir + c.file;
    const CuttingTestRecord r = import_cutting_test(path, kistler_conditions(c.feed_mm_per_min), kKistlerTool);
    std::printf("%-22s steady peak %7.1f ± %5.1f N (min %6.1f, max %6.1f) over %d of %d revolutions | expected %.1f N "
                "(%+.2f %%) | f_z %.3f mm, t_m %.3f mm, L %.3f mm\n",
                c.file, r.peak_mean_n, r.peak_std_n, r.peak_min_n, r.peak_max_n, r.revolutions_used,
                r.revolutions_total, c.expected_mean_n, 100 * (r.peak_mean_n - c.expected_mean_n) / c.expected_mean_n,
                r.feed_per_tooth_mm, r.chip_mm, r.contact_length_mm);
    for (const auto& note : r.notes) std::printf("    note: %s\n", note.c_str());
    EXPECT_NEAR(r.peak_mean_n, c.expected_mean_n, 0.02 * c.expected_mean_n);
    // 1 s at 6000 rpm: 100 revolutions; the recordings are mid-cut, so nearly all are steady.
    EXPECT_EQ(r.revolutions_total, 100);
    EXPECT_GE(r.revolutions_used, 90);
    EXPECT_EQ(static_cast<int>(r.steady_peaks_n.size()), r.revolutions_used);
    EXPECT_LE(r.peak_min_n, r.peak_mean_n);
    EXPECT_GE(r.peak_max_n, r.peak_mean_n);
    EXPECT_GT(r.peak_std_n, 0.0);
    EXPECT_DOUBLE_EQ(r.feed_per_tooth_mm, c.fz_mm);  // 300 / (2 · 6000) = 0.025 …
    EXPECT_DOUBLE_EQ(r.chip_mm, c.fz_mm);            // slot: sin(min(π, π/2)) = 1
    EXPECT_DOUBLE_EQ(r.contact_length_mm, 5.0 * kPi);
    EXPECT_EQ(r.source, path);
  }
}

TEST(CuttingTestImport, KistlerSpreadGrowsWithFeedAsTheSourceSays) {
  // The source's README: the 1500 mm/min run is noticeably less steady (560–916 N per revolution).
  const CuttingTestRecord slow = import_cutting_test(kKistlerDir + "n6000_f300_ap3.csv", kistler_conditions(300), kKistlerTool);
  const CuttingTestRecord fast =
      import_cutting_test(kKistlerDir + "n6000_f1500_ap3.csv", kistler_conditions(1500), kKistlerTool);
  EXPECT_LT(slow.peak_std_n / slow.peak_mean_n, 0.02);
  EXPECT_GT(fast.peak_std_n / fast.peak_mean_n, 0.05);
  EXPECT_NEAR(fast.peak_min_n, 560, 5);
  EXPECT_NEAR(fast.peak_max_n, 916, 5);
}

// ---------------------------------------------------------------------------------------------------
// (b) A virtual cutting test: the virtual machine knows the true per-revolution peaks

const geometry::Tool kSimTool{"SC EM D10 Z4", 10.0, 4, 30.0};
constexpr double kSimRpm = 2800;
constexpr double kSimFeed = 0.1 * 4 * kSimRpm;  // f_z 0.1 mm: 1120 mm/min
constexpr double kSimAe = 3.0;
constexpr double kSimAp = 5.0;
constexpr double kSimLength = 40.0;

// Al7075-T6 (Altintas, Manufacturing Automation, Table 2.1), as in the sim tests.
sim::CuttingCoefficients al7075() {
  sim::CuttingCoefficients k;
  k.ktc_n_per_mm2 = 796;
  k.krc_n_per_mm2 = 169;
  k.kac_n_per_mm2 = 222;
  k.kte_n_per_mm = 27.7;
  k.kre_n_per_mm = 30.8;
  k.kae_n_per_mm = 1.4;
  return k;
}

// One simulated down-milling test with dynamometer noise, run once for every test that needs it.
const sim::SimulationResult& simulated_test() {
  static const sim::SimulationResult result = [] {
    sim::CuttingTest test;
    test.radial_depth_mm = kSimAe;
    test.axial_depth_mm = kSimAp;
    test.feed_mm_per_min = kSimFeed;
    test.spindle_rpm = kSimRpm;
    test.cut_length_mm = kSimLength;
    test.mode = sim::MillingMode::kDown;
    const sim::CuttingTestSetup setup = sim::make_cutting_test(test, kSimTool);
    sim::SimulationRequest request;
    request.program = setup.program;
    request.stock = setup.stock;
    request.tool = kSimTool;
    request.coefficients = al7075();
    request.machine.max_accel_mm_per_s2 = 2000;
    request.sensors.dynamometer.noise_n = 2.0;
    request.sensors.seed = 7;
    return sim::simulate(request);
  }();
  return result;
}

CuttingTestConditions sim_conditions() {
  CuttingTestConditions c;
  c.tool_name = kSimTool.name;
  c.material_name = "Al7075-T6";
  c.spindle_rpm = kSimRpm;
  c.feed_mm_per_min = kSimFeed;
  c.radial_depth_mm = kSimAe;
  c.axial_depth_mm = kSimAp;
  c.mode = CutMode::kDown;
  return c;
}

TEST(CuttingTestImport, SimulatedTestMatchesTheTrueSteadyPeak) {
  const sim::SimulationResult& result = simulated_test();
  // Truth: the noise-free peaks of the revolutions during which the whole tool is inside the block's
  // length (centre x in [r, L − r]) — full engagement, at full feed. Taken from the virtual machine's
  // own revolution record, not from the log the import reads.
  double t_lo = 1e300, t_hi = -1e300;
  for (const auto& row : result.log.rows) {
    if (row.x_mm >= 5.0 && row.x_mm <= kSimLength - 5.0 && row.z_mm < -1.0) {
      t_lo = std::min(t_lo, row.t_s);
      t_hi = std::max(t_hi, row.t_s);
    }
  }
  double truth_sum = 0.0;
  int truth_count = 0;
  for (const auto& rev : result.revolutions) {
    if (rev.t_start_s < t_lo || rev.t_end_s > t_hi) continue;
    truth_sum += rev.peak_xy_n;
    ++truth_count;
  }
  ASSERT_GT(truth_count, 50);
  const double truth = truth_sum / truth_count;

  // Through a file, as a user would: written by the log writer, read back by the import.
  const ScratchFile file("simulated.csv", force_log::format_force_log(result.log));
  const CuttingTestRecord r = import_cutting_test(file.path(), sim_conditions(), kSimTool);
  std::printf("simulated: import %.2f ± %.2f N over %d of %d revolutions | true steady peak %.2f N over %d "
              "fully engaged revolutions | %+.3f %%\n",
              r.peak_mean_n, r.peak_std_n, r.revolutions_used, r.revolutions_total, truth, truth_count,
              100 * (r.peak_mean_n - truth) / truth);
  for (const auto& note : r.notes) std::printf("    note: %s\n", note.c_str());
  EXPECT_NEAR(r.peak_mean_n, truth, 0.01 * truth);
  // The steady part covers the fully engaged stretch (and not much more: entry and exit are trimmed).
  EXPECT_GE(r.revolutions_used, truth_count - 2);
  EXPECT_LE(r.revolutions_used, truth_count + 25);

  // Where the steady revolutions lie: find them among the log's revolutions, then check that the
  // virtual machine's noise-free peaks in that time window hold no transient (each within 1 % of the
  // fully engaged mean).
  const std::vector<force_log::RevolutionPeak> logged = [&] {
    const force_log::ForceLog log = force_log::load_force_log(file.path());
    std::vector<double> t, fx, fy;
    for (const auto& row : log.rows) {
      t.push_back(row.t_s);
      fx.push_back(row.fx_n);
      fy.push_back(row.fy_n);
    }
    return force_log::revolution_peaks(t, fx, fy, kSimRpm);
  }();
  std::size_t first = logged.size();
  for (std::size_t j = 0; j + r.steady_peaks_n.size() <= logged.size() && first == logged.size(); ++j) {
    bool match = true;
    for (std::size_t i = 0; i < r.steady_peaks_n.size() && match; ++i) {
      match = logged[j + i].peak_xy_n == r.steady_peaks_n[i];
    }
    if (match) first = j;
  }
  ASSERT_LT(first, logged.size()) << "the steady peaks are not a run of the log's revolutions";
  const double steady_from = logged[first].t_start_s;
  const double steady_to = logged[first + r.steady_peaks_n.size() - 1].t_end_s;
  int inside = 0;
  for (const auto& rev : result.revolutions) {
    if (rev.t_start_s < steady_from - 1e-6 || rev.t_end_s > steady_to + 1e-6) continue;  // not wholly inside
    EXPECT_NEAR(rev.peak_xy_n, truth, 0.01 * truth) << "true peak of the revolution at t = " << rev.t_start_s << " s";
    ++inside;
  }
  std::printf("steady window t %.4f–%.4f s: %d true revolutions, each within 1 %% of %.2f N\n", steady_from, steady_to,
              inside, truth);

  // Model inputs: α_en = acos(1 − a_e / r) = acos(0.4), t_m = f_z sin(min(α_en, π/2)), L = r α_en.
  const double alpha = std::acos(1.0 - kSimAe / 5.0);
  EXPECT_NEAR(r.feed_per_tooth_mm, 0.1, 1e-12);
  EXPECT_NEAR(r.chip_mm, 0.1 * std::sin(alpha), 1e-12);
  EXPECT_NEAR(r.contact_length_mm, 5.0 * alpha, 1e-12);
}

// ---------------------------------------------------------------------------------------------------
// The steady-state rule on a synthetic log whose transients are known

// 6000 rpm, 10 kHz: 100 samples per revolution. Revolution k's force is A_k |sin(2π θ)| along x
// (θ: fraction of the revolution), so its peak is A_k exactly.
force_log::ForceLog synthetic_log(const std::vector<double>& amplitudes_n) {
  force_log::ForceLog log;
  log.has_positions = false;
  log.metadata = {{"sample_rate_hz", "10000"}};
  for (std::size_t k = 0; k < amplitudes_n.size(); ++k) {
    for (int i = 0; i < 100; ++i) {
      force_log::ForceLogRow row{};
      row.t_s = (static_cast<double>(k) * 100 + i) * 1e-4;
      row.x_mm = row.y_mm = row.z_mm = kNaN;
      row.fx_n = amplitudes_n[k] * std::abs(std::sin(2 * kPi * i / 100.0));
      row.fy_n = 0.0;
      row.fz_n = kNaN;
      row.feed_mm_per_min = row.spindle_rpm = kNaN;
      log.rows.push_back(row);
    }
  }
  force_log::ForceLogRow end{};  // one more sample closes the last revolution
  end.t_s = static_cast<double>(amplitudes_n.size()) * 0.01;
  end.x_mm = end.y_mm = end.z_mm = end.fz_n = end.feed_mm_per_min = end.spindle_rpm = kNaN;
  log.rows.push_back(end);
  return log;
}

// The force over one revolution, averaged over the steady ones: with no runout every tooth cuts alike, so
// the average repeats every tooth period (a shift by bins / flutes), and its largest |F_xy| is the steady
// per-revolution peak (the dynamometer's 2 N noise averages out; 2° bins round the pulse's top).
TEST(CuttingTestImport, SimulatedTestKeepsItsForceOverARevolution) {
  const ScratchFile file("simulated.csv", force_log::format_force_log(simulated_test().log));
  const CuttingTestRecord r = import_cutting_test(file.path(), sim_conditions(), kSimTool);
  const std::size_t bins = r.synchronous_fx_n.size();
  ASSERT_GE(bins, 36u);
  ASSERT_EQ(r.synchronous_fy_n.size(), bins);
  double largest = 0.0;
  for (std::size_t b = 0; b < bins; ++b) largest = std::max(largest, std::hypot(r.synchronous_fx_n[b], r.synchronous_fy_n[b]));
  EXPECT_NEAR(largest, r.peak_mean_n, 0.05 * r.peak_mean_n);
  const auto shift = static_cast<std::size_t>(std::lround(static_cast<double>(bins) / kSimTool.flutes));
  for (std::size_t b = 0; b < bins; ++b) {
    const std::size_t c = (b + shift) % bins;
    EXPECT_NEAR(r.synchronous_fx_n[c], r.synchronous_fx_n[b], 0.06 * largest) << "bin " << b;
    EXPECT_NEAR(r.synchronous_fy_n[c], r.synchronous_fy_n[b], 0.06 * largest) << "bin " << b;
  }
}

TEST(CuttingTestImport, SteadyRuleDropsAirAndRampsButKeepsInteriorScatter) {
  // 5 in the air, a 10-revolution ramp up, 50 steady (100 ± 0.5 N, one at 70 N in the middle), a
  // 10-revolution ramp down, 5 in the air.
  std::vector<double> a(5, 0.0);
  for (int k = 1; k <= 10; ++k) a.push_back(10.0 * k - 5.0);  // 5 … 95 N
  const std::size_t steady_begin = a.size();
  for (int k = 0; k < 50; ++k) a.push_back(k == 25 ? 70.0 : (k % 2 == 0 ? 100.5 : 99.5));
  const std::size_t steady_end = a.size();
  for (int k = 10; k >= 1; --k) a.push_back(10.0 * k - 5.0);
  for (int k = 0; k < 5; ++k) a.push_back(0.0);

  CuttingTestConditions c = kistler_conditions(300);
  CuttingTestImportOptions options;
  options.source_name = "synthetic";
  const CuttingTestRecord r = import_cutting_test(synthetic_log(a), c, kKistlerTool, options);
  EXPECT_EQ(r.revolutions_total, static_cast<int>(a.size()));
  ASSERT_EQ(r.revolutions_used, static_cast<int>(steady_end - steady_begin));
  const std::vector<double> expected(a.begin() + static_cast<std::ptrdiff_t>(steady_begin),
                                     a.begin() + static_cast<std::ptrdiff_t>(steady_end));
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(r.steady_peaks_n[i], expected[i], 1e-9) << i;
  EXPECT_NEAR(r.peak_mean_n, (25 * 100.5 + 24 * 99.5 + 70.0) / 50.0, 1e-9);
  EXPECT_NEAR(r.peak_min_n, 70.0, 1e-9);
  EXPECT_NEAR(r.peak_max_n, 100.5, 1e-9);
}

// ---------------------------------------------------------------------------------------------------
// (c) Bad input

TEST(CuttingTestImportBadInput, TruncatedLogNamesTheFileAndLine) {
  // Cut the 300 mm/min recording in the middle of its row on line 5021 (t = 8.5 s): "8.5,<Fx digits>".
  std::vector<std::string> lines = lines_of(read_text(kKistlerDir + "n6000_f300_ap3.csv"));
  ASSERT_GT(lines.size(), 5021u);
  std::string text = join_lines(lines, 5020);
  text += lines[5020].substr(0, lines[5020].find(',') + 3);  // no newline: the file ends here
  const ScratchFile file("truncated.csv", text);
  const auto problems =
      problems_of([&] { import_cutting_test(file.path(), kistler_conditions(300), kKistlerTool); });
  EXPECT_TRUE(has_problem(problems, file.path() + " line 5021", "has 2 cells, the channel row (line 19) has 4"));
}

TEST(CuttingTestImportBadInput, NonMonotonicTimeNamesTheLine) {
  std::vector<std::string> lines = lines_of(read_text(kKistlerDir + "n6000_f300_ap3.csv"));
  ASSERT_EQ(lines[1020].substr(0, 4), "8.1,");
  lines[1020].replace(0, 3, "8.0");  // line 1021: t = 8.0 after 8.0999
  const ScratchFile file("backwards.csv", join_lines(lines, lines.size()));
  const auto problems =
      problems_of([&] { import_cutting_test(file.path(), kistler_conditions(300), kKistlerTool); });
  EXPECT_TRUE(has_problem(problems, file.path() + " line 1021, t_s", "= 8: must be after 8.0999 on line 1020"));
}

TEST(CuttingTestImportBadInput, MissingColumnsAreNamed) {
  const ScratchFile file("no_fy.csv",
                         "# spindle_rpm: 2800\n"
                         "t_s,x_mm,y_mm,fx_n\n"
                         "0,0,0,1\n"
                         "0.0001,0,0,2\n");
  const auto problems = problems_of([&] { import_cutting_test(file.path(), sim_conditions(), kSimTool); });
  EXPECT_TRUE(has_problem(problems, file.path() + " line 2 (header)", "lacks the column fy_n"));
}

TEST(CuttingTestImportBadInput, MissingFileIsNamed) {
  const std::string path = kKistlerDir + "no_such_file.csv";
  const auto problems = problems_of([&] { import_cutting_test(path, kistler_conditions(300), kKistlerTool); });
  ASSERT_FALSE(problems.empty());
  EXPECT_NE(to_string(problems.front()).find(path), std::string::npos) << to_string(problems.front());
}

TEST(CuttingTestImportBadInput, SpindleSpeedContradictingTheLog) {
  CuttingTestConditions c = sim_conditions();
  c.spindle_rpm = 3000;                      // the log was recorded at 2800
  c.feed_mm_per_min = 0.1 * 4 * 3000;        // keep f_z; the feed contradicts too, reported alongside
  const auto problems = problems_of([&] { import_cutting_test(simulated_test().log, c, kSimTool); });
  EXPECT_TRUE(has_problem(problems, "conditions.spindle_rpm",
                          "= 3000 rev/min, but force log says 2800 (# spindle_rpm): 7.1 % apart, more than 1.0 %"));
  EXPECT_TRUE(has_problem(problems, "conditions.spindle_rpm", "the spindle_rpm column of force log reads 2800"));

  // Within 1 % is accepted.
  c = sim_conditions();
  c.spindle_rpm = kSimRpm * 1.008;
  EXPECT_NO_THROW(import_cutting_test(simulated_test().log, c, kSimTool));
}

TEST(CuttingTestImportBadInput, FeedContradictingThePositions) {
  // No feed column (empty cells): the feed comes from x_mm, y_mm only.
  force_log::ForceLog log = simulated_test().log;
  for (auto& row : log.rows) row.feed_mm_per_min = kNaN;
  CuttingTestConditions c = sim_conditions();
  c.feed_mm_per_min = 1000;  // the positions move at 1120
  CuttingTestImportOptions options;
  options.source_name = "sim.csv";
  const auto problems = problems_of([&] { import_cutting_test(log, c, kSimTool, options); });
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_TRUE(has_problem(problems, "conditions.feed_mm_per_min",
                          "= 1000 mm/min, but the positions (x_mm, y_mm) in sim.csv move at 1120 mm/min in the steady "
                          "part: 10.7 % apart, more than 2.0 %"));

  // 1.5 % off is accepted.
  c.feed_mm_per_min = kSimFeed * 1.015;
  EXPECT_NO_THROW(import_cutting_test(log, c, kSimTool, options));
}

TEST(CuttingTestImportBadInput, FeedContradictingTheFeedColumn) {
  CuttingTestConditions c = sim_conditions();
  c.feed_mm_per_min = 1200;
  const auto problems = problems_of([&] { import_cutting_test(simulated_test().log, c, kSimTool); });
  EXPECT_TRUE(has_problem(problems, "conditions.feed_mm_per_min",
                          "= 1200 mm/min, but the feed_mm_per_min column of force log reads 1120 in the steady part"));
  EXPECT_TRUE(has_problem(problems, "conditions.feed_mm_per_min", "the positions (x_mm, y_mm) in force log move at"));
}

TEST(CuttingTestImportBadInput, SampleRateMetadataContradictingTheTimeColumn) {
  force_log::ForceLog log = simulated_test().log;
  for (auto& [key, value] : log.metadata) {
    if (key == "sample_rate_hz") value = "5000";
  }
  const auto problems = problems_of([&] { import_cutting_test(log, sim_conditions(), kSimTool); });
  EXPECT_TRUE(has_problem(problems, "force log sample_rate_hz",
                          "= 5000 Hz, but the time column steps by 0.0001 s (10000 Hz): 50.0 % apart"));
}

TEST(CuttingTestImportBadInput, TooShortALogSaysHowManyRevolutions) {
  // The first 500 samples of the 300 mm/min recording: 5 revolutions at 6000 rpm.
  const std::vector<std::string> lines = lines_of(read_text(kKistlerDir + "n6000_f300_ap3.csv"));
  const ScratchFile file("short.csv", join_lines(lines, 20 + 500));
  const auto problems =
      problems_of([&] { import_cutting_test(file.path(), kistler_conditions(300), kKistlerTool); });
  EXPECT_TRUE(has_problem(problems, file.path(),
                          "has 5 steady revolutions (of 5 complete revolutions at 6000 rev/min): at least 8 are "
                          "needed"));
}

TEST(CuttingTestImportBadInput, NaNInTheConditions) {
  CuttingTestConditions c = kistler_conditions(300);
  c.spindle_rpm = kNaN;
  c.axial_depth_mm = kNaN;
  const auto problems =
      problems_of([&] { import_cutting_test(kKistlerDir + "n6000_f300_ap3.csv", c, kKistlerTool); });
  EXPECT_TRUE(has_problem(problems, "conditions.spindle_rpm", "= nan: must be a finite number > 0 rev/min"));
  EXPECT_TRUE(has_problem(problems, "conditions.axial_depth_mm", "= nan: must be a finite number > 0 mm"));
}

TEST(CuttingTestImportBadInput, RadialDepthAboveTheDiameter) {
  CuttingTestConditions c = kistler_conditions(300);
  c.radial_depth_mm = 12;
  const auto problems = problems_of([&] { import_cutting_test(synthetic_log({}), c, kKistlerTool); });
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_TRUE(has_problem(problems, "conditions.radial_depth_mm",
                          "= 12: must be in (0, 10] mm — at most the tool diameter (tool.diameter_mm = 10)"));
}

TEST(CuttingTestImportBadInput, SlotModeAndFullRadialDepthGoTogether) {
  CuttingTestConditions c = kistler_conditions(300);
  c.radial_depth_mm = 8;  // slot mode, partial depth
  EXPECT_TRUE(has_problem(validate(c, kKistlerTool), "conditions.mode",
                          "= slot: a slot cuts the full tool diameter, but radial_depth_mm = 8"));
  c.radial_depth_mm = 10;
  c.mode = CutMode::kDown;  // full depth, not slot mode
  EXPECT_TRUE(has_problem(validate(c, kKistlerTool), "conditions.mode", "= down: radial_depth_mm = 10 is the tool "
                                                                        "diameter, which is a full slot — use slot"));
  c.mode = CutMode::kSlot;
  EXPECT_TRUE(validate(c, kKistlerTool).empty());
}

TEST(CuttingTestImportBadInput, BadTool) {
  geometry::Tool tool = kKistlerTool;
  tool.diameter_mm = -10;
  tool.flutes = 0;
  const auto problems = validate(kistler_conditions(300), tool);
  EXPECT_TRUE(has_problem(problems, "tool.diameter_mm", "= -10: must be a finite number > 0 mm"));
  EXPECT_TRUE(has_problem(problems, "tool.flutes", "= 0: must be at least 1"));
}

TEST(CuttingTestImportBadInput, LogWithoutForces) {
  force_log::ForceLog log = synthetic_log(std::vector<double>(20, 100.0));
  log.has_forces = false;
  log.has_currents = true;
  CuttingTestImportOptions options;
  options.source_name = "currents.csv";
  const auto problems = problems_of([&] { import_cutting_test(log, kistler_conditions(300), kKistlerTool, options); });
  EXPECT_TRUE(has_problem(problems, "currents.csv", "has no force columns (fx_n, fy_n)"));
}

}  // namespace
}  // namespace feedplan::model_db
