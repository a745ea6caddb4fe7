// The plan report (JSON) and the per-sample CSV: the JSON read by an independent parser (nlohmann) has
// every documented field with the plan's values; write → read gives the same settings, context and
// schedule, and re-planning from what was read gives the same blocks; bad report files are rejected with
// the field path and the value; the CSV has the documented columns and numbers that read back.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/plan_report.hpp"
#include "test_models.hpp"

namespace feedplan::planner {
namespace {

namespace fs = std::filesystem;
using ::testing::AllOf;
using ::testing::Contains;
using ::testing::Field;
using ::testing::HasSubstr;

// A real plan of the corner-rounding sample with settings that differ from every default, so that a
// reader falling back to a default is caught.
struct CornerPlan {
  PlanGeometry geometry;
  PlanSettings settings;
  PlanReportContext context;
  PlanResult result;
};

const CornerPlan& corner_plan() {
  static const CornerPlan corner = [] {
    CornerPlan p;
    const cycles::CycleSpec spec = testing::corner_spec();
    const cycles::Cycle cycle = cycles::generate(spec);
    p.geometry = analyse(cycle.path, cycle.stock, spec.tool, 0.1);
    p.settings.model = testing::s50c_like_model();
    p.settings.target_force_n = 337.5;
    p.settings.spindle_rpm = 2750.0;
    p.settings.machine = {8000.0, 12.5, 4200.0, 24000.0, 0.003};
    p.settings.options.mode = PlanMode::kRegulate;
    p.settings.options.air_feed_mm_per_min = 3000.0;
    p.settings.options.merge_tolerance = 0.03;
    p.settings.options.feed_step = 0.04;
    p.settings.options.min_block_duration_s = 0.05;
    p.settings.options.feed_resolution_mm_per_min = 5.0;
    p.settings.options.jerk_limit_mm_per_s3 = 0.0;
    p.settings.options.ds_mm = 0.1;
    p.context.spec_path = "samples/corner.yaml";
    p.context.cycle = spec.cycle;
    p.context.tool = spec.tool;
    p.context.material = spec.material;
    p.context.model_id = 42;
    p.context.model_version = 3;
    p.context.model_tool = "SC EM D10 Z4";
    p.context.model_material = "S50C";
    p.context.model_match = "exact tool and material \"S50C\" (version 3, active)";
    p.context.model_kind_reason = "response surface, as asked (--model-kind)";
    p.context.database_path = "/tmp/models.sqlite";
    p.context.program_path = "corner.ngc";
    p.context.dialect = "linuxcnc";
    p.result = plan(p.geometry, p.settings);
    return p;
  }();
  return corner;
}

fs::path temporary_path(const std::string& name) {
  // One directory per process: ctest runs each test case in its own process, two at a time.
  const fs::path directory = fs::temp_directory_path() / ("feedplan_plan_report_test_" + std::to_string(::getpid()));
  fs::create_directories(directory);
  return directory / name;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::set<std::string> keys_of(const nlohmann::json& object) {
  std::set<std::string> keys;
  for (auto it = object.begin(); it != object.end(); ++it) keys.insert(it.key());
  return keys;
}

// --- JSON as written ------------------------------------------------------------------------------

TEST(PlanReportJson, HoldsEveryDocumentedFieldWithThePlansValues) {
  const CornerPlan& p = corner_plan();
  ASSERT_FALSE(p.result.blocks.empty());
  const std::string text = plan_report_json(p.result, p.settings, p.context);
  const nlohmann::json json = nlohmann::json::parse(text);

  EXPECT_EQ(json["format"], "feedplan-plan");
  EXPECT_EQ(json["format_version"], 1);
  EXPECT_EQ(json["status"], to_string(p.result.status));
  EXPECT_EQ(json["messages"].size(), p.result.messages.size());
  EXPECT_EQ(json["spec"], "samples/corner.yaml");
  EXPECT_EQ(json["cycle"], "corner");
  EXPECT_EQ(json["tool"], (nlohmann::json{{"name", "SC EM D10 Z4"}, {"diameter_mm", 10.0}, {"flutes", 4},
                                          {"helix_deg", 30.0}}));
  EXPECT_EQ(json["material"], "S50C");

  const nlohmann::json& model = json["model"];
  EXPECT_EQ(model["id"], 42);
  EXPECT_EQ(model["version"], 3);
  EXPECT_EQ(model["database"], "/tmp/models.sqlite");
  EXPECT_EQ(model["tool"], "SC EM D10 Z4");
  EXPECT_EQ(model["material"], "S50C");
  EXPECT_EQ(model["match"], p.context.model_match);
  EXPECT_EQ(model["kind_reason"], p.context.model_kind_reason);
  EXPECT_EQ(model["beta"], (nlohmann::json{300.0, 180.0, 40.0, -8.0, -4.0, 12.0}));
  EXPECT_EQ(model["chip_center_mm"], 0.05);
  EXPECT_EQ(model["chip_scale_mm"], 0.04);
  EXPECT_EQ(model["contact_length_center_mm"], 4.0);
  EXPECT_EQ(model["contact_length_scale_mm"], 2.0);
  EXPECT_EQ(model["range"], (nlohmann::json{{"chip_min_mm", 0.005}, {"chip_max_mm", 0.15},
                                            {"contact_length_min_mm", 0.0}, {"contact_length_max_mm", 8.0}}));
  EXPECT_EQ(model["axial_depth_mm"], 10.0);
  EXPECT_EQ(model["spindle_rpm"], 2800.0);

  EXPECT_EQ(json["target_force_n"], 337.5);
  EXPECT_EQ(json["spindle_rpm"], 2750.0);
  EXPECT_EQ(json["machine"], (nlohmann::json{{"max_feed_mm_per_min", 8000.0}, {"min_feed_mm_per_min", 12.5},
                                             {"max_accel_mm_per_s2", 4200.0}, {"rapid_feed_mm_per_min", 24000.0},
                                             {"block_time_min_s", 0.003}}));
  EXPECT_EQ(json["options"], (nlohmann::json{{"mode", "regulate"}, {"air_feed_mm_per_min", 3000.0},
                                             {"merge_tolerance", 0.03}, {"feed_resolution_mm_per_min", 5.0},
                                             {"jerk_limit_mm_per_s3", 0.0}, {"ds_mm", 0.1},
                                             {"coordinate_resolution_mm", 0.001}, {"feed_step", 0.04},
                                             {"min_block_duration_s", 0.05}}));

  const nlohmann::json& summary = json["summary"];
  EXPECT_EQ(keys_of(summary),
            (std::set<std::string>{"cycle_time_s", "cutting_time_s", "air_time_s", "max_predicted_force_n",
                                   "min_feed_mm_per_min", "max_feed_mm_per_min", "baseline", "time_saved_percent",
                                   "engaged_samples", "force_limited_samples", "extrapolated_samples",
                                   "over_target_samples", "short_blocks", "accel_used_mm_per_s2"}));
  const PlanSummary& s = p.result.summary;
  EXPECT_EQ(summary["cycle_time_s"].get<double>(), s.cycle_time_s);
  EXPECT_EQ(summary["max_predicted_force_n"].get<double>(), s.max_predicted_force_n);
  EXPECT_EQ(summary["engaged_samples"].get<int>(), s.engaged_samples);
  EXPECT_EQ(summary["baseline"]["feed_mm_per_min"].get<double>(), s.baseline.feed_mm_per_min);
  EXPECT_EQ(summary["baseline"]["cycle_time_s"].get<double>(), s.baseline.cycle_time_s);
  EXPECT_EQ(keys_of(summary["baseline"]),
            (std::set<std::string>{"feed_mm_per_min", "peak_force_n", "cycle_time_s", "cutting_time_s"}));

  EXPECT_EQ(json["program"], (nlohmann::json{{"path", "corner.ngc"}, {"dialect", "linuxcnc"},
                                             {"blocks", p.result.program.blocks.size()}}));
  const nlohmann::json& blocks = json["blocks"];
  ASSERT_EQ(blocks.size(), p.result.blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const PlannedBlock& block = p.result.blocks[b];
    SCOPED_TRACE("block " + std::to_string(b));
    EXPECT_EQ(keys_of(blocks[b]), (std::set<std::string>{"move_index", "first_sample", "last_sample",
                                                         "feed_mm_per_min", "length_mm", "min_limit_mm_per_min",
                                                         "duration_s"}));
    EXPECT_EQ(blocks[b]["move_index"].get<int>(), block.move_index);
    EXPECT_EQ(blocks[b]["first_sample"].get<int>(), block.first_sample);
    EXPECT_EQ(blocks[b]["last_sample"].get<int>(), block.last_sample);
    EXPECT_EQ(blocks[b]["feed_mm_per_min"].get<double>(), block.feed_mm_per_min);
    EXPECT_EQ(blocks[b]["length_mm"].get<double>(), block.length_mm);
    EXPECT_EQ(blocks[b]["duration_s"].get<double>(), block.duration_s);
  }
  // One block per line after the header of the array.
  EXPECT_THAT(text, HasSubstr("\"blocks\": [\n    {\"move_index\":"));
  EXPECT_EQ(text.back(), '\n');
}

TEST(PlanReportJson, NonFiniteNumbersAreWrittenAsNullAndReadAsNaN) {
  const CornerPlan& p = corner_plan();
  PlanResult result = p.result;
  result.summary.time_saved_percent = std::numeric_limits<double>::quiet_NaN();
  result.summary.baseline.peak_force_n = std::numeric_limits<double>::infinity();
  result.blocks.front().min_limit_mm_per_min = std::numeric_limits<double>::infinity();
  const std::string text = plan_report_json(result, p.settings, p.context);
  const nlohmann::json json = nlohmann::json::parse(text);  // throws on NaN or Infinity tokens
  EXPECT_TRUE(json["summary"]["time_saved_percent"].is_null());
  EXPECT_TRUE(json["summary"]["baseline"]["peak_force_n"].is_null());
  EXPECT_TRUE(json["blocks"][0]["min_limit_mm_per_min"].is_null());

  const PlanReport report = parse_plan_report(text);
  EXPECT_TRUE(std::isnan(report.summary.time_saved_percent));
  EXPECT_TRUE(std::isnan(report.summary.baseline.peak_force_n));
  EXPECT_TRUE(std::isnan(report.blocks.front().min_limit_mm_per_min));
}

TEST(PlanReportJson, EmptyPlanIsValidJsonWithAnEmptySchedule) {
  const CornerPlan& p = corner_plan();
  const std::string text = plan_report_json(PlanResult{}, p.settings, p.context);
  const nlohmann::json json = nlohmann::json::parse(text);
  EXPECT_TRUE(json["blocks"].is_array());
  EXPECT_TRUE(json["blocks"].empty());
  EXPECT_TRUE(parse_plan_report(text).blocks.empty());
}

// --- Round trip -----------------------------------------------------------------------------------

TEST(PlanReportRoundTrip, WriteThenReadGivesTheSameSettingsContextAndBlocks) {
  const CornerPlan& p = corner_plan();
  const fs::path path = temporary_path("round_trip.json");
  ASSERT_EQ(write_plan_report(path, p.result, p.settings, p.context), "");
  const PlanReport report = read_plan_report(path);

  EXPECT_EQ(report.format_version, 1);
  EXPECT_EQ(report.status, p.result.status);
  EXPECT_EQ(report.messages, p.result.messages);

  const PlanReportContext& c = report.context;
  EXPECT_EQ(c.spec_path, p.context.spec_path);
  EXPECT_EQ(c.cycle, p.context.cycle);
  EXPECT_EQ(c.tool.name, p.context.tool.name);
  EXPECT_EQ(c.tool.diameter_mm, p.context.tool.diameter_mm);
  EXPECT_EQ(c.tool.flutes, p.context.tool.flutes);
  EXPECT_EQ(c.tool.helix_deg, p.context.tool.helix_deg);
  EXPECT_EQ(c.material, p.context.material);
  EXPECT_EQ(c.model_id, 42);
  EXPECT_EQ(c.model_version, 3);
  EXPECT_EQ(c.model_tool, p.context.model_tool);
  EXPECT_EQ(c.model_material, p.context.model_material);
  EXPECT_EQ(c.model_match, p.context.model_match);
  EXPECT_EQ(c.model_kind_reason, p.context.model_kind_reason);
  EXPECT_EQ(c.database_path, "/tmp/models.sqlite");
  EXPECT_EQ(c.program_path, "corner.ngc");
  EXPECT_EQ(c.dialect, "linuxcnc");

  const PlanSettings& s = report.settings;
  const model::ResponseSurfaceModel& m = p.settings.model;
  EXPECT_EQ(s.model.beta, m.beta);
  EXPECT_EQ(s.model.chip_center_mm, m.chip_center_mm);
  EXPECT_EQ(s.model.chip_scale_mm, m.chip_scale_mm);
  EXPECT_EQ(s.model.contact_length_center_mm, m.contact_length_center_mm);
  EXPECT_EQ(s.model.contact_length_scale_mm, m.contact_length_scale_mm);
  EXPECT_EQ(s.model.range.chip_min_mm, m.range.chip_min_mm);
  EXPECT_EQ(s.model.range.chip_max_mm, m.range.chip_max_mm);
  EXPECT_EQ(s.model.range.contact_length_min_mm, m.range.contact_length_min_mm);
  EXPECT_EQ(s.model.range.contact_length_max_mm, m.range.contact_length_max_mm);
  EXPECT_EQ(s.model.axial_depth_mm, m.axial_depth_mm);
  EXPECT_EQ(s.model.spindle_rpm, m.spindle_rpm);
  EXPECT_EQ(s.model.quantity, m.quantity);
  EXPECT_EQ(s.target_force_n, 337.5);
  EXPECT_EQ(s.spindle_rpm, 2750.0);
  EXPECT_EQ(s.machine.max_feed_mm_per_min, 8000.0);
  EXPECT_EQ(s.machine.min_feed_mm_per_min, 12.5);
  EXPECT_EQ(s.machine.max_accel_mm_per_s2, 4200.0);
  EXPECT_EQ(s.machine.rapid_feed_mm_per_min, 24000.0);
  EXPECT_EQ(s.machine.block_time_min_s, 0.003);
  EXPECT_EQ(s.options.mode, PlanMode::kRegulate);
  EXPECT_EQ(s.options.air_feed_mm_per_min, 3000.0);
  EXPECT_EQ(s.options.merge_tolerance, 0.03);
  EXPECT_EQ(s.options.feed_step, 0.04);
  EXPECT_EQ(s.options.min_block_duration_s, 0.05);
  EXPECT_EQ(s.options.feed_resolution_mm_per_min, 5.0);
  EXPECT_EQ(s.options.jerk_limit_mm_per_s3, 0.0);
  EXPECT_EQ(s.options.ds_mm, 0.1);

  const PlanSummary& want = p.result.summary;
  EXPECT_EQ(report.summary.cycle_time_s, want.cycle_time_s);
  EXPECT_EQ(report.summary.cutting_time_s, want.cutting_time_s);
  EXPECT_EQ(report.summary.air_time_s, want.air_time_s);
  EXPECT_EQ(report.summary.max_predicted_force_n, want.max_predicted_force_n);
  EXPECT_EQ(report.summary.min_feed_mm_per_min, want.min_feed_mm_per_min);
  EXPECT_EQ(report.summary.max_feed_mm_per_min, want.max_feed_mm_per_min);
  EXPECT_EQ(report.summary.baseline.feed_mm_per_min, want.baseline.feed_mm_per_min);
  EXPECT_EQ(report.summary.baseline.peak_force_n, want.baseline.peak_force_n);
  EXPECT_EQ(report.summary.baseline.cycle_time_s, want.baseline.cycle_time_s);
  EXPECT_EQ(report.summary.baseline.cutting_time_s, want.baseline.cutting_time_s);
  EXPECT_EQ(report.summary.time_saved_percent, want.time_saved_percent);
  EXPECT_EQ(report.summary.engaged_samples, want.engaged_samples);
  EXPECT_EQ(report.summary.force_limited_samples, want.force_limited_samples);
  EXPECT_EQ(report.summary.extrapolated_samples, want.extrapolated_samples);
  EXPECT_EQ(report.summary.over_target_samples, want.over_target_samples);
  EXPECT_EQ(report.summary.short_blocks, want.short_blocks);
  EXPECT_EQ(report.summary.accel_used_mm_per_s2, want.accel_used_mm_per_s2);
  EXPECT_EQ(report.program_blocks, static_cast<int>(p.result.program.blocks.size()));

  ASSERT_EQ(report.blocks.size(), p.result.blocks.size());
  for (std::size_t b = 0; b < report.blocks.size(); ++b) {
    const PlannedBlock& got = report.blocks[b];
    const PlannedBlock& block = p.result.blocks[b];
    SCOPED_TRACE("block " + std::to_string(b));
    EXPECT_EQ(got.move_index, block.move_index);
    EXPECT_EQ(got.first_sample, block.first_sample);
    EXPECT_EQ(got.last_sample, block.last_sample);
    EXPECT_EQ(got.feed_mm_per_min, block.feed_mm_per_min);
    EXPECT_EQ(got.length_mm, block.length_mm);
    EXPECT_EQ(got.min_limit_mm_per_min, block.min_limit_mm_per_min);
    EXPECT_EQ(got.duration_s, block.duration_s);
  }
}

TEST(PlanReportRoundTrip, LearningAlongThePathIsCarriedToTheNextPart) {
  const CornerPlan& p = corner_plan();
  const std::size_t n = p.result.samples.size();
  PlanSettings settings = p.settings;
  PlanReportContext context = p.context;
  for (std::size_t i = 0; i < n; ++i) {
    settings.force_correction.push_back(1.0 + 0.5 * static_cast<double>(i % 7) / 7.0);
    context.path_place_correction.push_back(0.7 + 0.1 * static_cast<double>(i % 5));
    context.path_measurements.push_back({0.01 * static_cast<double>(i % 9), 2.5, 100.0 + 1.0 / 3.0 * i, 0.125});
    context.path_brackets.push_back({0.01 * static_cast<double>(i % 3), 290.0 + i, 0.02 * static_cast<double>(i % 4), 410.5});
  }
  context.path_learned_model_id = 7;
  context.path_learned_model_version = 3;
  for (int cycle : {1, 2}) {
    PathHistoryCycle h;
    h.cycle = cycle;
    h.cycle_time_s = 20.0 / cycle;
    for (std::size_t i = 0; i < n; ++i) {
      h.feed_mm_per_min.push_back(100.0 + 0.1 * static_cast<double>(i));
      h.predicted_n.push_back(300.0 + cycle);
      h.measured_n.push_back(i % 4 == 0 ? 0.0 : 310.5 - cycle);
    }
    context.path_history.push_back(h);
  }
  const fs::path path = temporary_path("path_learning.json");
  ASSERT_EQ(write_plan_report(path, p.result, settings, context), "");
  const PlanReport report = read_plan_report(path);
  EXPECT_EQ(report.settings.force_correction, settings.force_correction);
  EXPECT_EQ(report.context.path_place_correction, context.path_place_correction);
  EXPECT_EQ(report.context.path_measurements, context.path_measurements);
  EXPECT_EQ(report.context.path_brackets, context.path_brackets);
  EXPECT_EQ(report.context.path_learned_model_id, 7);
  EXPECT_EQ(report.context.path_learned_model_version, 3);
  ASSERT_EQ(report.context.path_history.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(report.context.path_history[k].cycle, context.path_history[k].cycle);
    EXPECT_EQ(report.context.path_history[k].cycle_time_s, context.path_history[k].cycle_time_s);
    EXPECT_EQ(report.context.path_history[k].feed_mm_per_min, context.path_history[k].feed_mm_per_min);
    EXPECT_EQ(report.context.path_history[k].predicted_n, context.path_history[k].predicted_n);
    EXPECT_EQ(report.context.path_history[k].measured_n, context.path_history[k].measured_n);
  }
  // A plan that has not learned along its path writes none of it.
  const std::string plain = plan_report_json(p.result, p.settings, p.context);
  EXPECT_EQ(plain.find("path_learning"), std::string::npos);
  EXPECT_EQ(plain.find("force_correction"), std::string::npos);
}

TEST(PlanReportRoundTrip, ReplanningFromTheReadSettingsGivesTheSameSchedule) {
  // What `learn` relies on: the settings in the report are the ones the plan was made with.
  const CornerPlan& p = corner_plan();
  const PlanReport report = parse_plan_report(plan_report_json(p.result, p.settings, p.context));
  const PlanResult again = plan(p.geometry, report.settings);
  ASSERT_EQ(again.blocks.size(), p.result.blocks.size());
  for (std::size_t b = 0; b < again.blocks.size(); ++b) {
    EXPECT_EQ(again.blocks[b].first_sample, p.result.blocks[b].first_sample) << "block " << b;
    EXPECT_EQ(again.blocks[b].feed_mm_per_min, p.result.blocks[b].feed_mm_per_min) << "block " << b;
  }
  EXPECT_EQ(again.summary.cycle_time_s, p.result.summary.cycle_time_s);
}

// A plan made with the mechanistic kind carries its model (every member, the runout and helix too) and
// reads back to the same schedule: what `learn` re-makes the plan from.
TEST(PlanReportRoundTrip, TheMechanisticKindIsCarriedAndReplansTheSame) {
  const CornerPlan& p = corner_plan();
  PlanSettings settings = p.settings;
  model::MechanisticModel m;
  m.ktc_n_per_mm2 = 1834.5;
  m.krc_n_per_mm2 = 611.25;
  m.kte_n_per_mm = 17.125;
  m.kre_n_per_mm = 19.5;
  m.size_exponent = 0.1875;
  m.size_reference_chip_mm = 0.0437;
  m.runout_mm = {0.0, 0.0031, 0.0066, 0.0029};
  m.helix_deg = 26.25;
  settings.mechanistic = m;
  const PlanResult result = plan(p.geometry, settings);
  const std::string text = plan_report_json(result, settings, p.context);
  EXPECT_EQ(nlohmann::json::parse(text)["model"]["kind"], "mechanistic");
  const PlanReport report = parse_plan_report(text);
  ASSERT_TRUE(report.settings.mechanistic.has_value());
  const model::MechanisticModel& back = *report.settings.mechanistic;
  EXPECT_EQ(back.ktc_n_per_mm2, m.ktc_n_per_mm2);
  EXPECT_EQ(back.krc_n_per_mm2, m.krc_n_per_mm2);
  EXPECT_EQ(back.kte_n_per_mm, m.kte_n_per_mm);
  EXPECT_EQ(back.kre_n_per_mm, m.kre_n_per_mm);
  EXPECT_EQ(back.size_exponent, m.size_exponent);
  EXPECT_EQ(back.size_reference_chip_mm, m.size_reference_chip_mm);
  EXPECT_EQ(back.size_min_chip_mm, m.size_min_chip_mm);
  EXPECT_EQ(back.runout_mm, m.runout_mm);
  EXPECT_EQ(back.helix_deg, m.helix_deg);
  const PlanResult again = plan(p.geometry, report.settings);
  ASSERT_EQ(again.blocks.size(), result.blocks.size());
  for (std::size_t b = 0; b < again.blocks.size(); ++b) {
    EXPECT_EQ(again.blocks[b].feed_mm_per_min, result.blocks[b].feed_mm_per_min) << "block " << b;
  }
  // A report of the response surface says so, and one from before the kinds reads as the response surface.
  nlohmann::json old = nlohmann::json::parse(plan_report_json(p.result, p.settings, p.context));
  EXPECT_EQ(old["model"]["kind"], "response_surface");
  old["model"].erase("kind");
  EXPECT_FALSE(parse_plan_report(old.dump()).settings.mechanistic.has_value());
  old["model"]["kind"] = "quadratic";
  try {
    parse_plan_report(old.dump());
    ADD_FAILURE() << "an unknown kind was accepted";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("model.kind = 'quadratic': must be response_surface or mechanistic"));
  }
}

TEST(PlanReportRoundTrip, WritingIntoAMissingDirectoryFailsWithAMessageAndWritesNothing) {
  const CornerPlan& p = corner_plan();
  const fs::path path = temporary_path("no_such_dir") / "plan.json";
  const std::string error = write_plan_report(path, p.result, p.settings, p.context);
  EXPECT_THAT(error, HasSubstr(path.string()));
  EXPECT_FALSE(fs::exists(path));
}

// --- Bad report files -----------------------------------------------------------------------------

// The report as JSON, changed by `edit`, written to a file and read back; the problems thrown.
std::vector<InputProblem> problems_after(const std::function<void(nlohmann::ordered_json&)>& edit) {
  const CornerPlan& p = corner_plan();
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(plan_report_json(p.result, p.settings, p.context));
  edit(json);
  const fs::path path = temporary_path("edited.json");
  std::ofstream(path, std::ios::binary | std::ios::trunc) << json.dump(2);
  try {
    read_plan_report(path);
  } catch (const InputError& error) {
    return error.problems();
  }
  ADD_FAILURE() << "no InputError";
  return {};
}

auto problem(const std::string& field, const std::string& message_part) {
  return AllOf(Field(&InputProblem::field, field), Field(&InputProblem::message, HasSubstr(message_part)));
}

TEST(PlanReportRead, MissingFieldIsNamedWithItsPath) {
  EXPECT_THAT(problems_after([](auto& j) { j["model"].erase("chip_scale_mm"); }),
              Contains(problem("model.chip_scale_mm", "is missing")));
  EXPECT_THAT(problems_after([](auto& j) { j["model"]["range"].erase("chip_max_mm"); }),
              Contains(problem("model.range.chip_max_mm", "is missing")));
  EXPECT_THAT(problems_after([](auto& j) { j["blocks"][1].erase("feed_mm_per_min"); }),
              Contains(problem("blocks[1].feed_mm_per_min", "is missing")));
  EXPECT_THAT(problems_after([](auto& j) { j.erase("machine"); }), Contains(problem("machine", "is missing")));
}

TEST(PlanReportRead, MissingObjectIsReportedOnceNotOncePerMember) {
  const std::vector<InputProblem> problems = problems_after([](auto& j) { j.erase("machine"); });
  EXPECT_EQ(problems.size(), 1u) << InputError(problems).what();
}

TEST(PlanReportRead, WrongTypesAreNamedWithTheValueFound) {
  EXPECT_THAT(problems_after([](auto& j) { j["target_force_n"] = "300"; }),
              Contains(problem("target_force_n", "= \"300\": must be a finite number")));
  EXPECT_THAT(problems_after([](auto& j) { j["tool"]["flutes"] = 4.5; }),
              Contains(problem("tool.flutes", "= 4.5: must be an integer")));
  EXPECT_THAT(problems_after([](auto& j) { j["blocks"][2]["first_sample"] = "7"; }),
              Contains(problem("blocks[2].first_sample", "= \"7\"")));
  EXPECT_THAT(problems_after([](auto& j) { j["blocks"] = nlohmann::ordered_json::object(); }),
              Contains(problem("blocks", "must be an array")));
  EXPECT_THAT(problems_after([](auto& j) { j["blocks"][0] = 5; }), Contains(problem("blocks[0]", "= 5: must be an object")));
  EXPECT_THAT(problems_after([](auto& j) { j["messages"][0] = 1; }), Contains(problem("messages[0]", "must be a string")));
  EXPECT_THAT(problems_after([](auto& j) { j["model"]["beta"] = {1, 2, 3}; }),
              Contains(problem("model.beta", "has 3 elements: must have 6")));
}

TEST(PlanReportRead, NullOrNaNWhereTheSettingsNeedANumberIsAnError) {
  EXPECT_THAT(problems_after([](auto& j) { j["model"]["beta"][2] = nullptr; }),
              Contains(problem("model.beta[2]", "= null: must be a finite number")));
  EXPECT_THAT(problems_after([](auto& j) { j["machine"]["max_accel_mm_per_s2"] = nullptr; }),
              Contains(problem("machine.max_accel_mm_per_s2", "= null")));
  EXPECT_THAT(problems_after([](auto& j) { j["blocks"][0]["duration_s"] = nullptr; }),
              Contains(problem("blocks[0].duration_s", "= null")));
}

TEST(PlanReportRead, UnknownNamesAreListedWithTheAllowedOnes) {
  EXPECT_THAT(problems_after([](auto& j) { j["options"]["mode"] = "fast"; }),
              Contains(problem("options.mode", "= 'fast': must be one of 'safe', 'regulate'")));
  EXPECT_THAT(problems_after([](auto& j) { j["status"] = "great"; }),
              Contains(problem("status", "= 'great': must be one of 'ok', 'extrapolated', 'target not met'")));
}

TEST(PlanReportRead, OutOfRangeValuesAreRejectedByThePlannersChecks) {
  EXPECT_THAT(problems_after([](auto& j) { j["target_force_n"] = -5; }), Contains(Field(&InputProblem::field, "target_force_n")));
  EXPECT_THAT(problems_after([](auto& j) { j["model"]["chip_scale_mm"] = 0; }),
              Contains(Field(&InputProblem::field, "model.chip_scale_mm")));
  EXPECT_THAT(problems_after([](auto& j) { j["blocks"][0]["length_mm"] = -1; }),
              Contains(problem("blocks[0].length_mm", "= -1: must be ≥ 0")));
}

TEST(PlanReportRead, LearningAlongThePathMustMatchThePlanSamples) {
  // The corner plan's report has no force_correction: one value is one too many.
  EXPECT_THAT(problems_after([](auto& j) {
                j["path_learning"] = {{"place_correction", {1.0}}, {"measurements", {{0.05, 2.0, 300.0, 0.1}}}};
              }),
              Contains(problem("path_learning.place_correction", "has 1 values: must have 0")));
  const auto with_correction = [](auto& j) {
    j["force_correction"] = {1.0, 1.1};
    j["path_learning"] = {{"place_correction", {1.0, 9.0}}, {"measurements", {{0.05, 2.0, 300.0, 0.1}, {0.05, -2.0, 300.0}}}};
  };
  EXPECT_THAT(problems_after(with_correction),
              Contains(problem("path_learning.place_correction[1]", "= 9: must be in [0.2, 5]")));
  EXPECT_THAT(problems_after(with_correction),
              Contains(problem("path_learning.measurements[1]", "must be an array of 4 numbers")));
  EXPECT_THAT(problems_after([](auto& j) {
                j["force_correction"] = {1.0};
                j["path_learning"] = {{"place_correction", {1.0}}, {"measurements", {{0.05, -2.0, 300.0, 0.1}}}};
              }),
              Contains(problem("path_learning.measurements[0][1]", "= -2: must be ≥ 0")));
  const auto with_learning = [](const nlohmann::json& extra) {
    return [extra](auto& j) {
      j["force_correction"] = {1.0};
      j["path_learning"] = {{"place_correction", {1.0}}, {"measurements", {{0.05, 2.0, 300.0, 0.1}}}};
      for (const auto& [key, value] : extra.items()) j["path_learning"][key] = value;
    };
  };
  EXPECT_THAT(problems_after(with_learning({{"brackets", {{0.05, 300.0}}}})),
              Contains(problem("path_learning.brackets[0]", "must be an array of 4 numbers")));
  EXPECT_THAT(problems_after(with_learning({{"brackets", {{0.05, -300.0, 0.0, 0.0}}}})),
              Contains(problem("path_learning.brackets[0][1]", "= -300: must be ≥ 0")));
  EXPECT_THAT(problems_after(with_learning({{"learned_model", {{"id", 2.5}, {"version", 2}}}})),
              Contains(problem("path_learning.learned_model.id", "= 2.5: must be a whole number ≥ 1")));
  EXPECT_THAT(problems_after(with_learning({{"learned_model", {{"id", 2}, {"version", 0}}}})),
              Contains(problem("path_learning.learned_model.version", "= 0: must be a whole number ≥ 1")));
  const auto cycle = [](int number, nlohmann::json measured) {
    return nlohmann::json{{"cycle", number}, {"cycle_time_s", 12.5}, {"feed_mm_per_min", {800.0}},
                          {"predicted_n", {400.0}}, {"measured_n", std::move(measured)}};
  };
  EXPECT_THAT(problems_after(with_learning({{"history", {cycle(1, {410.0, 2.0})}}})),
              Contains(problem("path_learning.history[0].measured_n", "has 2 values: must have 1")));
  EXPECT_THAT(problems_after(with_learning({{"history", {cycle(1, {-4.0})}}})),
              Contains(problem("path_learning.history[0].measured_n[0]", "= -4: must be ≥ 0")));
  EXPECT_THAT(problems_after(with_learning({{"history", {cycle(2, {410.0}), cycle(2, {405.0})}}})),
              Contains(problem("path_learning.history[1].cycle", "= 2: must be larger than the cycle before (2)")));
  EXPECT_THAT(problems_after(with_learning({{"history", {cycle(0, {410.0})}}})),
              Contains(problem("path_learning.history[0].cycle", "")));
  // A well-formed history reads back (the edit that makes it so, and nothing else, in a valid report).
  const CornerPlan& p = corner_plan();
  nlohmann::ordered_json json = nlohmann::ordered_json::parse(plan_report_json(p.result, p.settings, p.context));
  json["force_correction"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < p.result.samples.size(); ++i) json["force_correction"].push_back(1.0);
  const std::vector<double> ones(p.result.samples.size(), 1.0), zeros(p.result.samples.size(), 0.0);
  std::vector<std::array<double, 4>> rows(p.result.samples.size(), {0.0, 0.0, 0.0, 0.0});
  json["path_learning"] = {{"place_correction", ones}, {"measurements", rows},
                           {"history", {{{"cycle", 1}, {"cycle_time_s", 12.5}, {"feed_mm_per_min", ones},
                                         {"predicted_n", ones}, {"measured_n", zeros}}}}};
  EXPECT_EQ(parse_plan_report(json.dump()).context.path_history.size(), 1u);
}

// A report's tool of diameter 0 was accepted, and learning refitted a model for a tool that cannot exist.
TEST(PlanReportRead, ToolOutsideTheSpecsRangesIsRejected) {
  EXPECT_THAT(problems_after([](auto& j) { j["tool"]["diameter_mm"] = 0; }),
              Contains(problem("tool.diameter_mm", "= 0: must be finite and > 0 mm")));
  EXPECT_THAT(problems_after([](auto& j) { j["tool"]["flutes"] = 1000; }),
              Contains(problem("tool.flutes", "= 1000: must be in [1, 32]")));
  EXPECT_THAT(problems_after([](auto& j) { j["tool"]["helix_deg"] = -5; }),
              Contains(problem("tool.helix_deg", "= -5: must be in [0, 60)")));
}

// A tool's own plunge feed per tooth goes into the report and comes back; the default is not written and
// reads back as the default.
TEST(PlanReportRoundTrip, TheToolsPlungeFeedPerToothComesBack) {
  const CornerPlan& p = corner_plan();
  PlanReportContext context = p.context;
  context.tool.max_plunge_feed_per_tooth_mm = 0.0375;
  const std::string text = plan_report_json(p.result, p.settings, context);
  EXPECT_EQ(nlohmann::json::parse(text)["tool"]["max_plunge_feed_per_tooth_mm"], 0.0375);
  const PlanReport report = parse_plan_report(text);
  EXPECT_EQ(report.context.tool.max_plunge_feed_per_tooth_mm, 0.0375);
  EXPECT_EQ(report.context.tool.plunge_feed_per_tooth_mm(), 0.0375);

  ASSERT_EQ(p.context.tool.max_plunge_feed_per_tooth_mm, 0.0);
  const std::string default_text = plan_report_json(p.result, p.settings, p.context);
  EXPECT_FALSE(nlohmann::json::parse(default_text)["tool"].contains("max_plunge_feed_per_tooth_mm"));
  const PlanReport default_report = parse_plan_report(default_text);
  EXPECT_EQ(default_report.context.tool.max_plunge_feed_per_tooth_mm, 0.0);
  EXPECT_DOUBLE_EQ(default_report.context.tool.plunge_feed_per_tooth_mm(), 0.0025 * p.context.tool.diameter_mm);
}

TEST(PlanReportRead, APlungeFeedPerToothOutsideZeroToTheDiameterIsRejected) {
  const std::string expected = ": must be in (0, 10] mm (a feed per tooth at most the tool diameter)";
  EXPECT_THAT(problems_after([](auto& j) { j["tool"]["max_plunge_feed_per_tooth_mm"] = 12; }),
              Contains(problem("tool.max_plunge_feed_per_tooth_mm", "= 12" + expected)));
  EXPECT_THAT(problems_after([](auto& j) { j["tool"]["max_plunge_feed_per_tooth_mm"] = 0; }),
              Contains(problem("tool.max_plunge_feed_per_tooth_mm", "= 0" + expected)));
  const std::vector<InputProblem> text = problems_after([](auto& j) { j["tool"]["max_plunge_feed_per_tooth_mm"] = "fast"; });
  ASSERT_EQ(text.size(), 1u);
  EXPECT_EQ(to_string(text.front()), "tool.max_plunge_feed_per_tooth_mm = \"fast\": must be a finite number");
}

TEST(PlanReportRead, BlocksOutOfOrderAreRejected) {
  EXPECT_THAT(problems_after([](auto& j) { j["blocks"][0]["last_sample"] = -1; }),
              Contains(Field(&InputProblem::field, "blocks[0].last_sample")));
  EXPECT_THAT(problems_after([](auto& j) {
                j["blocks"][1]["first_sample"] = 0;
                j["blocks"][0]["last_sample"] = 5;
              }),
              Contains(problem("blocks[1].first_sample", "must be ≥ blocks[0].last_sample (5)")));
}

TEST(PlanReportRead, EveryProblemIsReportedAtOnce) {
  const std::vector<InputProblem> problems = problems_after([](auto& j) {
    j["spindle_rpm"] = "fast";
    j["model"].erase("chip_center_mm");
    j["blocks"][0]["feed_mm_per_min"] = true;
  });
  EXPECT_THAT(problems, Contains(Field(&InputProblem::field, "spindle_rpm")));
  EXPECT_THAT(problems, Contains(Field(&InputProblem::field, "model.chip_center_mm")));
  EXPECT_THAT(problems, Contains(Field(&InputProblem::field, "blocks[0].feed_mm_per_min")));
}

TEST(PlanReportRead, AnotherFormatIsRejectedBeforeItsFields) {
  const std::vector<InputProblem> problems = problems_after([](auto& j) { j["format"] = "feedplan-model-db"; });
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_THAT(problems[0], problem("format", "= 'feedplan-model-db': must be 'feedplan-plan'"));
  EXPECT_THAT(problems_after([](auto& j) { j.erase("format"); }), Contains(problem("format", "is missing")));
}

TEST(PlanReportRead, NewerFormatVersionIsRejected) {
  EXPECT_THAT(problems_after([](auto& j) { j["format_version"] = 2; }),
              Contains(problem("format_version", "= 2: ")));
  EXPECT_THAT(problems_after([](auto& j) { j["format_version"] = 0; }), Contains(Field(&InputProblem::field, "format_version")));
  EXPECT_THAT(problems_after([](auto& j) { j["format_version"] = "1"; }),
              Contains(problem("format_version", "= \"1\"")));
}

TEST(PlanReportRead, TextThatIsNotAReportNamesTheSource) {
  EXPECT_THROW(
      {
        try {
          parse_plan_report("{\"format\": \"feedplan-plan\",", "plan.json");
        } catch (const InputError& error) {
          EXPECT_EQ(error.problems().at(0).field, "plan.json");
          EXPECT_THAT(error.problems().at(0).message, HasSubstr("is not valid JSON"));
          throw;
        }
      },
      InputError);
  EXPECT_THROW(parse_plan_report("[1, 2]", "plan.json"), InputError);
  const fs::path missing = temporary_path("does_not_exist.json");
  try {
    read_plan_report(missing);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.problems().at(0).field, missing.string());
  }
}

// --- CSV ------------------------------------------------------------------------------------------

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(line);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!line.empty() && line.back() == separator) parts.emplace_back();
  return parts;
}

