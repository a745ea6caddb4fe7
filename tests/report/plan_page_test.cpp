// The data of a plan page (report/plan_page.hpp) from a hand-made plan: columns rounded as the plan CSV
// rounds them, nothing measured as null, reasons by index into the page's list, a history's peak error.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>

#include "feedplan/report/plan_page.hpp"

namespace {

namespace planner = feedplan::planner;
namespace report = feedplan::report;

planner::PlannedSample sample(double s_mm, double x_mm, double y_mm) {
  planner::PlannedSample p;
  p.s_mm = s_mm;
  p.position.x_mm = x_mm;
  p.position.y_mm = y_mm;
  p.engaged = true;
  p.limit_reason = planner::FeedLimitReason::kForce;
  return p;
}

struct Fixture {
  planner::PlanResult result;
  planner::PlanSettings settings;
  Fixture() {
    result.samples = {sample(0.0, 1.0, 2.0), sample(1.23456789, 1.5, 2.5), sample(2.5, 2.0, 3.0)};
    result.samples[0].engagement_rad = std::numbers::pi / 2;
    result.samples[1].chip_thickness_mm = 0.0123456789;
    result.samples[1].feed_mm_per_min = 1234.56789;
    result.samples[2].limit_reason = planner::FeedLimitReason::kMaxFeed;
    result.samples[2].predicted_force_n = 299.99951;
    result.summary.cycle_time_s = 12.3;
    settings.target_force_n = 100.0;
    settings.machine.max_feed_mm_per_min = 8000.0;
  }
};

TEST(ReportPlanPage, SamplesRoundedAsThePlanCsv) {
  const Fixture f;
  const nlohmann::json data = nlohmann::json::parse(report::plan_page_json(f.result, f.settings, {}));
  EXPECT_EQ(data["kind"], "plan");
  const nlohmann::json& s = data["samples"];
  EXPECT_DOUBLE_EQ(s["s_mm"][1].get<double>(), 1.2346);
  EXPECT_DOUBLE_EQ(s["engagement_deg"][0].get<double>(), 90.0);
  EXPECT_DOUBLE_EQ(s["chip_thickness_mm"][1].get<double>(), 0.012346);
  EXPECT_DOUBLE_EQ(s["feed_mm_per_min"][1].get<double>(), 1234.568);
  EXPECT_DOUBLE_EQ(s["predicted_force_n"][2].get<double>(), 300.0);
  EXPECT_DOUBLE_EQ(s["x_mm"][2].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(data["machine"]["max_feed_mm_per_min"].get<double>(), 8000.0);
  EXPECT_FALSE(s.contains("measured_peak_n"));
}

TEST(ReportPlanPage, ReasonsByIndexIntoTheirNames) {
  const Fixture f;
  const nlohmann::json data = nlohmann::json::parse(report::plan_page_json(f.result, f.settings, {}));
  const auto name = [&](int i) { return data["limit_reasons"][data["samples"]["limit_reason"][i].get<int>()]; };
  EXPECT_EQ(name(0), "force");
  EXPECT_EQ(name(2), "max feed");
}

TEST(ReportPlanPage, NothingMeasuredIsNull) {
  const Fixture f;
  report::PlanPage page;
  page.measured_peak_n = {0.0, 101.23456, 0.0};
  const nlohmann::json data = nlohmann::json::parse(report::plan_page_json(f.result, f.settings, page));
  const nlohmann::json& m = data["samples"]["measured_peak_n"];
  EXPECT_TRUE(m[0].is_null());
  EXPECT_DOUBLE_EQ(m[1].get<double>(), 101.235);
  EXPECT_TRUE(m[2].is_null());
}

TEST(ReportPlanPage, HistoryCarriesEveryCycleAndItsPeakError) {
  const Fixture f;
  report::PlanPage page;
  planner::PathHistoryCycle first{1, 20.0, {100, 100, 100}, {90, 95, 99}, {110, 0, 95}};   // largest 110 N against 100 N: +10 %
  planner::PathHistoryCycle second{2, 19.0, {105, 105, 105}, {99, 99, 99}, {0, 0, 0}};     // nothing measured
  page.history = {first, second};
  page.cycle_table = {{"cycle"}, {{"1"}, {"2"}}};
  const nlohmann::json data = nlohmann::json::parse(report::plan_page_json(f.result, f.settings, page));
  EXPECT_EQ(data["kind"], "history");
  const nlohmann::json& cycles = data["history"]["cycles"];
  ASSERT_EQ(cycles.size(), 2u);
  EXPECT_DOUBLE_EQ(cycles[0]["peak_error_percent"].get<double>(), 10.0);
  EXPECT_TRUE(cycles[1]["peak_error_percent"].is_null());
  EXPECT_DOUBLE_EQ(cycles[1]["cycle_time_s"].get<double>(), 19.0);
  EXPECT_TRUE(cycles[0]["measured_n"][1].is_null());
  EXPECT_EQ(data["history"]["table"]["rows"].size(), 2u);
}

TEST(ReportPlanPage, SummaryLinesNameTheCycleTimeAndTarget) {
  const Fixture f;
  const std::vector<report::SummaryLine> lines = report::plan_summary_lines(f.result, f.settings);
  const auto value = [&](const std::string& label) {
    for (const auto& [l, v] : lines) {
      if (l == label) return v;
    }
    return std::string("(missing)");
  };
  EXPECT_EQ(value("cycle time, planned"), "12.30 s");
  EXPECT_EQ(value("target force"), "100.0 N");
  EXPECT_EQ(value("status"), "ok");
}

}  // namespace
