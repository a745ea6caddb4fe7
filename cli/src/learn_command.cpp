#include "learn_command.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "calibration_command.hpp"
#include "database_path.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/learning/current_calibration.hpp"
#include "feedplan/learning/model_update.hpp"
#include "feedplan/learning/path_correction.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/plan_plot.hpp"
#include "feedplan/planner/plan_report.hpp"
#include "feedplan/force_log/force_log.hpp"

namespace feedplan::cli {
namespace {

namespace fs = std::filesystem;

// The spec as the report names it: as given, else beside the report.
std::string resolve_spec(const std::string& spec_path, const std::string& report_path) {
  if (fs::exists(spec_path)) return spec_path;
  const fs::path beside = fs::path(report_path).parent_path() / fs::path(spec_path).filename();
  if (fs::exists(beside)) return beside.string();
  throw InputError("context.spec_path", "= '" + spec_path + "': the cycle spec the plan came from is not there (nor beside " +
                                            report_path + ")");
}

void print_errors(const char* what, const learning::PredictionErrors& e) {
  std::printf("  %-28s RMS %7.2f N, |error| median %6.2f %%, p95 %6.2f %%, max %7.2f %%, mean %+6.2f %%\n", what, e.rms_n,
              e.median_abs_percent, e.p95_abs_percent, e.max_abs_percent, e.mean_percent);
}

}  // namespace

void add_learn_command(CLI::App& app, LearnOptions& options) {
  auto* cmd = app.add_subcommand(
      "learn",
      "Refit the plan's force model from the force logs of parts cut with it (RLS and a robust batch refit with a\n"
      "prior), store it as a new model version, and re-plan the cycle with it");
  cmd->add_option("plan", options.plan_path, "Plan report (JSON) the parts were cut with")->required();
  cmd->add_option("logs", options.log_paths, "Force logs (feedplan CSV or Kistler DynoWare export)")->required();
  cmd->add_option("-o,--output", options.program_path, "Re-planned G-code program to write")->required();
  cmd->add_option("--db", options.db_path, "Model database (default: the report's, else $FEEDPLAN_DB, else the sample)");
  cmd->add_option("--report", options.report_path, "Write the re-planned plan's report (JSON)");
  cmd->add_option("--plot", options.plot_path, "Write the re-planned plan's plot (SVG) with the measured peaks");
  cmd->add_option("--note", options.note, "Note stored with the new model version");
  cmd->add_option("--calibration", options.calibration_path,
                  "Servo-current calibration (feedplan calibrate-currents -o) for logs with currents but no forces");
  cmd->add_flag("--json", options.json, "Print the summary as JSON");
}

int run_learn_command(const LearnOptions& o) {
  // 1. Inputs, all read and checked before anything is written.
  const planner::PlanReport report = planner::read_plan_report(o.plan_path);
  const cycles::CycleSpec spec = cycles::load_cycle_spec(resolve_spec(report.context.spec_path, o.plan_path));
  std::vector<learning::NamedLog> logs;
  std::optional<learning::CurrentCalibration> calibration;
  if (!o.calibration_path.empty()) calibration = load_current_calibration(o.calibration_path);
  for (const std::string& path : o.log_paths) {
    force_log::ForceLog log = force_log::load_force_log(path);
    if (!log.has_forces) {
      if (!log.has_currents || !calibration) {
        throw InputError(path, log.has_currents ? "has servo currents but no forces: give --calibration (feedplan calibrate-currents)"
                                                : "has no force columns");
      }
      // Currents see the mean force (≈ 62 Hz), not the tooth peaks: what is learned is then the model of that.
      log = learning::forces_from_currents(log, *calibration);
    }
    logs.push_back({fs::path(path).filename().string(), std::move(log)});
  }
  const std::string db_path = !o.db_path.empty() ? o.db_path
                              : !report.context.database_path.empty() ? report.context.database_path
                                                                      : database_path("");
  model_db::Store store = model_db::Store::open(db_path, model_db::OpenMode::kExisting);
  const auto before = store.model_by_id(report.context.model_id);
  if (!before) {
    throw InputError("model.id", "= " + std::to_string(report.context.model_id) + ": the plan's model is not in " + db_path);
  }

  // 2. The plan again (deterministic from the spec and the report's settings); it must be the one cut.
  const cycles::Cycle cycle = cycles::generate(spec);
  const planner::PlanGeometry geometry =
      planner::analyse(cycle.path, cycle.stock, spec.tool, report.settings.options.ds_mm);
  const planner::PlanResult plan = planner::plan(geometry, report.settings);
  if (plan.blocks.size() != report.blocks.size()) {
    throw InputError("blocks", "the plan re-made from " + report.context.spec_path + " has " +
                                   std::to_string(plan.blocks.size()) + " blocks, the report " +
                                   std::to_string(report.blocks.size()) + ": the spec changed since the plan was made");
  }

  // 3. Learn.
  std::optional<model::Covariance> prior_covariance;
  if (before->fit.covariance(0, 0) > 0.0) prior_covariance = before->fit.covariance;
  // Every earlier learning step of this tool and material (stored with its samples): the refit spans them all.
  std::vector<learning::LearningSample> earlier;
  for (const model_db::LearnedSample& stored : store.learned_samples(before->tool_name, before->material_name)) {
    earlier.push_back({stored.chip_mm, stored.contact_length_mm, stored.force_n, stored.weight, stored.s_mm});
  }
  const learning::ModelUpdate update =
      learning::update_model(plan, report.settings, spec.tool.flutes, logs, earlier, prior_covariance);
  std::vector<InputProblem> problems;
  for (std::size_t i = 0; i < update.logs.size(); ++i) {
    const auto status = update.logs[i].alignment.status;
    if (status == learning::AlignmentStatus::kNotThisProgram || status == learning::AlignmentStatus::kUnitsLookWrong) {
      problems.push_back({o.log_paths[i], learning::to_string(status) + ": " + update.logs[i].alignment.message});
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  for (const std::string& message : update.messages) std::cerr << "feedplan: " << message << "\n";
  if (update.status != learning::ModelUpdateStatus::kOk) {
    std::cerr << "feedplan: failed: nothing to learn from; the database is unchanged\n";
    return 1;
  }

  // 4. Re-plan with the learned model before storing anything, so that a plan problem stores nothing.
  planner::PlanSettings next_settings = report.settings;
  next_settings.model = update.model;
  learning::PathLearning along_path;
  {
    // Learning along this path too (learning/path_correction.hpp), carried in the report to the next part.
    std::vector<learning::MeasuredRevolutions> measured;
    for (const auto& log : update.logs) measured.push_back(log.revolutions);
    learning::PathLearning previous;
    previous.correction = report.settings.force_correction;
    previous.place_correction = report.context.path_place_correction;
    for (const auto& m : report.context.path_measurements) previous.measurement.push_back({m[0], m[1], m[2], m[3]});
    along_path = learning::learn_along_path(plan, update.model, measured, report.settings.target_force_n, previous);
    next_settings.force_correction = along_path.correction;
  }
  const planner::PlanResult next = planner::plan(geometry, next_settings);
  gcode::WriterOptions writer;
  writer.dialect = gcode::dialect_from_string(report.context.dialect).value_or(gcode::Dialect::kLinuxCnc);
  writer.program_name = spec.cycle + " " + spec.tool.name;
  const std::string text = gcode::write_gcode(next.program, writer);

  // 5. Store (one transaction), then write the files.
  model_db::ModelRecord learned;
  learned.tool_name = before->tool_name;
  learned.material_name = before->material_name;
  learned.model = update.model;
  learned.fit.n = update.batch.n;
  learned.fit.rmse_n = update.batch.rms_error_after_n;
  learned.fit.covariance = update.covariance;
  learned.fit.standard_errors = update.batch.standard_error_n;
  learned.source = model_db::ModelSource::kLearned;
  learned.note = o.note.empty() ? "learned from " + std::to_string(logs.size()) + " log(s) of " + spec.cycle : o.note;
  model_db::LearningEntry entry;
  entry.model_id_before = before->id;
  entry.part_name = fs::path(o.plan_path).filename().string();
  entry.n_samples = static_cast<int>(update.samples.size());
  entry.error_before_n = update.before.rms_n;
  entry.error_after_n = update.after_batch.rms_n;
  entry.note = learned.note;
  std::vector<model_db::LearnedSample> learned_samples;
  for (const learning::LearningSample& sample : update.samples) {
    learned_samples.push_back({sample.chip_mm, sample.contact_length_mm, sample.force_n, sample.weight, sample.s_mm});
  }
  const auto [stored, stored_entry] = store.add_learned_model(learned, entry, learned_samples);
  if (auto error = write_file_atomically(o.program_path, text); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return 1;
  }
  planner::PlanReportContext context = report.context;
  context.model_id = stored.id;
  context.model_version = stored.version;
  context.program_path = o.program_path;
  context.database_path = db_path;
  context.path_place_correction = along_path.place_correction;
  context.path_measurements.clear();
  for (const auto& m : along_path.measurement) {
    context.path_measurements.push_back({m.chip_mm, m.contact_length_mm, m.force_n, m.window_mm});
  }
  if (!o.report_path.empty()) {
    if (auto error = planner::write_plan_report(o.report_path, next, next_settings, context); !error.empty()) {
      std::cerr << "feedplan: failed: " << error << "\n";
      return 1;
    }
  }
  if (!o.plot_path.empty()) {
    planner::PlanPlotOptions plot;
    plot.title = spec.cycle + " re-planned with model v" + std::to_string(stored.version) + " (markers: measured peaks)";
    std::vector<std::pair<double, double>> peaks;
    for (const auto& log : update.logs) {
      for (const auto& r : log.revolutions.revolutions) peaks.emplace_back(0.5 * (r.s_start_mm + r.s_end_mm), r.peak_n);
    }
    plot.measured_peaks = peaks;
    if (auto error = planner::write_plan_plot(o.plot_path, next, next_settings.target_force_n, plot); !error.empty()) {
      std::cerr << "feedplan: failed: " << error << "\n";
      return 1;
    }
  }

  if (o.json) {
    nlohmann::json out;
    out["model_before"] = {{"id", before->id}, {"version", before->version}};
    out["model_after"] = {{"id", stored.id}, {"version", stored.version}};
    out["samples"] = update.samples.size();
    out["gain"] = update.gain;
    const auto errors = [](const learning::PredictionErrors& e) {
      return nlohmann::json{{"rms_n", e.rms_n}, {"median_abs_percent", e.median_abs_percent},
                            {"p95_abs_percent", e.p95_abs_percent}, {"max_abs_percent", e.max_abs_percent},
                            {"mean_percent", e.mean_percent}};
    };
    out["before"] = errors(update.before);
    out["after_rls"] = errors(update.after_rls);
    out["after_batch"] = errors(update.after_batch);
    out["cycle_time_s"] = {{"before", report.summary.cycle_time_s}, {"after", next.summary.cycle_time_s}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("learned from %zu log(s): %zu per-revolution samples; model %s in %s v%d → v%d (id %lld)\n", logs.size(),
                update.samples.size(), stored.tool_name.c_str(), stored.material_name.c_str(), before->version,
                stored.version, static_cast<long long>(stored.id));
    std::printf("per-revolution measured vs predicted:\n");
    print_errors("model planned with", update.before);
    print_errors("after RLS (seed 003 Eq. 5)", update.after_rls);
    print_errors("after robust batch refit", update.after_batch);
    std::printf("re-planned: cycle time %.2f s (was %.2f s), %zu blocks; wrote %s\n", next.summary.cycle_time_s,
                report.summary.cycle_time_s, next.blocks.size(), o.program_path.c_str());
  }
  return 0;
}

}  // namespace feedplan::cli
