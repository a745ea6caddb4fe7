// Force logs: the written format (docs/method.md §4), round trips, every reader error with its line and
// column, and real Kistler DynoWare exports (tests/data/kistler, excerpts of data/kistler_slot).

#include "feedplan/force_log/force_log.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <locale>
#include <sstream>
#include <string>

#include "feedplan/core/input_error.hpp"
#include "has_problem.hpp"

namespace feedplan::force_log {
namespace {

using test_support::has_problem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
const std::string kKistlerDir = std::string(FEEDPLAN_TEST_DATA_DIR) + "/kistler/";

std::vector<InputProblem> problems_of(const std::string& text) {
  try {
    read_force_log(text, "log.csv");
  } catch (const InputError& e) {
    return e.problems();
  }
  ADD_FAILURE() << "read_force_log accepted:\n" << text;
  return {};
}

ForceLog sample_log() {
  ForceLog log;
  log.metadata = {{"source", "feedplan simulate"}, {"spindle_rpm", "2800"}, {"sample_rate_hz", "10000"},
                  {"tool", "SC EM D10 Z4"}};
  log.rows.push_back({0.0, 1.0, 2.0, -10.0, 123.4567, -0.0001, 5.5, 1000.0, 2800.0, 0, 0, 0});
  log.rows.push_back({0.0001, 1.00016667, 2.0, -10.0, 130.0, -20.25, kNaN, 1000.0, 2800.0, 0, 0, 0});
  return log;
}

// A numpunct that writes "1.234,5": what a German locale does to iostreams.
struct CommaDecimal : std::numpunct<char> {
  char do_decimal_point() const override { return ','; }
  char do_thousands_sep() const override { return '.'; }
  std::string do_grouping() const override { return "\3"; }
};

TEST(ForceLogFormat, MetadataHeaderAndPrecision) {
  const std::string text = format_force_log(sample_log());
  const std::string expected =
      "# source: feedplan simulate\n"
      "# spindle_rpm: 2800\n"
      "# sample_rate_hz: 10000\n"
      "# tool: SC EM D10 Z4\n"
      "t_s,x_mm,y_mm,z_mm,fx_n,fy_n,fz_n,feed_mm_per_min,spindle_rpm\n"
      "0.000000,1.0000,2.0000,-10.0000,123.457,0.000,5.500,1000.00,2800.0\n"
      "0.000100,1.0002,2.0000,-10.0000,130.000,-20.250,,1000.00,2800.0\n";
  EXPECT_EQ(text, expected);
}

TEST(ForceLogFormat, CurrentsAndMissingPositions) {
  ForceLog log;
  log.has_positions = false;
  log.has_currents = true;
  log.rows.push_back({8.0, 1, 2, 3, 10, 20, 30, kNaN, 6000, 4.12, 7.24, 18.5});
  EXPECT_EQ(format_force_log(log),
            "t_s,x_mm,y_mm,z_mm,fx_n,fy_n,fz_n,feed_mm_per_min,spindle_rpm,ix_a,iy_a,iz_a\n"
            "8.000000,,,,10.000,20.000,30.000,,6000.0,4.12000,7.24000,18.50000\n");
}

TEST(ForceLogFormat, MetadataStaysOnOneLine) {
  ForceLog log;
  log.metadata = {{"odd:key", "two\nlines"}};
  log.rows.push_back({0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0});
  const std::string text = format_force_log(log);
  EXPECT_EQ(text.substr(0, text.find('\n') + 1), "# odd_key: two lines\n");
  EXPECT_EQ(read_force_log(text, "t").metadata_value("odd_key"), "two lines");
}

TEST(ForceLogFormat, DecimalPointIgnoresTheGlobalLocale) {
  const std::locale previous = std::locale::global(std::locale(std::locale::classic(), new CommaDecimal));
  std::ostringstream probe;
  probe << 1234.5;
  const std::string localised = probe.str();
  const std::string text = format_force_log(sample_log());
  std::locale::global(previous);
  ASSERT_EQ(localised, "1.234,5") << "the test locale did not take effect";
  EXPECT_NE(text.find("123.457,0.000,5.500,1000.00"), std::string::npos) << text;
}

TEST(ForceLogFormat, RoundTripThroughReader) {
  const ForceLog original = sample_log();
  const ForceLog back = read_force_log(format_force_log(original), "round trip");
  EXPECT_EQ(back.metadata, original.metadata);
  EXPECT_TRUE(back.has_positions);
  EXPECT_TRUE(back.has_forces);
  EXPECT_FALSE(back.has_currents);
  ASSERT_EQ(back.rows.size(), 2u);
  EXPECT_EQ(back.rows[1].t_s, 0.0001);
  EXPECT_EQ(back.rows[1].x_mm, 1.0002);  // 4 decimals
  EXPECT_EQ(back.rows[0].fx_n, 123.457);
  EXPECT_EQ(back.rows[1].fy_n, -20.25);
  EXPECT_TRUE(std::isnan(back.rows[1].fz_n));
  EXPECT_EQ(back.rows[0].spindle_rpm, 2800.0);
  EXPECT_EQ(back.metadata_value("spindle_rpm"), "2800");
  EXPECT_EQ(back.metadata_value("nothing"), "");
}

TEST(ForceLogFile, WritesAtomicallyAndReportsBadDirectories) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "feedplan_force_log_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "log.csv").string();
  ASSERT_EQ(write_force_log(path, sample_log()), "");
  const ForceLog back = load_force_log(path);
  EXPECT_EQ(back.rows.size(), 2u);
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename(), "log.csv") << "temporary file left behind";
  }
  std::filesystem::remove_all(dir);
  const std::string error = write_force_log("/nonexistent-dir/log.csv", sample_log());
  EXPECT_NE(error.find("cannot write /nonexistent-dir/log.csv"), std::string::npos) << error;
  EXPECT_THROW(load_force_log("/nonexistent-dir/log.csv"), InputError);
}

