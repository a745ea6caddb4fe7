#include "optimize_outputs.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

#include "database_path.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/planner/plan_plot.hpp"

namespace feedplan::cli {

namespace {

using Json = nlohmann::ordered_json;

Json stock_json(const OptimizeRecord& record) {
  Json stock = Json::object();
  if (record.stock_box_mm) {
    stock["box_mm"] = *record.stock_box_mm;
  } else {
    stock["file"] = stored_path(record.stock_path);
  }
  stock["z_bottom_mm"] = record.stock.z_bottom_mm;
  stock["z_top_mm"] = record.stock.z_top_mm;
  return stock;
}

Json summary_json(const OptimizeRecord& record) {
  double cycle_time_s = 0.0, input_cycle_time_s = 0.0, peak_n = 0.0, input_peak_n = 0.0;
  for (const RecordedRun& r : record.runs) {
    if (r.drilling) continue;
    cycle_time_s += r.result.summary.cycle_time_s;
    input_cycle_time_s += r.input_cycle_time_s;
    peak_n = std::max(peak_n, r.result.summary.max_predicted_force_n);
    input_peak_n = std::max(input_peak_n, r.input_peak_force_n);
  }
  Json summary = Json::object();
  summary["cycle_time_s"] = cycle_time_s;
  summary["input_cycle_time_s"] = input_cycle_time_s;
  summary["max_predicted_force_n"] = peak_n;
  summary["input_max_predicted_force_n"] = input_peak_n;
  summary["lines_changed"] = record.refed.lines_changed;
  summary["lines_added"] = record.refed.lines_added;
  summary["moves_split"] = record.refed.moves_split;
  summary["moves_at_lowest_feed"] = record.refed.moves_at_lowest_feed;
  return summary;
}

Json run_json(const RecordedRun& r) {
  Json run = Json::object();
  run["tool_number"] = r.run.number;
  run["first_line"] = r.first_line;
  run["last_line"] = r.last_line;
  run["drilling"] = r.drilling;
  if (r.drilling) return run;
  run["model_kind_reason"] = r.model_kind_reason;
  run["plan"] = Json::parse(planner::plan_report_json(r.result, r.settings, r.context));
  return run;
}

Json operations_json(const OptimizeRecord& record) {
  Json operations = Json::array();
  for (std::size_t k = 0; k < record.operations.size() && k < record.figures.size(); ++k) {
    const ProgramOperation& op = record.operations[k];
    const OperationFigures& f = record.figures[k];
    Json row = Json::object();
    row["name"] = op.name;
    row["first_line"] = op.first_line;
    row["last_line"] = op.last_line;
    row["planned"] = f.planned;
    row["drilling"] = f.drilling;
    row["input_time_s"] = f.input_s;
    row["refed_time_s"] = f.refed_s;
    row["input_peak_force_n"] = f.input_peak_n;
    row["refed_peak_force_n"] = f.refed_peak_n;
    operations.push_back(row);
  }
  return operations;
}

// The run's rows of planner::plan_samples_csv (without its header), each with the tool and line columns.
void append_run_rows(const RecordedRun& r, std::string& csv) {
  const std::string rows = planner::plan_samples_csv(r.result);
  const std::string tool = r.run.number >= 0 ? std::to_string(r.run.number) : std::string();
  std::size_t begin = rows.find('\n') + 1;  // after the header
  for (std::size_t sample = 0; begin < rows.size(); ++sample) {
    const std::size_t end = rows.find('\n', begin);
    csv.append(rows, begin, end - begin);
    csv += ',';
    csv += tool;
    csv += ',';
    if (sample < r.sample_lines.size()) csv += std::to_string(r.sample_lines[sample]);
    csv += '\n';
    begin = end + 1;
  }
}

// The planned runs as one plan: samples and blocks one after the other, s and t continued (for the plot).
planner::PlanResult joined_plan(const OptimizeRecord& record) {
  planner::PlanResult joined;
  double s_mm = 0.0, t_s = 0.0;
  for (const RecordedRun& r : record.runs) {
    if (r.drilling || r.result.samples.empty()) continue;
    const int sample_offset = static_cast<int>(joined.samples.size());
    const int block_offset = static_cast<int>(joined.blocks.size());
    for (planner::PlannedSample p : r.result.samples) {
      p.s_mm += s_mm;
      p.time_s += t_s;
      if (p.block_index >= 0) p.block_index += block_offset;
      joined.samples.push_back(p);
    }
    for (planner::PlannedBlock b : r.result.blocks) {
      b.first_sample += sample_offset;
      b.last_sample += sample_offset;
      joined.blocks.push_back(b);
    }
    s_mm = joined.samples.back().s_mm;
    t_s = joined.samples.back().time_s;
  }
  return joined;
}

}  // namespace

std::string optimize_report_json(const OptimizeRecord& record) {
  Json root = Json::object();
  root["format"] = "feedplan-optimize";
  root["format_version"] = 1;
  root["status"] = record.refused ? "refused" : "ok";
  root["program"] = stored_path(record.program_path);
  root["output"] = record.output_path.empty() ? std::string() : stored_path(record.output_path);
  root["material"] = record.material;
  root["target_force_n"] = record.target_force_n;
  root["stock"] = stock_json(record);
  root["summary"] = summary_json(record);
  Json runs = Json::array();
  for (const RecordedRun& r : record.runs) runs.push_back(run_json(r));
  root["runs"] = runs;
  root["operations"] = operations_json(record);
  return root.dump(2) + "\n";
}

std::string optimize_samples_csv(const OptimizeRecord& record) {
  const std::string plan_csv = planner::plan_samples_csv(planner::PlanResult{});
  std::string csv = plan_csv.substr(0, plan_csv.find('\n'));
  csv += ",tool,line\n";
  for (const RecordedRun& r : record.runs) {
    if (!r.drilling) append_run_rows(r, csv);
  }
  return csv;
}

std::string optimize_plot_svg(const OptimizeRecord& record) {
  planner::PlanPlotOptions options;
  options.title = std::filesystem::path(record.program_path).filename().string();
  options.title += " re-fed — ";
  options.title += record.material;
  options.title += ", target ";
  options.title += shortest_number_text(record.target_force_n);
  options.title += " N";
  if (record.runs.size() > 1) options.title += " (tool runs one after the other)";
  return planner::plan_plot_svg(joined_plan(record), record.target_force_n, options);
}

void stage_optimize_files(const OptimizeOptions& options, const OptimizeRecord& record, OutputFiles& files) {
  if (!options.report_path.empty()) files.add(options.report_path, optimize_report_json(record));
  if (!options.csv_path.empty()) files.add(options.csv_path, optimize_samples_csv(record));
  if (!options.plot_path.empty()) files.add(options.plot_path, optimize_plot_svg(record));
}

}  // namespace feedplan::cli
