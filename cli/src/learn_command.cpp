#include "learn_command.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>

#include "calibration_command.hpp"
#include "database_path.hpp"
#include "html_report_pages.hpp"
#include "learning_pair.hpp"
#include "model_choice.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/writer.hpp"
#include "feedplan/learning/current_calibration.hpp"
#include "feedplan/learning/mechanistic_update.hpp"
#include "feedplan/learning/model_update.hpp"
#include "feedplan/learning/path_correction.hpp"
#include "feedplan/model_db/stale_model_error.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/planner/path_history_plot.hpp"
#include "feedplan/planner/plan_plot.hpp"
#include "feedplan/planner/plan_report.hpp"
#include "feedplan/report/plan_page.hpp"
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

// The plan the parts were cut with, their logs and the database to learn into.
struct LearnInputs {
  planner::PlanReport report;            // the plan report
  std::string spec_path;                 // the cycle spec it came from, where it was found
  cycles::CycleSpec spec;                // that spec
  std::vector<learning::NamedLog> logs;  // the logs, with forces (from currents when calibrated)
  std::string db_path;                   // --db, else the report's (found from here), else $FEEDPLAN_DB, else the sample
  std::optional<learning::SensorDynamics> sensor;  // --sensor-hz, --sensor-damping
};

// The model version planned with, the version learning builds on, and the one learned.
struct ModelVersions {
  model_db::ModelRecord before;   // the plan's model
  model_db::ModelRecord lineage;  // the newest version learned from this program (the plan's model the first time)
  model_db::ModelRecord after;    // the learned version, as stored
};

// The plan again, as it was cut.
struct RemadePlan {
  planner::PlanSettings settings;  // the report's, with the cautious bound it was planned on
  planner::PlanGeometry geometry;  // path and engagement
  planner::PlanResult plan;        // the plan
};

// The plan again: the same model with the correction learned along the path (the response surface), or the
// learned model (the mechanistic kind).
struct Replanned {
  planner::PlanSettings settings;      // the report's, with the path correction (or the learned model)
  learning::PathLearning along_path;   // the learning along this path, for the next part
  std::vector<planner::PathHistoryCycle> history;  // the parts learned from so far, this one last
  planner::PlanResult plan;            // the new plan
  std::string program_text;            // its G-code
};

std::vector<learning::NamedLog> read_logs(const LearnOptions& o) {
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
  return logs;
}

// --db, else the database the report names (found from here), else $FEEDPLAN_DB, else the sample.
std::string learn_database_path(const LearnOptions& o, const planner::PlanReport& report) {
  if (!o.db_path.empty()) return o.db_path;
  if (!report.context.database_path.empty()) return report_database_path(report.context.database_path, o.plan_path);
  return database_path("");
}

// No output may be one of the inputs (the report, the spec it names, the logs, the database) or another output.
void check_learn_outputs(const LearnOptions& o, const LearnInputs& in) {
  std::vector<NamedPath> inputs{{"PLAN", o.plan_path},
                                {"the plan's spec", in.spec_path},
                                {o.db_path.empty() ? "the model database" : "--db", in.db_path},
                                {"--calibration", o.calibration_path}};
  for (const std::string& log : o.log_paths) inputs.push_back({"LOG", log});
  std::vector<InputProblem> problems;
  check_outputs(inputs, {{"-o", o.program_path}, {"--report", o.report_path}, {"--plot", o.plot_path}, {"--html", o.html_path}}, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
}

// Inputs, all read and checked before anything is written.
LearnInputs read_learn_inputs(const LearnOptions& o) {
  LearnInputs in;
  in.sensor = sensor_dynamics(o.sensor);
  in.report = planner::read_plan_report(o.plan_path);
  in.spec_path = resolve_spec(in.report.context.spec_path, o.plan_path);
  in.db_path = learn_database_path(o, in.report);
  check_learn_outputs(o, in);
  in.spec = cycles::load_cycle_spec(in.spec_path);
  in.logs = read_logs(o);
  return in;
}

// Logs that are not of this program, or whose units look wrong, stop the run: each named with why.
void throw_if_not_these_parts(const std::vector<learning::LogEvidence>& logs, const std::vector<std::string>& paths) {
  std::vector<InputProblem> problems;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const auto status = logs[i].alignment.status;
    if (status == learning::AlignmentStatus::kNotThisProgram || status == learning::AlignmentStatus::kUnitsLookWrong) {
      problems.push_back({paths[i], learning::to_string(status) + ": " + logs[i].alignment.message});
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));
}