const std::string kHeader = "t_s,x_mm,y_mm,fx_n,fy_n\n";

TEST(ForceLogReader, AcceptsCurrentOnlyLogsAndCrlf) {
  const ForceLog log = read_force_log("# spindle_rpm: 600\r\nt_s,x_mm,y_mm,ix_a,iy_a\r\n0,0,0,4.5,7.5\r\n0.002,0.01,0,4.6,7.4\r\n",
                                      "log.csv");
  EXPECT_FALSE(log.has_forces);
  EXPECT_TRUE(log.has_currents);
  ASSERT_EQ(log.rows.size(), 2u);
  EXPECT_EQ(log.rows[1].ix_a, 4.6);
  EXPECT_TRUE(std::isnan(log.rows[1].fx_n));
  EXPECT_EQ(log.metadata_value("spindle_rpm"), "600");
}

TEST(ForceLogReader, MissingRequiredColumns) {
  EXPECT_TRUE(has_problem(problems_of("t_s,fx_n,fy_n\n0,1,2\n"), "log.csv line 1 (header)",
                          "lacks the columns x_mm, y_mm: a force log needs t_s, x_mm, y_mm and fx_n, fy_n"));
  EXPECT_TRUE(has_problem(problems_of("# a: b\nx_mm,y_mm,fx_n\n0,1,2\n"), "log.csv line 2 (header)",
                          "lacks the columns t_s, fy_n"));
  EXPECT_TRUE(has_problem(problems_of("t_s,x_mm,y_mm,fz_n\n0,1,2,3\n"), "log.csv line 1 (header)",
                          "lacks the columns fx_n, fy_n"));
}

TEST(ForceLogReader, UnknownAndRepeatedColumns) {
  const auto problems = problems_of("t_s,x_mm,y_mm,fx_N,fy_n,fy_n\n0,0,0,1,2,3\n");
  EXPECT_TRUE(has_problem(problems, "log.csv line 1, column 4", "= \"fx_N\": unknown column; expected t_s, x_mm"));
  EXPECT_TRUE(has_problem(problems, "log.csv line 1, column 4", "(did you mean fx_n?)"));
  EXPECT_TRUE(has_problem(problems, "log.csv line 1, column 6", "= \"fy_n\": repeats column 5"));
}

