// End-to-end tests of `feedplan simulate`: a cutting test and a G-code program run and write a force
// log; bad programs, materials, stocks and flags exit 2 naming the line or field and leave an
// existing log exactly as it was.

#include <gtest/gtest.h>

#include <string>

#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;

const std::string kTool = "--tool diameter_mm=10,flutes=4,helix_deg=30";

const std::string kProgram =
    "%\n"
    "O0100 (side cut along a block)\n"
    "G21 G17 G90\n"
    "M3 S6000\n"
    "G0 X-10 Y0 Z5\n"
    "G0 Z-3\n"
    "G1 X20 F600\n"
    "G2 X30 Y-10 I0 J-10\n"
    "G0 Z5\n"
    "M5\n"
    "M30\n"
    "%\n";

const std::string kStock =
    "stock:\n"
    "  z_bottom_mm: -10\n"
    "  z_top_mm: 0\n"
    "  regions:\n"
    "    - outer: {polygon: [[0, -40], [40, -40], [40, -3.5], [0, -3.5]]}\n";

class SimulateCliTest : public CliTest {
 protected:
  // Runs `feedplan simulate <arguments> --log <existing log>` and checks that it exits 2 with
  // `fragment` in its message and the log untouched.
  void expect_bad_input(const std::string& arguments, const std::string& fragment) {
    const fs::path log = dir_ / "existing.csv";
    std::ofstream(log) << "previous log\n";
    const RunResult r = run_feedplan("simulate " + arguments + " --log " + log.string());
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(fragment), std::string::npos) << "expected '" << fragment << "' in:\n" << r.output;
    EXPECT_EQ(read_text(log), "previous log\n") << arguments;
  }
};

TEST_F(SimulateCliTest, CuttingTestWritesALogAndASummary) {
  const fs::path log = dir_ / "test.csv";
  const fs::path plot = dir_ / "test.svg";
  const fs::path peaks = dir_ / "peaks.csv";
  const RunResult r = run_feedplan("simulate --cutting-test " + kTool +
                                   " --material Al7075-T6 --radial-depth-mm 1.5 --axial-depth-mm 10"
                                   " --feed-mm-per-min 1120 --spindle-rpm 2800 --log-rate 5000 --json --log " +
                                   log.string() + " --plot " + plot.string() +
                                   " --peaks " + peaks.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"max_revolution_peak_n\""), std::string::npos) << r.output;
  const std::string text = read_text(log);
  EXPECT_NE(text.find("# sample_rate_hz: 5000"), std::string::npos);
  EXPECT_NE(text.find("# material: Al7075-T6"), std::string::npos);
  EXPECT_NE(text.find("t_s,x_mm,y_mm,z_mm,fx_n,fy_n,fz_n,feed_mm_per_min,spindle_rpm\n"), std::string::npos);
  EXPECT_NE(read_text(plot).find("<svg"), std::string::npos);
  const std::string peak_text = read_text(peaks);
  EXPECT_EQ(peak_text.rfind("revolution,t_start_s,t_end_s,t_peak_s,peak_xy_n,mean_xy_n\n0,", 0), 0u) << peak_text.substr(0, 200);
}

TEST_F(SimulateCliTest, TheSampleProgramRunsWithItsSpec) {
  const fs::path log = dir_ / "trochoid.csv";
  const RunResult r = run_feedplan("simulate " + std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid_constant_feed.ngc --spec " +
                                   std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid.yaml --log-rate 1000 --log " + log.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("material S50C"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
}

TEST_F(SimulateCliTest, ProgramRunsOnAGivenStock) {
  const fs::path program = write_spec("side.ngc", kProgram);
  const fs::path stock = write_spec("stock.yaml", kStock);
  const fs::path log = dir_ / "side.csv";
  const RunResult r = run_feedplan("simulate " + program.string() + " " + kTool + " --material S50C --stock " +
                                   stock.string() + " --currents --log " + log.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("cycle time"), std::string::npos) << r.output;
  EXPECT_NE(read_text(log).find(",ix_a,iy_a,iz_a\n"), std::string::npos);
}

TEST_F(SimulateCliTest, BadProgramsNameTheLineAndWord) {
  const fs::path stock = write_spec("stock.yaml", kStock);
  const std::string common = kTool + " --material S50C --stock " + stock.string();
  auto program_with = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string text = kProgram;
    text.replace(text.find(from), from.size(), to);
    return write_spec(name, text).string();
  };
  expect_bad_input(program_with("q.ngc", "G1 X20 F600", "G1 X20 F600 Q5") + " " + common, "line 7");
  expect_bad_input(program_with("nof.ngc", "G1 X20 F600", "G1 X20") + " " + common, "line 7");
  expect_bad_input(program_with("arc.ngc", "I0 J-10", "I0 J-12") + " " + common, "line 8");
  expect_bad_input(program_with("nan.ngc", "G1 X20 F600", "G1 Xnan F600") + " " + common, "line 7");
  expect_bad_input((dir_ / "missing.ngc").string() + " " + common, "missing.ngc");
}