nlohmann::json errors_json(const learning::PredictionErrors& e) {
  return nlohmann::json{{"rms_n", e.rms_n}, {"median_abs_percent", e.median_abs_percent},
                        {"p95_abs_percent", e.p95_abs_percent}, {"max_abs_percent", e.max_abs_percent},
                        {"mean_percent", e.mean_percent}};
}

// The plan's model, by the report's id; its version, tool and material must be the report's too, or the
// file is not the database the plan was made with (another one, or rebuilt since).
model_db::ModelRecord planned_model(const model_db::Store& store, const LearnOptions& o, const LearnInputs& in) {
  const planner::PlanReportContext& c = in.report.context;
  const auto before = store.model_by_id(c.model_id);
  if (before && before->version == c.model_version && before->tool_name == c.model_tool &&
      before->material_name == c.model_material) {
    return *before;
  }
  const std::string there = before ? "; id " + std::to_string(c.model_id) + " there is " + before->tool_name + " in " +
                                         before->material_name + " v" + std::to_string(before->version)
                                   : "; it has no model with that id";
  const bool other_file = !o.db_path.empty() && !c.database_path.empty() && stored_path(o.db_path) != c.database_path;
  const std::string advice = other_file ? "the plan was made with " + c.database_path + ": give that one with --db (or leave --db out)"
                                        : "the file there was replaced or rebuilt since the plan was made: give the database the plan "
                                          "was made with, with --db";
  throw InputError("model.id", "= " + std::to_string(c.model_id) + ": the plan's model (" + c.model_tool + " in " +
                                   c.model_material + " v" + std::to_string(c.model_version) + ") is not in " + in.db_path +
                                   there + " — " + advice);
}

// The version learning builds on: the newest one learned from this program's logs, as the report of a
// re-planned program names it, else the plan's model. It must be in the database with that version,
// tool and material.
model_db::ModelRecord lineage_model(const model_db::Store& store, const LearnInputs& in, const model_db::ModelRecord& before) {
  const planner::PlanReportContext& c = in.report.context;
  if (c.path_learned_model_id <= 0) return before;
  const auto learned = store.model_by_id(c.path_learned_model_id);
  if (learned && learned->version == c.path_learned_model_version && learned->kind == before.kind) return *learned;
  throw InputError("path_learning.learned_model.id",
                   "= " + std::to_string(c.path_learned_model_id) + " (v" + std::to_string(c.path_learned_model_version) +
                       "): the version learned from this program's earlier parts is not in " + in.db_path +
                       (learned ? " (id " + std::to_string(c.path_learned_model_id) + " there is " + learned->tool_name +
                                      " in " + learned->material_name + " v" + std::to_string(learned->version) + ")"
                                : "") +
                       " — give the database the earlier learning steps were stored in, with --db");
}

// The plan's model must still be the active version of the pair learned into, since the learned version
// is filed as its child; a borrowed plan's pair must have no model yet (one made since would be the
// plan's model now): said before learning, and checked again when storing (Store::add_learned_model).
void require_learnable(const model_db::Store& store, const model_db::ModelRecord& before, const LearningPair& pair) {
  const auto active = store.active_model(pair.tool_name, pair.material_name, before.kind);
  if (active && active->id != before.id) throw model_db::StaleModelError(before, *active);
}

