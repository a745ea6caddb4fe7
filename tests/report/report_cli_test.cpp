// `feedplan report` and `plan --html` from the command line, on a database holding the sample model of the
// Ø10 4-flute end mill in S50C: the pages are written and carry the plan's samples; every kind of bad
// input exits 2 naming the file and the field, and leaves an existing output as it was.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

#include "run_feedplan.hpp"

namespace {

using namespace feedplan::cli_test;

const std::string kSamples = FEEDPLAN_SAMPLES_DIR;

class ReportCliTest : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    db_ = (dir_ / "t.db").string();
    ASSERT_EQ(run_feedplan("db init --db " + db_).exit_code, 0);
    const RunResult r = run_feedplan("db import " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/cli/s50c_d10_model.json --db " + db_);
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }

  // The page's data: the JSON between the data script's tags.
  static nlohmann::json page_data(const std::string& html) {
    const std::string open = "<script type=\"application/json\" id=\"report-data\">\n";
    const std::size_t start = html.find(open);
    const std::size_t end = html.find("\n</script>", start);
    if (start == std::string::npos || end == std::string::npos) return {};
    return nlohmann::json::parse(html.substr(start + open.size(), end - start - open.size()));
  }

  static std::size_t csv_rows(const fs::path& csv) {
    std::ifstream in(csv);
    std::size_t lines = 0;
    for (std::string line; std::getline(in, line);) ++lines;
    return lines - 1;
  }

  // A file holding `text` that a failed run must leave as it was.
  fs::path existing(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }

  std::string db_;
};

TEST_F(ReportCliTest, PlanHtmlAndReportDrawTheSamePlan) {
  const fs::path report = dir_ / "p.json", csv = dir_ / "p.csv", html = dir_ / "p.html", redrawn = dir_ / "r.html";
  RunResult r = run_feedplan("plan " + kSamples + "/corner.yaml --db " + db_ + " -o " + (dir_ / "p.nc").string() +
                             " --report " + report.string() + " --csv " + csv.string() + " --html " + html.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json planned = page_data(read_text(html));
  ASSERT_TRUE(planned.contains("samples")) << "no page data in " << html;
  EXPECT_EQ(planned["kind"], "plan");
  EXPECT_EQ(planned["samples"]["s_mm"].size(), csv_rows(csv));

  r = run_feedplan("report " + report.string() + " -o " + redrawn.string() + " --db " + db_);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json drawn = page_data(read_text(redrawn));
  EXPECT_EQ(drawn["samples"], planned["samples"]);  // the plan re-made from the report is the one planned
  EXPECT_EQ(drawn["target_force_n"], planned["target_force_n"]);
}

TEST_F(ReportCliTest, MissingFileIsBadInput) {
  const fs::path out = existing("out.html", "before");
  const RunResult r = run_feedplan("report " + (dir_ / "nothing.json").string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("nothing.json"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(out), "before");
}

TEST_F(ReportCliTest, NotJsonIsBadInput) {
  const fs::path in = existing("in.json", "plan: yes\n");
  const fs::path out = existing("out.html", "before");
  const RunResult r = run_feedplan("report " + in.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is not a JSON object"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(out), "before");
}

TEST_F(ReportCliTest, AnotherFormatIsBadInputNamingTheField) {
  const fs::path in = existing("in.json", R"({"format": "feedplan-model", "format_version": 1})");
  const fs::path out = existing("out.html", "before");
  const RunResult r = run_feedplan("report " + in.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("in.json: format"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("feedplan-model"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(out), "before");
}

TEST_F(ReportCliTest, BrokenPlanReportIsBadInputNamingTheField) {
  const fs::path in = existing("in.json", R"({"format": "feedplan-plan", "format_version": 1, "status": "ok"})");
  const fs::path out = existing("out.html", "before");
  const RunResult r = run_feedplan("report " + in.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("is missing"), std::string::npos) << r.output;
  EXPECT_EQ(read_text(out), "before");
}

TEST_F(ReportCliTest, OutputInAMissingFolderIsBadInput) {
  const RunResult r = run_feedplan("report " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/report/compare.json -o " +
                                   (dir_ / "no" / "out.html").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("-o"), std::string::npos) << r.output;
}

TEST_F(ReportCliTest, ComparisonPageHasEveryStrategy) {
  const fs::path out = dir_ / "c.html";
  const RunResult r = run_feedplan("report " + std::string(FEEDPLAN_TEST_DATA_DIR) + "/report/compare.json -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json data = page_data(read_text(out));
  EXPECT_EQ(data["kind"], "comparison");
  const nlohmann::json compared = nlohmann::json::parse(read_text(std::string(FEEDPLAN_TEST_DATA_DIR) + "/report/compare.json"));
  ASSERT_EQ(data["comparison"]["rows"].size(), compared["rows"].size());
  for (std::size_t k = 0; k < compared["rows"].size(); ++k) {
    EXPECT_EQ(data["comparison"]["rows"][k]["name"], compared["rows"][k]["name"]);
    EXPECT_EQ(data["comparison"]["rows"][k]["figures"]["max_peak_n"], compared["rows"][k]["max_peak_n"]);
  }
}

}  // namespace