const std::string kCsvHeader =
    "s_mm,x_mm,y_mm,engagement_deg,chip_thickness_mm,contact_length_mm,feed_mm_per_min,predicted_force_n,time_s,"
    "z_mm,chip_factor,feed_limit_mm_per_min,limit_reason,command_feed_mm_per_min,block_feed_mm_per_min,block,"
    "engaged,extrapolated";

TEST(PlanSamplesCsv, OneRowPerSampleUnderTheDocumentedHeader) {
  PlanResult result;
  PlannedSample sample;
  sample.s_mm = 1.25;
  sample.position = {10.5, -2.0, -10.0};
  sample.engagement_rad = 3.14159265358979323846 / 2.0;
  sample.chip_thickness_mm = 0.0421;
  sample.contact_length_mm = 7.853981633974483;
  sample.feed_mm_per_min = 1234.5;
  sample.predicted_force_n = 299.99999;
  sample.time_s = 0.0125;
  sample.chip_factor = 1.0;
  sample.feed_limit_mm_per_min = 10000.0;
  sample.limit_reason = FeedLimitReason::kMaxFeed;
  sample.command_feed_mm_per_min = 1240.0;
  sample.block_feed_mm_per_min = 1235.0;
  sample.block_index = 3;
  sample.engaged = true;
  sample.extrapolated = false;
  result.samples.push_back(sample);
  sample.limit_reason = FeedLimitReason::kRapid;
  sample.engaged = false;
  sample.extrapolated = true;
  sample.predicted_force_n = std::numeric_limits<double>::quiet_NaN();
  sample.position.x_mm = -0.00001;
  result.samples.push_back(sample);

  const std::string csv = plan_samples_csv(result);
  const std::vector<std::string> lines = split(csv, '\n');
  ASSERT_EQ(lines.size(), 4u);  // header, two rows, "" after the final newline
  EXPECT_EQ(lines[0], kCsvHeader);
  EXPECT_EQ(lines[1], "1.25,10.5,-2,90,0.0421,7.854,1234.5,300,0.0125,-10,1,10000,max feed,1240,1235,3,1,0");
  EXPECT_EQ(lines[2], "1.25,0,-2,90,0.0421,7.854,1234.5,nan,0.0125,-10,1,10000,rapid,1240,1235,3,0,1");
  EXPECT_EQ(lines[3], "");
}