// The report's settings with the cautious bound F̂ + z·σ the plan held when it recorded a relative
// uncertainty (a borrowed model, or --cautious): the covariance is the planned version's, as
// the plan command takes it from the database.
planner::PlanSettings settings_as_planned(const planner::PlanReport& report, const model_db::ModelRecord& before) {
  planner::PlanSettings settings = report.settings;
  if (const auto bound = cautious_bound(before, report.context.model_relative_uncertainty)) settings.uncertainty = bound;
  return settings;
}

// The plan again (deterministic from the spec and the report's settings); it must be the one cut.
RemadePlan remake_plan(const LearnInputs& in, const model_db::ModelRecord& before) {
  const planner::PlanReport& report = in.report;
  const cycles::Cycle cycle = cycles::generate(in.spec);
  RemadePlan remade;
  remade.settings = settings_as_planned(report, before);
  remade.geometry = planner::analyse(cycle.path, cycle.stock, in.spec.tool, report.settings.options.ds_mm);
  remade.plan = planner::plan(remade.geometry, remade.settings);
  if (remade.plan.blocks.size() != report.blocks.size()) {
    throw InputError("blocks", "the plan re-made from " + report.context.spec_path + " has " +
                                   std::to_string(remade.plan.blocks.size()) + " blocks, the report " +
                                   std::to_string(report.blocks.size()) + ": the spec changed since the plan was made");
  }
  return remade;
}

// Learn: RLS and the batch refit over every earlier step of this tool and material and these logs, from
// `before` (the version learning builds on). Throws InputError naming the logs that are not of this program
// or whose units look wrong.
learning::ModelUpdate learn_from_logs(const LearnOptions& o, const LearnInputs& in, const model_db::Store& store,
                                      const model_db::ModelRecord& before, const LearningPair& pair,
                                      const RemadePlan& remade) {
  std::optional<model::Covariance> prior_covariance;
  if (before.fit.covariance(0, 0) > 0.0) prior_covariance = before.fit.covariance;
  // Every earlier learning step of the pair learned into (stored with its samples): the refit spans them all.
  std::vector<learning::LearningSample> earlier;
  for (const model_db::LearnedSample& stored : store.learned_samples(pair.tool_name, pair.material_name)) {
    earlier.push_back({stored.chip_mm, stored.contact_length_mm, stored.force_n, stored.weight, stored.s_mm});
  }
  // The refit goes on from the version learned so far; the plan as cut is the one the logs are aligned with.
  planner::PlanSettings learn_settings = remade.settings;
  learn_settings.model = before.model;
  learning::ModelUpdateOptions options;
  std::optional<model::MechanisticModel> kernel;
  if (in.sensor) {
    // The dynamometer's factor at the feeds the parts were cut with (the plan the logs are aligned with).
    kernel = sensor_kernel(store, pair.tool_name, pair.material_name);
    options.revolutions.sensor_peak_gain =
        learning::sensor_peak_gains(remade.geometry.engagement, remade.geometry.tool, remade.settings.spindle_rpm,
                                    *in.sensor, {kernel ? &*kernel : nullptr, planner::sample_feeds_mm_per_min(remade.plan)});
  }
  learning::ModelUpdate update = learning::update_model(remade.plan, learn_settings, in.spec.tool.flutes, in.logs,
                                                        earlier, prior_covariance, options);
  throw_if_not_these_parts(update.logs, o.log_paths);
  if (in.sensor) update.messages.push_back(describe_sensor_correction(kernel));
  return update;
}

// The re-planned program's G-code, in the dialect the plan was written in.
std::string program_text(const LearnInputs& in, const planner::PlanResult& plan) {
  gcode::WriterOptions writer;
  writer.dialect = gcode::dialect_from_string(in.report.context.dialect).value_or(gcode::Dialect::kLinuxCnc);
  writer.program_name = in.spec.cycle + " " + in.spec.tool.name;
  return gcode::write_gcode(plan.program, writer);
}

