// The HTML report of a large plan (report/plan_page.hpp): the time to write it, its size, and the time
// headless Chromium takes to open it until every chart is drawn (bench/open_report.mjs through
// puppeteer-core), with a hover readout and a zoom once open. The plan is made up in the shape a real one
// has — a trochoidal path, engagement, feed and force varying along it — at 100 000 samples, ten times the
// bundled trochoid's at its default spacing.
//
// Run: build/bench/report_open_bench   (needs Chromium and report/web/node_modules: scripts/install-deps.sh)

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "feedplan/report/plan_page.hpp"

namespace {

namespace planner = feedplan::planner;
namespace report = feedplan::report;

// A trochoid of pitch 1 mm and radius 4 mm sampled every 0.05 mm of path, n samples.
planner::PlanResult made_up_plan(int n) {
  planner::PlanResult plan;
  plan.samples.resize(static_cast<std::size_t>(n));
  double time_s = 0.0;
  for (int i = 0; i < n; ++i) {
    planner::PlannedSample& p = plan.samples[static_cast<std::size_t>(i)];
    const double turn = 2.0 * std::numbers::pi * i / 600.0;  // 600 samples per loop
    p.s_mm = 0.05 * i;
    p.position.x_mm = turn / (2.0 * std::numbers::pi) + 4.0 * std::cos(turn);
    p.position.y_mm = 4.0 * std::sin(turn);
    p.engaged = std::sin(turn) < 0.2;
    p.engagement_rad = p.engaged ? 0.5 + 0.8 * std::abs(std::sin(turn)) : 0.0;
    p.chip_thickness_mm = p.engaged ? 0.03 + 0.02 * std::cos(turn) : 0.0;
    p.contact_length_mm = 5.0 * p.engagement_rad;
    p.feed_limit_mm_per_min = p.engaged ? 900.0 + 600.0 * std::cos(turn) : 3000.0;
    p.feed_mm_per_min = std::min(p.feed_limit_mm_per_min, 2500.0);
    p.limit_reason = p.engaged ? planner::FeedLimitReason::kForce : planner::FeedLimitReason::kAirFeed;
    p.predicted_force_n = p.engaged ? 300.0 - 15.0 * std::sin(3.0 * turn) : 0.0;
    p.upper_force_n = 1.1 * p.predicted_force_n;
    time_s += 0.05 / (p.feed_mm_per_min / 60.0);
    p.time_s = time_s;
  }
  plan.summary.cycle_time_s = time_s;
  return plan;
}

planner::PlanSettings settings() {
  planner::PlanSettings s;
  s.target_force_n = 300.0;
  s.spindle_rpm = 5000.0;
  return s;
}

report::PlanPage page_of(const planner::PlanResult& plan) {
  report::PlanPage page;
  page.title = "made-up trochoid, " + std::to_string(plan.samples.size()) + " samples";
  page.summary = report::plan_summary_lines(plan, settings());
  page.measured_peak_n.resize(plan.samples.size());
  for (std::size_t i = 0; i < plan.samples.size(); ++i) {
    page.measured_peak_n[i] = plan.samples[i].engaged && i % 20 == 0 ? 1.05 * plan.samples[i].predicted_force_n : 0.0;
  }
  return page;
}

void BM_WritePlanPage(benchmark::State& state) {
  const planner::PlanResult plan = made_up_plan(static_cast<int>(state.range(0)));
  const report::PlanPage page = page_of(plan);
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string html = report::plan_page_html(plan, settings(), page);
    bytes = html.size();
    benchmark::DoNotOptimize(html.data());
  }
  state.counters["html_MB"] = static_cast<double>(bytes) / 1e6;
}
BENCHMARK(BM_WritePlanPage)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

// Milliseconds of one field of open_report.mjs's JSON line; NaN when missing.
double field_ms(const std::string& line, const std::string& key) {
  const std::size_t at = line.find("\"" + key + "\":");
  return at == std::string::npos ? std::nan("") : std::stod(line.substr(at + key.size() + 3));
}

void BM_OpenPlanPageInChromium(benchmark::State& state) {
  const planner::PlanResult plan = made_up_plan(static_cast<int>(state.range(0)));
  const std::string html = report::plan_page_html(plan, settings(), page_of(plan));
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("feedplan_report_bench_" + std::to_string(state.range(0)) + ".html");
  std::ofstream(file, std::ios::binary) << html;
  const std::string command = "node '" FEEDPLAN_BENCH_OPEN_SCRIPT "' '" FEEDPLAN_REPORT_WEB_DIR "' '" FEEDPLAN_CHROMIUM "' '" +
                              file.string() + "' 2>&1";
  double hover_ms = 0.0, zoom_ms = 0.0;
  for (auto _ : state) {
    std::string line;
    FILE* pipe = popen(command.c_str(), "r");
    char buffer[4096];
    while (pipe && std::fgets(buffer, sizeof buffer, pipe)) line += buffer;
    const int status = pipe ? pclose(pipe) : -1;
    const double open_ms = field_ms(line, "open_ms");
    if (status != 0 || !std::isfinite(open_ms)) {
      state.SkipWithError(("open_report.mjs failed: " + line).c_str());
      break;
    }
    state.SetIterationTime(open_ms / 1000.0);
    hover_ms = field_ms(line, "hover_ms");
    zoom_ms = field_ms(line, "zoom_ms");
  }
  state.counters["html_MB"] = static_cast<double>(html.size()) / 1e6;
  state.counters["hover_ms"] = hover_ms;
  state.counters["zoom_ms"] = zoom_ms;
  std::filesystem::remove(file);
}
BENCHMARK(BM_OpenPlanPageInChromium)->Arg(10000)->Arg(100000)->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