TEST(PlanSamplesCsv, RealPlanReadsBackWithinTheWrittenPrecision) {
  const CornerPlan& p = corner_plan();
  const fs::path path = temporary_path("samples.csv");
  ASSERT_EQ(write_plan_samples_csv(path, p.result), "");
  std::istringstream in(read_text(path));
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, kCsvHeader);
  const std::size_t columns = split(kCsvHeader, ',').size();
  ASSERT_EQ(columns, 18u);
  std::size_t row = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(row, p.result.samples.size());
    const PlannedSample& s = p.result.samples[row];
    const std::vector<std::string> fields = split(line, ',');
    ASSERT_EQ(fields.size(), columns) << line;
    EXPECT_NEAR(std::stod(fields[0]), s.s_mm, 0.5e-4);
    EXPECT_NEAR(std::stod(fields[1]), s.position.x_mm, 0.5e-4);
    EXPECT_NEAR(std::stod(fields[2]), s.position.y_mm, 0.5e-4);
    EXPECT_NEAR(std::stod(fields[3]), s.engagement_rad * 180.0 / 3.14159265358979323846, 0.5e-4);
    EXPECT_NEAR(std::stod(fields[4]), s.chip_thickness_mm, 0.5e-6);
    EXPECT_NEAR(std::stod(fields[6]), s.feed_mm_per_min, 0.5e-3);
    EXPECT_NEAR(std::stod(fields[7]), s.predicted_force_n, 0.5e-3);
    EXPECT_NEAR(std::stod(fields[8]), s.time_s, 0.5e-6);
    EXPECT_EQ(fields[12], to_string(s.limit_reason));
    EXPECT_EQ(std::stoi(fields[15]), s.block_index);
    EXPECT_EQ(fields[16], s.engaged ? "1" : "0");
    ++row;
  }
  EXPECT_EQ(row, p.result.samples.size());
}

}  // namespace
}  // namespace feedplan::planner