// Learning along this path too (learning/path_correction.hpp), carried in the report to the next part.
learning::PathLearning learn_along_this_path(const planner::PlanReport& report, const planner::PlanResult& plan,
                                             const model::ResponseSurfaceModel& planned_model,
                                             const learning::ModelUpdate& update) {
  std::vector<learning::MeasuredRevolutions> measured;
  for (const auto& log : update.logs) measured.push_back(log.revolutions);
  learning::PathLearning previous;
  previous.correction = report.settings.force_correction;
  previous.place_correction = report.context.path_place_correction;
  for (const auto& m : report.context.path_measurements) previous.measurement.push_back({m[0], m[1], m[2], m[3]});
  for (const auto& b : report.context.path_brackets) previous.bracket.push_back({b[0], b[1], b[2], b[3]});
  return learning::learn_along_path(plan, planned_model, measured, report.settings.target_force_n, previous);
}

// Re-plan the same program: the same model, with the correction learned along its path — a fixed knob per
// place from part to part (learning/path_correction.hpp); the refitted version is for other programs.
// The program's G-code.
Replanned replan(const LearnInputs& in, const RemadePlan& remade, const learning::ModelUpdate& update) {
  const planner::PlanReport& report = in.report;
  Replanned next;
  next.settings = remade.settings;
  next.along_path = learn_along_this_path(report, remade.plan, remade.settings.model, update);
  next.history = planner::with_cycle(report.context.path_history,
                                     planner::history_cycle(remade.plan, next.along_path.step_force_n, report.context.path_history));
  next.settings.force_correction = next.along_path.correction;
  next.plan = planner::plan(remade.geometry, next.settings);
  next.program_text = program_text(in, next.plan);
  return next;
}

// Store the learned version with its learning entry and samples (one transaction); returns it as stored.
model_db::ModelRecord store_learned_model(const LearnOptions& o, const LearnInputs& in, model_db::Store& store,
                                          const model_db::ModelRecord& before, const LearningPair& pair,
                                          const learning::ModelUpdate& update) {
  model_db::ModelRecord learned;
  learned.tool_name = pair.tool_name;
  learned.material_name = pair.material_name;
  learned.model = update.model;
  learned.fit.n = update.batch.n;
  learned.fit.rmse_n = update.batch.rms_error_after_n;
  learned.fit.covariance = update.covariance;
  learned.fit.standard_errors = update.batch.standard_error_n;
  learned.source = model_db::ModelSource::kLearned;
  learned.note = o.note.empty() ? "learned from " + std::to_string(in.logs.size()) + " log(s) of " + in.spec.cycle : o.note;
  if (pair.borrowed && o.note.empty() && before.tool_name != pair.tool_name) {
    learned.note += ", starting from the borrowed model of " + before.tool_name + " in " + before.material_name + " v" +
                    std::to_string(before.version);
  }
  model_db::LearningEntry entry;
  entry.model_id_before = before.id;
  entry.part_name = fs::path(o.plan_path).filename().string();
  entry.n_samples = static_cast<int>(update.samples.size());
  entry.error_before_n = update.before.rms_n;
  entry.error_after_n = update.after_batch.rms_n;
  entry.note = learned.note;
  std::vector<model_db::LearnedSample> learned_samples;
  for (const learning::LearningSample& sample : update.samples) {
    learned_samples.push_back({sample.chip_mm, sample.contact_length_mm, sample.force_n, sample.weight, sample.s_mm});
  }
  return store.add_learned_model(learned, entry, learned_samples).first;
}