TEST(ForceLogReader, NonNumericAndNonFiniteCellsNameLineAndColumn) {
  const auto problems = problems_of(kHeader + "0,0,0,1,2\n0.1,0,0,1.2.3,2\n0.2,0,0,nan,2\n");
  EXPECT_TRUE(has_problem(problems, "log.csv line 3, column 4 (fx_n)", "= \"1.2.3\": not a number"));
  EXPECT_TRUE(has_problem(problems, "log.csv line 4, column 4 (fx_n)", "= \"nan\": must be a finite number (leave the "
                                                                      "cell empty"));
  const auto comma_decimal = problems_of(kHeader + "0,0,0,1,2\n0;1;0;0;1;2\n");
  EXPECT_TRUE(has_problem(comma_decimal, "log.csv line 3", "has 1 cells, the header (line 1) has 5"));
}

TEST(ForceLogReader, WrongColumnCount) {
  const auto problems = problems_of(kHeader + "0,0,0,1,2\n0.1,0,0,1\n0.2,0,0,1,2,3\n");
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(to_string(problems[0]), "log.csv line 3 has 4 cells, the header (line 1) has 5");
  EXPECT_EQ(to_string(problems[1]), "log.csv line 4 has 6 cells, the header (line 1) has 5");
}

TEST(ForceLogReader, TimeMustIncrease) {
  const auto problems = problems_of(kHeader + "0,0,0,1,2\n0.1,0,0,1,2\n0.1,0,0,1,2\n0.05,0,0,1,2\n");
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(to_string(problems[0]), "log.csv line 4, t_s = 0.1: must be after 0.1 on line 3 — time must increase from "
                                    "row to row");
  EXPECT_EQ(problems[1].field, "log.csv line 5, t_s");
  EXPECT_TRUE(has_problem(problems_of(kHeader + ",0,0,1,2\n"), "log.csv line 2, column 1 (t_s)", "is empty"));
}

TEST(ForceLogReader, PositionsAndForcesAllOrNothing) {
  const ForceLog no_positions = read_force_log(kHeader + "0,,,1,2\n0.1,,,1,2\n", "log.csv");
  EXPECT_FALSE(no_positions.has_positions);
  EXPECT_TRUE(std::isnan(no_positions.rows[0].x_mm));
  EXPECT_TRUE(has_problem(problems_of(kHeader + "0,0,0,1,2\n0.1,,0,1,2\n"), "log.csv line 3, column 2 (x_mm)",
                          "is empty, but other rows record positions: give it in every row or in none"));
  EXPECT_TRUE(has_problem(problems_of(kHeader + "0,0,0,,\n"), "log.csv line 1 (header)",
                          "fx_n, fy_n are empty in every row"));
}

TEST(ForceLogReader, EmptyHeaderOnlyAndNoHeader) {
  for (const std::string empty : {"", "\n\n"}) {
    const auto problems = problems_of(empty);
    ASSERT_EQ(problems.size(), 1u);
    EXPECT_EQ(to_string(problems[0]), "log.csv is empty: expected a force log (header row t_s,x_mm,y_mm,...,fx_n,fy_n "
                                      "then samples)");
  }
  EXPECT_TRUE(has_problem(problems_of("# spindle_rpm: 2800\n"), "log.csv", "has no header row"));
  EXPECT_TRUE(has_problem(problems_of("# a: b\n" + kHeader), "log.csv line 2", "no samples follow it"));
}

TEST(ForceLogReader, ProblemCountIsCapped) {
  std::string text = kHeader;
  for (int i = 0; i < 30; ++i) text += std::to_string(i) + ",0,0,x,2\n";
  const auto problems = problems_of(text);
  ASSERT_EQ(problems.size(), 21u);
  EXPECT_EQ(to_string(problems.back()), "log.csv … and 10 more problems");
}

