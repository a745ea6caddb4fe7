// End-to-end tests of `feedplan db`: a database built from a virtual cutting test, and every kind of
// bad input (corrupt or newer database, duplicate names, bad values, broken logs, conditions that
// contradict the log) exiting 2 with the field named and the database unchanged.

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;

const std::string kTool = "\"SC EM D10 Z4\"";

class DbCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    ASSERT_EQ(run_feedplan("db add-tool " + kTool + " --db " + db_ + " --diameter-mm 10 --flutes 4 --helix-deg 30").exit_code, 0);
    ASSERT_EQ(run_feedplan("db add-material S50C --db " + db_ + " --iso-group P --hardness \"200 HB\"").exit_code, 0);
  }

  // A simulated cutting test at 400 mm/min, 2546 rpm, a_e 1.5, a_p 10, written to `name`.
  fs::path cutting_log(const std::string& name) {
    const fs::path log = dir_ / name;
    const RunResult r = run_feedplan(
        "simulate --cutting-test --tool diameter_mm=10,flutes=4,helix_deg=30 --material S50C --radial-depth-mm 1.5"
        " --axial-depth-mm 10 --feed-mm-per-min 400 --spindle-rpm 2546 --cut-length-mm 30 --log-rate 20000 --log " +
        log.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return log;
  }

  std::string import_args(const fs::path& log, const std::string& rpm = "2546") {
    return "db import-test " + log.string() + " --db " + db_ + " --tool " + kTool + " --material S50C --spindle-rpm " + rpm +
           " --feed-mm-per-min 400 --radial-depth-mm 1.5 --axial-depth-mm 10";
  }

  std::string content() {
    const fs::path out = dir_ / "content.json";
    const RunResult r = run_feedplan("db export " + out.string() + " --all-versions --db " + db_);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_text(out);
  }

  // Runs `arguments`, expects exit 2 with `fragment` in the output and the database content unchanged.
  void expect_bad_input(const std::string& arguments, const std::string& fragment) {
    const std::string before = content();
    const RunResult r = run_feedplan(arguments);
    EXPECT_EQ(r.exit_code, 2) << arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(fragment), std::string::npos) << "expected '" << fragment << "' in:\n" << r.output;
    EXPECT_EQ(content(), before) << arguments;
  }

  std::string db_;
};

TEST_F(DbCliTest, ImportFitShowPredictExportImportRollback) {
  const fs::path log = cutting_log("cut.csv");
  const RunResult imported = run_feedplan(import_args(log) + " --json");
  ASSERT_EQ(imported.exit_code, 0) << imported.output;
  EXPECT_NE(imported.output.find("\"peak_mean_n\""), std::string::npos);
  // One test cannot determine six coefficients: no model, a message, exit 1, nothing stored.
  const RunResult fit = run_feedplan("db fit --db " + db_ + " --tool " + kTool + " --material S50C");
  EXPECT_EQ(fit.exit_code, 1) << fit.output;
  EXPECT_EQ(run_feedplan("db show --db " + db_ + " --tool " + kTool + " --material S50C").exit_code, 2);
  // Export, import into a fresh database, export again: the same document.
  const fs::path a = dir_ / "a.json";
  const fs::path b = dir_ / "b.json";
  ASSERT_EQ(run_feedplan("db export " + a.string() + " --all-versions --db " + db_).exit_code, 0);
  const std::string other = (dir_ / "other.db").string();
  const RunResult round = run_feedplan("db import " + a.string() + " --db " + other);
  ASSERT_EQ(round.exit_code, 0) << round.output;
  ASSERT_EQ(run_feedplan("db export " + b.string() + " --all-versions --db " + other).exit_code, 0);
  EXPECT_EQ(read_text(a), read_text(b));
}

