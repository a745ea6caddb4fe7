#include "html_report_pages.hpp"

#include <algorithm>
#include <cmath>

#include "plan_summary.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/report/comparison_page.hpp"

namespace feedplan::cli {
namespace {

// Per plan sample, the largest per-revolution peak of the revolutions spanning it (0: none in cut there).
std::vector<double> measured_per_sample(const planner::PlanResult& plan, const planner::PeakComparison& comparison) {
  std::vector<double> measured(plan.samples.size(), 0.0);
  std::size_t first = 0;
  for (const planner::RevolutionComparison& r : comparison.revolutions) {
    if (!r.in_cut) continue;
    while (first < plan.samples.size() && plan.samples[first].s_mm < r.revolution.s_start_mm) ++first;
    for (std::size_t i = first; i < plan.samples.size() && plan.samples[i].s_mm <= r.revolution.s_end_mm; ++i) {
      if (plan.samples[i].engaged) measured[i] = std::max(measured[i], r.revolution.peak_n);
    }
  }
  return measured;
}

std::string plan_title(const std::string& cycle, const geometry::Tool& tool, const std::string& material, double target_n) {
  std::string title = cycle;
  title += " — ";
  title += tool.name;
  title += " in " + material + ", target " + shortest_number_text(target_n) + " N";
  return title;
}

}  // namespace

report::PlanPage plan_command_page(const PlanInputs& in, const PlanModel& model, const PlannedCycle& planned,
                                   const PlanOutputs& out) {
  const planner::PlanResult& result = planned.result;
  report::PlanPage page;
  page.title = plan_title(in.spec.cycle, in.spec.tool, in.spec.material, in.target_force_n);
  page.summary.emplace_back("plan", plan_status_text(result, model));
  page.summary.emplace_back("model", "id " + std::to_string(model.chosen.record.id) + " v" +
                                         std::to_string(model.chosen.record.version) + " " +
                                         model.chosen.record.tool_name + " in " + model.chosen.record.material_name +
                                         " (" + model.chosen.match + ")");
  if (!model.kind_reason.empty()) page.summary.emplace_back("model kind", model.kind_reason);
  for (report::SummaryLine& line : report::plan_summary_lines(result, planned.settings)) page.summary.push_back(std::move(line));
  if (out.check) {
    page.summary.emplace_back("virtual machine: largest per-revolution peak",
                              fixed_number_text(out.check->max_peak_n, 1) + " N");
    page.summary.emplace_back("virtual machine: cycle time", fixed_number_text(out.check->cycle_time_s, 2) + " s");
    page.measured_peak_n = measured_per_sample(result, out.check->comparison);
    for (const std::string& warning : out.check->warnings) page.notes.push_back("virtual machine: " + warning);
  }
  if (model.relative_uncertainty > 0.0) {
    page.notes.push_back("cautious mode: the plan holds F̂ + " + shortest_number_text(kBorrowedModelSigmas) +
                         "σ at the target (relative uncertainty r = " + shortest_number_text(model.relative_uncertainty) +
                         (model.uncertainty_requested ? ", --cautious)" : ", from how far the model is borrowed)"));
  }
  for (const std::string& message : result.messages) page.notes.push_back(message);
  return page;
}

report::PlanPage plan_report_page(const planner::PlanReport& report, const planner::PlanResult& plan,
                                  const std::string& source_name) {
  const planner::PlanReportContext& c = report.context;
  report::PlanPage page;
  page.title = plan_title(c.cycle, c.tool, c.material, report.settings.target_force_n);
  page.summary.emplace_back("plan report", source_name);
  page.summary.emplace_back("model", "id " + std::to_string(c.model_id) + " v" + std::to_string(c.model_version) + " " +
                                         c.model_tool + " in " + c.model_material +
                                         (c.model_match_status.empty() ? "" : " (" + c.model_match_status + ")"));
  if (!c.model_kind_reason.empty()) page.summary.emplace_back("model kind", c.model_kind_reason);
  if (!c.program_path.empty()) page.summary.emplace_back("program", c.program_path + " (" + c.dialect + ")");
  for (report::SummaryLine& line : report::plan_summary_lines(plan, report.settings)) page.summary.push_back(std::move(line));
  if (c.model_relative_uncertainty > 0.0) {
    page.notes.push_back("cautious mode: the plan holds F̂ + " + shortest_number_text(kBorrowedModelSigmas) +
                         "σ at the target (relative uncertainty r = " + shortest_number_text(c.model_relative_uncertainty) + ")");
  }
  for (const std::string& difference : c.model_differences) page.notes.push_back("borrowed model: " + difference);
  for (const std::string& message : plan.messages) page.notes.push_back(message);
  if (c.path_measurements.size() == plan.samples.size()) {
    page.measured_peak_n.reserve(plan.samples.size());
    for (const auto& m : c.path_measurements) page.measured_peak_n.push_back(m[2]);
  }
  if (!c.path_history.empty() && c.path_history.front().measured_n.size() == plan.samples.size()) {
    page.history = c.path_history;
    page.cycle_table.columns = {"cycle", "planned cycle time [s]", "largest measured peak [N]", "against the target [%]",
                                "places measured"};
    for (const planner::PathHistoryCycle& h : c.path_history) {
      double largest = 0.0;
      int measured = 0;
      for (const double f : h.measured_n) {
        if (!(f > 0.0)) continue;
        ++measured;
        largest = std::max(largest, f);
      }
      const double target = report.settings.target_force_n;
      page.cycle_table.rows.push_back({std::to_string(h.cycle), fixed_number_text(h.cycle_time_s, 2),
                                       measured > 0 ? fixed_number_text(largest, 1) : "—",
                                       measured > 0 ? fixed_number_text(100.0 * (largest - target) / target, 1) : "—",
                                       std::to_string(measured)});
    }
  }
  return page;
}

std::string comparison_page_html(const nlohmann::json& comparison, const std::string& source_name) {
  const auto number = [](const nlohmann::json& v) { return v.is_number() ? v.get<double>() : std::nan(""); };
  const nlohmann::json* rows = comparison.contains("rows") ? &comparison["rows"] : nullptr;
  if (!rows || !rows->is_array() || rows->empty() || !comparison.contains("target_force_n")) {
    throw InputError(source_name, "is not a comparison (compare.json): it needs rows[] and target_force_n");
  }
  report::ComparisonPage page;
  const double target = number(comparison["target_force_n"]);
  page.title = comparison.value("spec", std::string("comparison")) + " (" + comparison.value("cycle", std::string("")) +
               "): strategies on the virtual machine, target " + shortest_number_text(target) + " N";
  page.summary.emplace_back("comparison", source_name);
  page.summary.emplace_back("virtual machine", comparison.value("machine", std::string("")));
  page.summary.emplace_back("model", comparison.value("model", std::string("")));
  page.summary.emplace_back("target force", shortest_number_text(target) + " N");
  if (comparison.contains("constant_feed_mm_per_min")) {
    page.summary.emplace_back("constant feed", fixed_number_text(number(comparison["constant_feed_mm_per_min"]), 0) +
                                                   " mm/min (" + comparison.value("constant_feed_source", std::string("")) + ")");
  }
  if (comparison.contains("learning_cycles")) {
    page.summary.emplace_back("learning cycles", std::to_string(comparison["learning_cycles"].get<int>()));
  }
  if (comparison.contains("notes") && comparison["notes"].is_array()) {
    for (const auto& note : comparison["notes"]) {
      if (note.is_string()) page.notes.push_back(note.get<std::string>());
    }
  }
  page.figures = {{"max_peak_n", "largest per-revolution peak [N]"},
                  {"max_overshoot_percent", "largest overshoot [%]"},
                  {"rms_error_percent", "RMS error [%]"},
                  {"within_5_percent_share", "share of revolutions within 5 %"},
                  {"cycle_time_s", "cycle time [s]"},
                  {"time_above_target_s", "time above the target [s]"}};
  page.table.columns = {"strategy"};
  for (const report::ComparisonFigure& f : page.figures) page.table.columns.push_back(f.label);
  for (std::size_t k = 0; k < rows->size(); ++k) {
    const nlohmann::json& row = (*rows)[k];
    if (!row.is_object() || !row.contains("name") || !row["name"].is_string()) {
      throw InputError(source_name + ": rows[" + std::to_string(k) + "].name", "is missing: every row names its strategy");
    }
    page.strategies.push_back(row["name"].get<std::string>());
    std::vector<double> values;
    std::vector<std::string> cells{page.strategies.back()};
    for (const report::ComparisonFigure& f : page.figures) {
      values.push_back(row.contains(f.key) ? number(row[f.key]) : std::nan(""));
      cells.push_back(std::isfinite(values.back()) ? fixed_number_text(values.back(), 2) : "—");
    }
    page.values.push_back(std::move(values));
    page.table.rows.push_back(std::move(cells));
    if (row.contains("warnings") && row["warnings"].is_array()) {
      for (const auto& w : row["warnings"]) {
        if (w.is_string()) page.notes.push_back(page.strategies.back() + ": " + w.get<std::string>());
      }
    }
  }
  return report::comparison_page_html(page);
}

}  // namespace feedplan::cli