TEST(KistlerExport, ReadsRealExcerpt) {
  const ForceLog log = load_force_log(kKistlerDir + "n6000_f300_ap3_excerpt.csv");
  EXPECT_FALSE(log.has_positions);
  EXPECT_TRUE(log.has_forces);
  EXPECT_FALSE(log.has_currents);
  EXPECT_EQ(log.metadata_value("sample_rate_hz"), "10000");
  EXPECT_EQ(log.metadata_value("source"), "Kistler DynoWare export (Version 2.5.1.2)");
  EXPECT_EQ(log.metadata_value("dynoware.Filename"), "6-n6000f300ap3ae25.dwd");
  ASSERT_EQ(log.rows.size(), 1000u);
  // First and last data lines of the file, as written there.
  EXPECT_EQ(log.rows.front().t_s, 8.0);
  EXPECT_EQ(log.rows.front().fx_n, 72.6013);
  EXPECT_EQ(log.rows.front().fy_n, -209.473);
  EXPECT_EQ(log.rows.front().fz_n, 82.6721);
  EXPECT_EQ(log.rows.back().t_s, 8.0999);
  EXPECT_EQ(log.rows.back().fx_n, 98.5107);
  EXPECT_TRUE(std::isnan(log.rows.front().x_mm));
  EXPECT_TRUE(std::isnan(log.rows.front().spindle_rpm));
  for (std::size_t i = 1; i < log.rows.size(); ++i) {
    ASSERT_NEAR(log.rows[i].t_s - log.rows[i - 1].t_s, 1e-4, 1e-9) << "row " << i;
  }
}

TEST(KistlerExport, AllExcerptsReadAndRoundTripThroughOurFormat) {
  for (const char* name : {"n6000_f300_ap3", "n6000_f900_ap3", "n6000_f1500_ap3"}) {
    SCOPED_TRACE(name);
    const ForceLog log = load_force_log(kKistlerDir + name + "_excerpt.csv");
    ASSERT_EQ(log.rows.size(), 1000u);
    const ForceLog back = read_force_log(format_force_log(log), "converted");
    EXPECT_FALSE(back.has_positions);
    ASSERT_EQ(back.rows.size(), log.rows.size());
    for (std::size_t i = 0; i < log.rows.size(); i += 97) {
      EXPECT_NEAR(back.rows[i].t_s, log.rows[i].t_s, 5e-7);
      EXPECT_NEAR(back.rows[i].fx_n, log.rows[i].fx_n, 5e-4);
      EXPECT_NEAR(back.rows[i].fz_n, log.rows[i].fz_n, 5e-4);
    }
  }
}

const std::string kDynoHeader =
    "DynoWare,Version 2.5.1.2\n"
    "Sampling rate [Hz]:,1000\n";

TEST(KistlerExport, KilonewtonsAreScaledAndExtraChannelsIgnored) {
  const ForceLog log = read_force_log(kDynoHeader + "Time,Fx,Fy,Mz\ns,kN,kN,Nm\n0,0.1,-0.2,5\n0.001,0.15,-0.25,6\n",
                                      "dyno.csv");
  ASSERT_EQ(log.rows.size(), 2u);
  EXPECT_DOUBLE_EQ(log.rows[1].fx_n, 150.0);
  EXPECT_DOUBLE_EQ(log.rows[1].fy_n, -250.0);
  EXPECT_TRUE(std::isnan(log.rows[1].fz_n));
  EXPECT_EQ(log.metadata_value("sample_rate_hz"), "1000");
}

TEST(KistlerExport, Problems) {
  EXPECT_TRUE(has_problem(problems_of(kDynoHeader + "Time,Fx,Fz\ns,N,N\n0,1,2\n"), "log.csv line 3",
                          "has no channel Fy: a force log needs Time, Fx and Fy"));
  EXPECT_TRUE(has_problem(problems_of(kDynoHeader + "Time,Fx,Fy\ns,lbf,N\n0,1,2\n"), "log.csv line 4, column 2 (Fx)",
                          "= \"lbf\": the force unit must be N or kN"));
  EXPECT_TRUE(has_problem(problems_of(kDynoHeader + "Time,Fx,Fy\ns,N,N\n0,1,2\n0.001,a,2\n"),
                          "log.csv line 6, column 2 (Fx)", "= \"a\": not a number"));
  EXPECT_TRUE(has_problem(problems_of(kDynoHeader + "Time,Fx,Fy\ns,N,N\n0,1,2\n0,1,2\n"), "log.csv line 6, t_s",
                          "must be after 0 on line 5"));
  EXPECT_TRUE(has_problem(problems_of(kDynoHeader), "log.csv", "without a channel row"));
  EXPECT_TRUE(has_problem(problems_of("DynoWare,Version 2\nSampling rate [Hz]:,fast\nTime,Fx,Fy\ns,N,N\n0,1,2\n"),
                          "log.csv line 2, Sampling rate [Hz]", "= \"fast\": must be a number > 0 Hz"));
}

}  // namespace
}  // namespace feedplan::force_log