TEST_F(DbCliTest, BadDatabasesAreRefusedAndLeftAlone) {
  const fs::path corrupt = dir_ / "corrupt.db";
  std::ofstream(corrupt) << std::string(4096, 'x');
  const RunResult r = run_feedplan("db list --db " + corrupt.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("corrupt.db"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(corrupt), std::string(4096, 'x'));
  // A database from a newer schema: user_version (big-endian at byte 60 of the header) set to 99.
  {
    std::fstream file(db_, std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(60);
    const char version[4] = {0, 0, 0, 99};
    file.write(version, 4);
  }
  const RunResult newer = run_feedplan("db list --db " + db_);
  EXPECT_EQ(newer.exit_code, 2) << newer.output;
  EXPECT_NE(newer.output.find("99"), std::string::npos) << newer.output;
  const RunResult missing = run_feedplan("db list --db " + (dir_ / "nope.db").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_FALSE(fs::exists(dir_ / "nope.db"));
}

TEST_F(DbCliTest, BadRecordsNameTheField) {
  expect_bad_input("db add-tool " + kTool + " --db " + db_ + " --diameter-mm 12 --flutes 4", "already exists");
  expect_bad_input("db add-material S50C --db " + db_ + " --iso-group P --hardness \"180 HB\"", "already exists");
  expect_bad_input("db add-tool T2 --db " + db_ + " --diameter-mm -3 --flutes 4", "--diameter-mm = -3");
  expect_bad_input("db add-material X1 --db " + db_ + " --iso-group X --hardness \"180 HB\"", "--iso-group");
  expect_bad_input("db add-material X1 --db " + db_ + " --iso-group P --hardness hard", "--hardness");
  // A model with a NaN coefficient in an import file (JSON has no NaN: the exporter writes null).
  const fs::path doc = dir_ / "nan.json";
  std::ofstream(doc) << R"({"format": "feedplan-model-db", "format_version": 1, "contents": "active_models",
 "tools": [{"name": "SC EM D10 Z4", "diameter_mm": 10.0, "flutes": 4, "helix_deg": 30.0, "tool_material": "", "coating": "", "notes": ""}],
 "materials": [{"name": "S50C", "iso_group": "P", "hardness_value": 200.0, "hardness_scale": "HB", "notes": ""}],
 "models": [{"tool": "SC EM D10 Z4", "material": "S50C", "version": 1, "parent_version": null, "active": true,
   "source": "imported", "created_at": "2026-11-23T10:38:01.179Z", "note": "",
   "model": {"beta": [566.1, null, 246.5, 3.9, -8.3, 115.0], "chip_center_mm": 0.1, "chip_scale_mm": 0.08,
     "contact_length_center_mm": 4.0, "contact_length_scale_mm": 1.7,
     "range": {"chip_min_mm": 0.017, "chip_max_mm": 0.18, "contact_length_min_mm": 2.2, "contact_length_max_mm": 5.8},
     "axial_depth_mm": 10.0, "spindle_rpm": 2546.0, "quantity": "peak_xy_force_per_revolution_n"},
   "fit": {"n": 25, "rmse_n": 1.8, "r_squared": 0.99, "covariance": [0,0,0,0,0,0, 0,0,0,0,0,0, 0,0,0,0,0,0, 0,0,0,0,0,0, 0,0,0,0,0,0, 0,0,0,0,0,0],
     "standard_errors": [0,0,0,0,0,0], "loo_rmse_n": 2.0}}],
 "cutting_tests": [], "learning_history": []})";
  expect_bad_input("db import " + doc.string() + " --db " + db_, "beta[1]");
}

TEST_F(DbCliTest, BrokenLogsAndContradictingConditions) {
  const fs::path log = cutting_log("cut.csv");
  const std::string text = read_text(log);
  // Truncated mid-row.
  const fs::path truncated = dir_ / "truncated.csv";
  std::ofstream(truncated) << text.substr(0, text.size() / 2 + 7);
  expect_bad_input(import_args(truncated), "truncated.csv");
  // Time going backwards: two data rows swapped.
  std::string swapped = text;
  const auto header_end = swapped.find("t_s,");
  const auto row1 = swapped.find('\n', swapped.find('\n', header_end) + 1000) + 1;
  const auto row2 = swapped.find('\n', row1) + 1;
  const auto row3 = swapped.find('\n', row2) + 1;
  swapped = swapped.substr(0, row1) + swapped.substr(row2, row3 - row2) + swapped.substr(row1, row2 - row1) + swapped.substr(row3);
  const fs::path backwards = dir_ / "backwards.csv";
  std::ofstream(backwards) << swapped;
  expect_bad_input(import_args(backwards), "must be after");
  // Missing force column.
  std::string no_fy = text;
  no_fy.replace(no_fy.find(",fy_n,"), 6, ",fq_n,");
  const fs::path missing = dir_ / "missing.csv";
  std::ofstream(missing) << no_fy;
  expect_bad_input(import_args(missing), "fy_n");
  // Conditions that contradict the log.
  expect_bad_input(import_args(log, "3000"), "--spindle-rpm = 3000");
  expect_bad_input(import_args(log) + " --mode slot", "slot");
  expect_bad_input("db import-test " + log.string() + " --db " + db_ + " --tool Nope --material S50C --spindle-rpm 2546"
                   " --feed-mm-per-min 400 --radial-depth-mm 1.5 --axial-depth-mm 10", "--tool");
}

}  // namespace