// The report's context for the new plan: the stored version, the program, the learning along the path.
planner::PlanReportContext next_context(const LearnOptions& o, const LearnInputs& in, const model_db::ModelRecord& stored,
                                        const Replanned& next) {
  const learning::PathLearning& along_path = next.along_path;
  planner::PlanReportContext context = in.report.context;
  if (along_path.correction.empty()) {
    // Re-planned with the learned version itself (the mechanistic kind).
    context.model_id = stored.id;
    context.model_version = stored.version;
    context.model_tool = stored.tool_name;  // the spec's own pair after learning from a borrowed model
    context.model_material = stored.material_name;
  } else {
    // Re-planned with the same model and the correction: the report names the learned version beside it.
    context.path_learned_model_id = stored.id;
    context.path_learned_model_version = stored.version;
  }
  context.program_path = o.program_path;
  context.spec_path = stored_path(in.spec_path);  // absolute: the next learn finds both from any folder
  context.database_path = stored_path(in.db_path);
  context.path_place_correction = along_path.place_correction;
  context.path_measurements.clear();
  for (const auto& m : along_path.measurement) {
    context.path_measurements.push_back({m.chip_mm, m.contact_length_mm, m.force_n, m.window_mm});
  }
  context.path_brackets.clear();
  for (const auto& b : along_path.bracket) {
    context.path_brackets.push_back({b.below_chip_mm, b.below_force_n, b.above_chip_mm, b.above_force_n});
  }
  context.path_history = next.history;
  return context;
}

// Stages --report and --plot (with the measured peaks), which name the stored version.
void stage_learn_reports(const LearnOptions& o, const LearnInputs& in, const model_db::ModelRecord& stored,
                         const std::string& model_label, const std::vector<std::pair<double, double>>& peaks,
                         const Replanned& next, OutputFiles& files) {
  const planner::PlanReportContext context = next_context(o, in, stored, next);
  if (!o.report_path.empty()) files.add(o.report_path, planner::plan_report_json(next.plan, next.settings, context));
  if (!o.html_path.empty()) {
    planner::PlanReport as_written;
    as_written.context = context;
    as_written.settings = next.settings;
    files.add(o.html_path, report::plan_page_html(next.plan, next.settings,
                                                  plan_report_page(as_written, next.plan, o.report_path.empty() ? o.plan_path : o.report_path)));
  }
  if (!o.plot_path.empty() && !next.history.empty()) {
    // Every part learned from so far, and the plan for the next one.
    planner::PathHistoryPlotOptions plot;
    plot.title = in.spec.cycle + ": learning along the path, " + std::to_string(next.history.size()) +
                 (next.history.size() == 1 ? " cycle" : " cycles") + " (newest darkest) and the next plan";
    plot.next = &next.plan;
    std::vector<double> s_mm;
    for (const auto& sample : next.plan.samples) s_mm.push_back(sample.s_mm);
    files.add(o.plot_path, planner::path_history_svg(s_mm, next.history, next.settings.target_force_n, plot));
  } else if (!o.plot_path.empty()) {
    planner::PlanPlotOptions plot;
    plot.title = next.along_path.correction.empty()
                     ? in.spec.cycle + " re-planned with " + model_label + " v" + std::to_string(stored.version) +
                           " (markers: measured peaks)"
                     : in.spec.cycle + " re-planned with the correction learned along its path (markers: measured peaks)";
    plot.measured_peaks = peaks;
    files.add(o.plot_path, planner::plan_plot_svg(next.plan, next.settings.target_force_n, plot));
  }
}

// The measured per-revolution peaks at the middle of their span on the path, for the plot.
std::vector<std::pair<double, double>> measured_peaks(const std::vector<learning::LogEvidence>& logs) {
  std::vector<std::pair<double, double>> peaks;
  for (const auto& log : logs) {
    for (const auto& r : log.revolutions.revolutions) peaks.emplace_back(0.5 * (r.s_start_mm + r.s_end_mm), r.peak_n);
  }
  return peaks;
}

// The outputs are staged around the store write: one that cannot be written stops the run before anything
// is stored (`store_version` is not called), and none is put in place unless the learned version was stored.
// Returns 0, or 1 after saying what failed.
int store_and_write(const LearnOptions& o, const Replanned& next, ModelVersions& models,
                    const std::function<model_db::ModelRecord()>& store_version,
                    const std::function<void(OutputFiles&)>& stage_reports) {
  OutputFiles files;
  if (!files.add(o.program_path, next.program_text)) {
    std::cerr << "feedplan: failed: " << files.error() << "; the database is unchanged\n";
    return 1;
  }
  models.after = store_version();
  stage_reports(files);
  if (auto error = files.commit(); !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "; the learned version v" << models.after.version << " (id "
              << models.after.id << ") is stored (feedplan db history)\n";
    return 1;
  }
  return 0;
}

