#include "report_command.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "database_path.hpp"
#include "html_report_pages.hpp"
#include "model_choice.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/plan_report.hpp"
#include "feedplan/report/plan_page.hpp"

namespace feedplan::cli {
namespace {

namespace fs = std::filesystem;

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("REPORT", "= '" + path + "': cannot be read (no such file, or not readable)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The cycle spec a plan report names: as stored, else beside the report (a folder moved as a whole).
std::string plan_spec_path(const planner::PlanReport& report, const std::string& report_path) {
  const std::string& stored = report.context.spec_path;
  if (fs::exists(stored)) return stored;
  const fs::path beside = fs::path(report_path).parent_path() / fs::path(stored).filename();
  if (fs::exists(beside)) return beside.string();
  throw InputError(report_path + ": spec", "= '" + stored + "': the cycle spec the plan came from is not there (nor beside " +
                                               report_path + "): the report draws the plan re-made from it");
}

// The settings the plan was made with: a recorded caution is the bound F̂ + z·σ with the planned version's
// covariance, read from the database as `plan` and `learn` do.
planner::PlanSettings settings_as_planned(const ReportOptions& o, const planner::PlanReport& report) {
  planner::PlanSettings settings = report.settings;
  const double r = report.context.model_relative_uncertainty;
  if (!(r > 0.0)) return settings;
  const std::string db = !o.db_path.empty()                         ? o.db_path
                         : !report.context.database_path.empty() ? report_database_path(report.context.database_path, o.input_path)
                                                                   : database_path("");
  const model_db::Store store = model_db::Store::open(db, model_db::OpenMode::kReadOnly);
  const std::optional<model_db::ModelRecord> record = store.model_by_id(report.context.model_id);
  if (!record) {
    throw InputError(o.input_path + ": model.id", "= " + std::to_string(report.context.model_id) + ": no such model in " + db +
                                                      " (the plan was made cautiously with its covariance; give its database with --db)");
  }
  if (const auto bound = cautious_bound(*record, r)) settings.uncertainty = bound;
  return settings;
}

// The plan report's page: the plan re-made from its spec and settings (deterministic), checked to be the
// one reported.
std::string plan_report_html(const ReportOptions& o, const std::string& text) {
  const planner::PlanReport report = planner::parse_plan_report(text, o.input_path);
  const cycles::CycleSpec spec = cycles::load_cycle_spec(plan_spec_path(report, o.input_path));
  const planner::PlanSettings settings = settings_as_planned(o, report);
  const cycles::Cycle cycle = cycles::generate(spec);
  const planner::PlanGeometry geometry = planner::analyse(cycle.path, cycle.stock, spec.tool, settings.options.ds_mm);
  const planner::PlanResult plan = planner::plan(geometry, settings);
  if (plan.blocks.size() != report.blocks.size()) {
    throw InputError(o.input_path + ": blocks", "the plan re-made from " + report.context.spec_path + " has " +
                                                    std::to_string(plan.blocks.size()) + " blocks, the report " +
                                                    std::to_string(report.blocks.size()) +
                                                    ": the spec changed since the plan was made");
  }
  return report::plan_page_html(plan, settings, plan_report_page(report, plan, o.input_path));
}

}  // namespace

void add_report_command(CLI::App& app, ReportOptions& options) {
  auto* cmd = app.add_subcommand(
      "report",
      "Write one self-contained HTML file (opens offline) from a plan report (plan/learn --report) or a\n"
      "comparison (compare.json): the tool path coloured by feed or force with a readout of every sample, force,\n"
      "feed and engagement along the path zoomed together, the learning history, the summary and the notes");
  cmd->add_option("report", options.input_path, "Plan report (JSON) or compare.json")->required();
  cmd->add_option("-o,--output", options.output_path, "HTML file to write")->required();
  cmd->add_option("--db", options.db_path, "Model database (default: the report's, else $FEEDPLAN_DB, else the sample)");
}

int run_report_command(const ReportOptions& o) {
  std::vector<InputProblem> problems;
  check_outputs({{"REPORT", o.input_path}}, {{"-o", o.output_path}}, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  const std::string text = read_text(o.input_path);
  const nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
  if (document.is_discarded() || !document.is_object()) {
    throw InputError("REPORT", "= '" + o.input_path + "': is not a JSON object: expected a plan report (plan --report) or "
                                                      "compare.json");
  }
  std::string html;
  if (document.contains("format")) {
    const nlohmann::json& format = document["format"];
    if (!format.is_string() || format.get<std::string>() != "feedplan-plan") {
      throw InputError(o.input_path + ": format", "= " + format.dump() + ": expected \"feedplan-plan\" (a plan report) "
                                                                          "or a comparison (compare.json, no format)");
    }
    html = plan_report_html(o, text);
  } else if (document.contains("rows") && document.contains("learning")) {
    html = comparison_page_html(document, o.input_path);
  } else {
    throw InputError(o.input_path + ": format", "is missing: expected a plan report (\"format\": \"feedplan-plan\", from "
                                                "plan --report) or a comparison (compare.json, with rows[] and learning[])");
  }
  OutputFiles files;
  files.add(o.output_path, html);
  if (const std::string error = files.commit(); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return 1;
  }
  std::printf("report: %s (%zu bytes)\n", o.output_path.c_str(), html.size());
  return 0;
}

}  // namespace feedplan::cli
