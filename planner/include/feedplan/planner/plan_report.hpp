#pragma once
// The plan report (docs/method.md §4): a JSON summary of one plan — what was asked (model, target, machine,
// options), where it came from (spec, tool, material, model version, database, program) and what the
// planner predicts (summary, the constant-feed baseline, the block schedule) — and a CSV with one row
// per engagement sample. The `learn` command reads the JSON back (read_plan_report) to re-plan with a
// refitted model, so the field names below are a stable format.
//
// JSON ("format": "feedplan-plan", "format_version": 1), keys in this order:
//   format, format_version, status, messages[],
//   spec, cycle, tool {name, diameter_mm, flutes, helix_deg, max_plunge_feed_per_tooth_mm (only when the
//        tool has its own plunge feed per tooth; absent: the default of geometry::Tool)}, material,
//   model {id, version, database, tool, material, match, beta[6], chip_center_mm, chip_scale_mm,
//          contact_length_center_mm, contact_length_scale_mm,
//          range {chip_min_mm, chip_max_mm, contact_length_min_mm, contact_length_max_mm},
//          axial_depth_mm, spindle_rpm, quantity, kind ("response_surface" or "mechanistic"; optional on
//          reading: the response surface), kind_reason (which kind planned and why; optional on reading), mechanistic {model/mechanistic_json.hpp's members} (only with
//          the mechanistic kind, which plans with it: the response surface's members then give only its
//          tests' range)},
//   target_force_n, spindle_rpm,
//   machine {max_feed_mm_per_min, min_feed_mm_per_min, max_accel_mm_per_s2, rapid_feed_mm_per_min,
//            block_time_min_s},
//   options {mode, air_feed_mm_per_min, merge_tolerance, feed_resolution_mm_per_min,
//            jerk_limit_mm_per_s3, ds_mm, coordinate_resolution_mm (optional on reading: 0.001),
//            feed_step, min_block_duration_s (optional on reading: 0, 0.1)},
//   force_correction[] (only when set: one c per plan sample),
//   path_learning {place_correction[], measurements[[t_m, L, F, window] per sample],
//            brackets[[t_m below, F below, t_m above, F above] per sample] (optional on reading),
//            learned_model {id, version} (optional on reading),
//            history [{cycle, cycle_time_s, feed_mm_per_min[], predicted_n[], measured_n[]}] (path_history.hpp;
//            optional on reading)} (only after learning along the path; as many entries as force_correction,
//            in every array of history too),
//   summary {every PlanSummary field by its name; baseline {feed_mm_per_min, peak_force_n,
//            cycle_time_s, cutting_time_s}},
//   program {path, dialect, blocks (count of program blocks)},
//   blocks [{move_index, first_sample, last_sample, feed_mm_per_min, length_mm, min_limit_mm_per_min,
//            duration_s}]   (one block per line, in program order)
// Numbers are written so that they read back as the same double. JSON has no NaN or infinity: a
// non-finite number is written as null. The reader accepts null only where the writer may produce it
// from a plan (summary numbers and blocks[].min_limit_mm_per_min, read back as NaN); everywhere the
// settings or the schedule need a number, null is an error.
//
// CSV: a header row, then one row per sample, comma-separated, no metadata lines. Columns:
//   s_mm, x_mm, y_mm, engagement_deg, chip_thickness_mm, contact_length_mm, feed_mm_per_min,
//   predicted_force_n, time_s                         (docs/method.md §4)
//   z_mm, chip_factor, feed_limit_mm_per_min, limit_reason, command_feed_mm_per_min,
//   block_feed_mm_per_min, block, engaged, extrapolated   (extras)
// Numbers in fixed precision with trailing zeros dropped: lengths 4 decimals (0.1 µm), angles 4, chip
// thickness and chip factor 6, feeds and forces 3, times 6; non-finite values as nan, inf, -inf.
// limit_reason is to_string(FeedLimitReason) ("max feed"); block is PlannedSample::block_index;
// engaged and extrapolated are 1 or 0.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/geometry/tool.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/path_history.hpp"