// The step's messages on stderr; false (after saying so) when it found nothing to learn from.
bool report_update(const std::vector<std::string>& messages, learning::ModelUpdateStatus status) {
  for (const std::string& message : messages) std::cerr << "feedplan: " << message << "\n";
  if (status == learning::ModelUpdateStatus::kOk) return true;
  std::cerr << "feedplan: failed: nothing to learn from; the database is unchanged\n";
  return false;
}

// The before/after errors and the re-planned cycle, as text.
void print_errors_and_replan(const LearnOptions& o, const LearnInputs& in, const learning::PredictionErrors& before,
                             const learning::PredictionErrors& after_rls, const learning::PredictionErrors& after_batch,
                             const Replanned& next) {
  std::printf("per-revolution measured vs predicted:\n");
  print_errors("model learned so far", before);
  print_errors("after RLS (seed 003 Eq. 5)", after_rls);
  print_errors("after robust batch refit", after_batch);
  std::printf("re-planned: cycle time %.2f s (was %.2f s), %zu blocks; wrote %s\n", next.plan.summary.cycle_time_s,
              in.report.summary.cycle_time_s, next.plan.blocks.size(), o.program_path.c_str());
}

void print_learn_json(const LearnInputs& in, const ModelVersions& models, const learning::ModelUpdate& update,
                      const Replanned& next) {
  nlohmann::json out;
  out["model_before"] = {{"id", models.lineage.id}, {"version", models.lineage.version}};
  out["model_after"] = {{"id", models.after.id}, {"version", models.after.version}};
  out["planned_with"] = {{"id", models.before.id}, {"version", models.before.version}};
  out["samples"] = update.samples.size();
  out["gain"] = update.gain;
  out["before"] = errors_json(update.before);
  out["after_rls"] = errors_json(update.after_rls);
  out["after_batch"] = errors_json(update.after_batch);
  out["cycle_time_s"] = {{"before", in.report.summary.cycle_time_s}, {"after", next.plan.summary.cycle_time_s}};
  std::cout << out.dump(2) << "\n";
}

void print_learn_text(const LearnOptions& o, const LearnInputs& in, const ModelVersions& models,
                      const learning::ModelUpdate& update, const Replanned& next) {
  const model_db::ModelRecord& stored = models.after;
  std::printf("learned from %zu log(s): %zu per-revolution samples; model %s in %s v%d → v%d (id %lld)\n", in.logs.size(),
              update.samples.size(), stored.tool_name.c_str(), stored.material_name.c_str(), models.lineage.version,
              stored.version, static_cast<long long>(stored.id));
  print_errors_and_replan(o, in, update.before, update.after_rls, update.after_batch, next);
  std::printf("this program is re-planned with %s in %s v%d and the correction learned along its path; v%d is for "
              "other programs\n",
              models.before.tool_name.c_str(), models.before.material_name.c_str(), models.before.version, stored.version);
}

// The report's kind must be the stored version's: a report edited by hand would otherwise learn one kind
// from the other's plan.
void require_same_kind(const planner::PlanReport& report, const model_db::ModelRecord& before) {
  const bool report_mechanistic = report.settings.mechanistic.has_value();
  if (report_mechanistic == (before.kind == model_db::ModelKind::kMechanistic)) return;
  throw InputError("model.kind", std::string("= ") + (report_mechanistic ? "mechanistic" : "response_surface") +
                                     ", but model id " + std::to_string(before.id) + " in the database is " +
                                     (report_mechanistic ? "a response surface" : "a mechanistic version") +
                                     ": the report and the database disagree (was the report edited?)");
}

// --- the mechanistic kind ---------------------------------------------------------------------------