TEST_F(SimulateCliTest, BadMaterialsStocksAndFlagsNameTheField) {
  const fs::path program = write_spec("side.ngc", kProgram);
  const fs::path stock = write_spec("stock.yaml", kStock);
  const std::string run = program.string() + " " + kTool + " --stock " + stock.string();
  expect_bad_input(run + " --material S55C", "did you mean S50C");
  const fs::path materials = write_spec("materials.yaml",
                                        "materials:\n"
                                        "  - name: Foo\n"
                                        "    source: test\n"
                                        "    coefficients: {ktc_n_per_mm2: -5, krc_n_per_mm2: 1, kac_n_per_mm2: 1,"
                                        " kte_n_per_mm: 1, kre_n_per_mm: 1, kae_n_per_mm: 1}\n");
  expect_bad_input(run + " --material Foo --materials " + materials.string(), "ktc_n_per_mm2");
  const fs::path bad_stock = write_spec("bad_stock.yaml",
                                        "stock:\n  z_bottom_mm: -10\n  z_top_mm: 0\n  regions:\n"
                                        "    - outer: {circle: {center: [0, 0], radius_mm: -4}}\n");
  expect_bad_input(program.string() + " " + kTool + " --material S50C --stock " + bad_stock.string(),
                   "stock.regions[0].outer.circle.radius_mm (line 5)");
  expect_bad_input(program.string() + " --tool diameter_mm=ten --material S50C", "--tool diameter_mm");
  expect_bad_input(program.string() + " --tool diameter_mm=10,flutez=4 --material S50C", "flutez");
  expect_bad_input(run + " --material S50C --runout-mm 0.01,0.02", "options.runout_mm");
  expect_bad_input(run + " --material S50C --noise-n -1", "--noise-n");
  expect_bad_input(run + " --material S50C --cutting-test", "not both");
  expect_bad_input("--cutting-test " + kTool + " --material S50C --radial-depth-mm 12 --axial-depth-mm 10"
                   " --feed-mm-per-min 500 --spindle-rpm 3000",
                   "--radial-depth-mm = 12");
}

// Checked with the flags, before the simulation runs; a write that fails is exit 1.
TEST_F(SimulateCliTest, ALogInAMissingDirectoryIsBadInputAndAFullDeviceAFailure) {
  const std::string cut = "simulate --cutting-test " + kTool +
                          " --material S50C --radial-depth-mm 1 --axial-depth-mm 5 --feed-mm-per-min 500 --spindle-rpm 3000";
  const RunResult r = run_feedplan(cut + " --log /nonexistent-dir/x.csv");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--log = '/nonexistent-dir/x.csv': directory '/nonexistent-dir' does not exist"), std::string::npos)
      << r.output;
  if (!std::filesystem::is_character_file("/dev/full")) return;
  const RunResult full = run_feedplan(cut + " --log /dev/full");
  EXPECT_EQ(full.exit_code, 1) << full.output;
  EXPECT_NE(full.output.find("cannot write /dev/full: No space left on device"), std::string::npos) << full.output;
  EXPECT_EQ(full.output.find("written to"), std::string::npos) << full.output;
}

}  // namespace

namespace {

const std::string kMachines = std::string(FEEDPLAN_SAMPLES_DIR) + "/../data/machines";
const std::string kMachineCut =
    "--cutting-test --tool diameter_mm=10,flutes=4,helix_deg=30 --radial-depth-mm 2 --axial-depth-mm 10"
    " --feed-mm-per-min 560 --spindle-rpm 2800 --cut-length-mm 20 --log-rate 5000";

TEST_F(SimulateCliTest, AMachineFileSetsThePhysicsAndIsRecordedInTheLog) {
  const fs::path log = dir_ / "machine.csv";
  const RunResult r = run_feedplan("simulate " + kMachineCut + " --machine " + kMachines + "/steel-worn.yaml --log " + log.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("material S50C"), std::string::npos) << r.output;
  EXPECT_NE(read_text(log).find("# machine: steel-worn ("), std::string::npos);
  const RunResult plain = run_feedplan("simulate " + kMachineCut + " --material S50C --log " + (dir_ / "plain.csv").string() + " --json");
  const RunResult worn = run_feedplan("simulate " + kMachineCut + " --machine " + kMachines + "/steel-worn.yaml --log " +
                                      (dir_ / "worn.csv").string() + " --json");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  ASSERT_EQ(worn.exit_code, 0) << worn.output;
  EXPECT_NE(plain.output, worn.output);  // other coefficients, runout and helix: other forces
}

TEST_F(SimulateCliTest, AMachineFileConflictsWithTheFlagsItSets) {
  const std::string machine = " --machine " + kMachines + "/steel-mild.yaml";
  expect_bad_input(kMachineCut + machine + " --material S50C", "--material conflicts with --machine");
  expect_bad_input(kMachineCut + machine + " --noise-n 2", "--noise-n conflicts with --machine");
  expect_bad_input(kMachineCut + machine + " --runout-mm 0.01,0,0,0", "--runout-mm conflicts with --machine");
}

TEST_F(SimulateCliTest, BadMachineFilesNameTheFieldAndLine) {
  const fs::path bad = dir_ / "bad.yaml";
  std::ofstream(bad) << "name: x\nmaterial: S50C\nruonut_mm: [0.005, 0, 0, 0]\nhelix_offset_deg: 2\n"
                        "dynamometer: {bandwidth_hz: 800, noise_n: 8}\n";
  expect_bad_input(kMachineCut + " --machine " + bad.string(), bad.string() + ": ruonut_mm (line 3) is not a known field");
  expect_bad_input(kMachineCut + " --machine " + (dir_ / "missing.yaml").string(), "missing.yaml");
  expect_bad_input("--cutting-test --tool diameter_mm=6,flutes=3,helix_deg=35 --radial-depth-mm 1 "
                   "--axial-depth-mm 6 --feed-mm-per-min 500 --spindle-rpm 4000 --machine " + kMachines + "/steel-mild.yaml",
                   "runout_mm has 4 values: must have one per flute");
}

}  // namespace