namespace feedplan::planner {

//! The "format_version" this code writes; the reader accepts 1 up to this.
inline constexpr int kPlanReportFormatVersion = 1;

//! What the caller (the CLI) knows about a plan besides the PlanResult and its settings.
struct PlanReportContext {
  std::string spec_path;          //!< the cycle spec the plan came from (the CLI stores it absolute)
  std::string cycle;              //!< cycle name, e.g. "trochoid"
  geometry::Tool tool;            //!< the end mill: name, diameter, flutes, helix, plunge feed per tooth
  std::string material;           //!< workpiece material name, e.g. "S50C"
  std::int64_t model_id = 0;      //!< row id of the stored model version used (0: not from a database)
  int model_version = 0;          //!< version number of that model
  std::string model_tool;         //!< tool name the model was fitted for
  std::string model_material;     //!< material name the model was fitted for
  std::string model_match;        //!< one sentence on how the model was chosen
  std::string model_match_status; //!< "exact" or "borrowed" ("" when not recorded)
  std::vector<std::string> model_differences;  //!< what the borrowed model differs in, e.g. "diameter 10 mm for 8 mm"
  double model_relative_uncertainty = 0.0;     //!< r of the cautious bound the plan held (0: the model alone)
  std::string model_kind_reason;  //!< which kind of model planned and why, for people ("" when not recorded)
  std::string database_path;      //!< the model database ("" when none; the CLI stores it absolute and canonical)
  std::string program_path;       //!< the G-code file written ("" when none)
  std::string dialect;            //!< G-code dialect of that file, e.g. "linuxcnc"
  //! Learning along the path carried from part to part (learning/path_correction.hpp), one entry per
  //! plan sample, or empty: the correction before the look-ahead, and the latest measurement at each
  //! sample as {t_m mm, L mm, force N, tooth-period window mm} (force 0: nothing measured there).
  std::vector<double> path_place_correction;
  std::vector<std::array<double, 4>> path_measurements;  //!< see path_place_correction
  //! Per plan sample, the thickest chip measured at or under the target and the thinnest over it with their
  //! forces, {t_m mm, F N, t_m mm, F N} (t_m 0: none); empty when the report has none.
  std::vector<std::array<double, 4>> path_brackets;
  //! The newest model version learned from this program's logs (0: none recorded): the next learning step
  //! builds on it, while the program itself keeps being planned with `model_id` and the corrections.
  long long path_learned_model_id = 0;
  int path_learned_model_version = 0;  //!< see path_learned_model_id
  //! The parts learned from so far, oldest first (path_history.hpp); empty when the report has none.
  std::vector<PathHistoryCycle> path_history;
};

//! The plan report as JSON text (the format at the top of this file), indented by 2, ending in a
//! newline. Deterministic: the same inputs give the same text.
std::string plan_report_json(const PlanResult& result, const PlanSettings& settings, const PlanReportContext& context);

//! One CSV row per sample of `result` under the header row (the columns at the top of this file).
std::string plan_samples_csv(const PlanResult& result);

//! Writes plan_report_json(...) to `path` atomically. Returns "" on success, otherwise a message naming
//! the path and the reason; the target is then left as it was.
std::string write_plan_report(const std::filesystem::path& path, const PlanResult& result,
                              const PlanSettings& settings, const PlanReportContext& context);

//! Writes plan_samples_csv(result) to `path` atomically. Returns "" or a message, as write_plan_report.
std::string write_plan_samples_csv(const std::filesystem::path& path, const PlanResult& result);

//! A plan report read back: everything needed to re-plan the same cycle and to compare with the plan.
struct PlanReport {
  int format_version = kPlanReportFormatVersion;  //!< the file's format_version
  PlanStatus status = PlanStatus::kOk;            //!< the plan's status
  std::vector<std::string> messages;              //!< the plan's messages
  PlanReportContext context;                      //!< spec, cycle, tool, material, model identity, files
  PlanSettings settings;                          //!< model, target, spindle speed, machine, options (with ds_mm)
  PlanSummary summary;                            //!< the predicted totals (null numbers read as NaN)
  int program_blocks = 0;                         //!< program.blocks: blocks in the program written
  std::vector<PlannedBlock> blocks;               //!< the feed schedule, in program order
};

//! Parses plan report JSON text. `source_name` (usually the file name) names the document in messages.
//! Checks every field and throws one InputError listing every problem, each naming the field's path and
//! the value found ("blocks[3].feed_mm_per_min = 'fast': must be a finite number", "model.chip_scale_mm
//! is missing"): text that is not JSON, a "format" other than "feedplan-plan", a format_version newer than
//! kPlanReportFormatVersion (or < 1), missing members, wrong types, null or out-of-range numbers, an
//! unknown status or mode, blocks whose samples are out of order, and settings that validate() rejects.
PlanReport parse_plan_report(std::string_view json_text, const std::string& source_name = "plan report");

//! Reads and parses the plan report at `path` (parse_plan_report). Throws InputError naming the path when
//! the file cannot be read, and as parse_plan_report otherwise.
PlanReport read_plan_report(const std::filesystem::path& path);

}  // namespace feedplan::planner