// The plan with the learned mechanistic model; learning along the path is the response surface's and is
// not carried (its corrections were made against that model's predictions).
Replanned replan_mechanistic(const LearnInputs& in, const RemadePlan& remade, const learning::MechanisticUpdate& update) {
  Replanned next;
  next.settings = remade.settings;
  next.settings.mechanistic = update.model;
  next.settings.force_correction.clear();
  next.plan = planner::plan(remade.geometry, next.settings);
  next.program_text = program_text(in, next.plan);
  return next;
}

// The learned mechanistic version with its learning entry (one transaction); returns it as stored.
model_db::ModelRecord store_learned_mechanistic(const LearnOptions& o, const LearnInputs& in, model_db::Store& store,
                                                const model_db::ModelRecord& before, const LearningPair& pair,
                                                const learning::MechanisticUpdate& update) {
  model_db::ModelRecord learned = before;  // the tests' range and the identification's diagnostics
  learned.tool_name = pair.tool_name;
  learned.material_name = pair.material_name;
  learned.kind = model_db::ModelKind::kMechanistic;
  learned.mechanistic->model = update.model;
  learned.mechanistic->covariance = update.covariance;
  learned.fit.n = static_cast<int>(update.samples.size());
  learned.fit.rmse_n = update.rms_error_after_n;
  learned.source = model_db::ModelSource::kLearned;
  learned.note = o.note.empty() ? "mechanistic, learned from " + std::to_string(in.logs.size()) + " log(s) of " + in.spec.cycle
                                : o.note;
  model_db::LearningEntry entry;
  entry.model_id_before = before.id;
  entry.part_name = fs::path(o.plan_path).filename().string();
  entry.n_samples = static_cast<int>(update.samples.size());
  entry.error_before_n = update.before.rms_n;
  entry.error_after_n = update.after_batch.rms_n;
  entry.note = learned.note;
  return store.add_learned_model(learned, entry).first;
}

void print_mechanistic_learn(const LearnOptions& o, const LearnInputs& in, const ModelVersions& models,
                             const learning::MechanisticUpdate& update, const Replanned& next) {
  const model_db::ModelRecord& stored = models.after;
  const model::MechanisticModel& k = update.model;
  if (o.json) {
    nlohmann::json out;
    out["kind"] = "mechanistic";
    out["model_before"] = {{"id", models.before.id}, {"version", models.before.version}};
    out["model_after"] = {{"id", stored.id}, {"version", stored.version}};
    out["samples"] = update.samples.size();
    out["coefficients"] = {{"ktc_n_per_mm2", k.ktc_n_per_mm2}, {"krc_n_per_mm2", k.krc_n_per_mm2},
                           {"kte_n_per_mm", k.kte_n_per_mm}, {"kre_n_per_mm", k.kre_n_per_mm}};
    out["before"] = errors_json(update.before);
    out["after_rls"] = errors_json(update.after_rls);
    out["after_batch"] = errors_json(update.after_batch);
    out["cycle_time_s"] = {{"before", in.report.summary.cycle_time_s}, {"after", next.plan.summary.cycle_time_s}};
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf("learned from %zu log(s): %zu per-revolution samples; mechanistic model %s in %s v%d → v%d (id %lld)\n",
              in.logs.size(), update.samples.size(), stored.tool_name.c_str(), stored.material_name.c_str(),
              models.before.version, stored.version, static_cast<long long>(stored.id));
  std::printf("  K_tc %.1f N/mm², K_rc %.1f N/mm², K_te %.2f N/mm, K_re %.2f N/mm (runout, helix, size effect held)\n",
              k.ktc_n_per_mm2, k.krc_n_per_mm2, k.kte_n_per_mm, k.kre_n_per_mm);
  print_errors_and_replan(o, in, update.before, update.after_rls, update.after_batch, next);
}

// learn for a plan made with the mechanistic kind: the same inputs, checks and outputs as the response
// surface's, the coefficients learned by learning::update_mechanistic.
int run_mechanistic_learn(const LearnOptions& o, const LearnInputs& in, model_db::Store& store, ModelVersions& models,
                          const LearningPair& pair) {
  const RemadePlan remade = remake_plan(in, models.before);
  const learning::MechanisticUpdate update =
      learning::update_mechanistic(remade.plan, remade.settings, remade.geometry.engagement, in.spec.tool, in.logs,
                                   models.before.mechanistic->covariance);
  throw_if_not_these_parts(update.logs, o.log_paths);
  if (!report_update(update.messages, update.status)) return 1;
  const Replanned next = replan_mechanistic(in, remade, update);
  std::vector<std::pair<double, double>> peaks;
  for (const auto& s : update.samples) peaks.emplace_back(s.s_mm, s.force_n);
  const int written = store_and_write(
      o, next, models, [&] { return store_learned_mechanistic(o, in, store, models.before, pair, update); },
      [&](OutputFiles& files) { stage_learn_reports(o, in, models.after, "mechanistic model", peaks, next, files); });
  if (written != 0) return written;
  print_mechanistic_learn(o, in, models, update, next);
  return 0;
}

}  // namespace

void add_learn_command(CLI::App& app, LearnOptions& options) {
  auto* cmd = app.add_subcommand(
      "learn",
      "Refit the plan's force model from the force logs of parts cut with it (RLS and a robust batch refit with a\n"
      "prior), store it as a new model version for other programs, and re-plan this program with the correction\n"
      "learned along its path");
  cmd->add_option("plan", options.plan_path, "Plan report (JSON) the parts were cut with")->required();
  cmd->add_option("logs", options.log_paths, "Force logs (feedplan CSV or Kistler DynoWare export)")->required();
  cmd->add_option("-o,--output", options.program_path, "Re-planned G-code program to write")->required();
  cmd->add_option("--db", options.db_path, "Model database (default: the report's, else $FEEDPLAN_DB, else the sample)");
  cmd->add_option("--report", options.report_path, "Write the re-planned plan's report (JSON)");
  cmd->add_option("--html", options.html_path,
                  "Write the re-planned plan and the learning history as one self-contained HTML file (feedplan report)");
  cmd->add_option("--plot", options.plot_path, "Write the learning history (SVG): measured force and feed along the path for every cycle so far, and the next plan (the mechanistic kind: the re-planned plan with the measured peaks)");
  cmd->add_option("--note", options.note, "Note stored with the new model version");
  cmd->add_option("--calibration", options.calibration_path,
                  "Servo-current calibration (feedplan calibrate-currents -o) for logs with currents but no forces");
  add_sensor_flags(cmd, options.sensor);
  cmd->add_flag("--json", options.json, "Print the summary as JSON");
}

int run_learn_command(const LearnOptions& o) {
  const LearnInputs in = read_learn_inputs(o);
  model_db::Store store = model_db::Store::open(in.db_path, model_db::OpenMode::kExisting);
  ModelVersions models;
  models.before = planned_model(store, o, in);
  require_same_kind(in.report, models.before);
  models.lineage = lineage_model(store, in, models.before);
  const LearningPair pair = learning_pair(store, in.db_path, in.spec, models.before, in.report.context.model_match_status);
  require_learnable(store, models.lineage, pair);
  if (in.report.settings.mechanistic) return run_mechanistic_learn(o, in, store, models, pair);
  const RemadePlan remade = remake_plan(in, models.before);
  const learning::ModelUpdate update = learn_from_logs(o, in, store, models.lineage, pair, remade);
  if (!report_update(update.messages, update.status)) return 1;
  // Re-plan before storing anything, so that a plan problem stores nothing.
  const Replanned next = replan(in, remade, update);
  const int written = store_and_write(
      o, next, models, [&] { return store_learned_model(o, in, store, models.lineage, pair, update); },
      [&](OutputFiles& files) {
        stage_learn_reports(o, in, models.after, "model", measured_peaks(update.logs), next, files);
      });
  if (written != 0) return written;
  if (o.json) {
    print_learn_json(in, models, update, next);
  } else {
    print_learn_text(o, in, models, update, next);
  }
  return 0;
}

}  // namespace feedplan::cli
