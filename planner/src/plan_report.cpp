#include "feedplan/planner/plan_report.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>

#include <nlohmann/json.hpp>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/json_document.hpp"
#include "feedplan/core/json_fields.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/model/mechanistic_json.hpp"
#include "feedplan/model/model_json.hpp"

namespace feedplan::planner {
namespace {

using Json = nlohmann::ordered_json;
using Reader = JsonFieldReader<Json>;  // the plan report's rules are JsonFieldRules' defaults
using Node = JsonNode<Json>;

constexpr const char* kFormatTag = "feedplan-plan";
// The largest report read_plan_report reads: JSON parsed whole takes about ten times its size.
constexpr std::size_t kMaxPlanReportFileBytes = std::size_t{256} << 20;
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// --- Writing --------------------------------------------------------------------------------------

// JSON has no NaN or infinity: such a number becomes null (plan_report.hpp says where the reader allows it).
Json json_number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

Json block_json(const PlannedBlock& block) {
  return Json{{"move_index", block.move_index},
              {"first_sample", block.first_sample},
              {"last_sample", block.last_sample},
              {"feed_mm_per_min", json_number(block.feed_mm_per_min)},
              {"length_mm", json_number(block.length_mm)},
              {"min_limit_mm_per_min", json_number(block.min_limit_mm_per_min)},
              {"duration_s", json_number(block.duration_s)}};
}

Json summary_json(const PlanSummary& summary) {
  const ConstantFeedBaseline& baseline = summary.baseline;
  return Json{{"cycle_time_s", json_number(summary.cycle_time_s)},
              {"cutting_time_s", json_number(summary.cutting_time_s)},
              {"air_time_s", json_number(summary.air_time_s)},
              {"max_predicted_force_n", json_number(summary.max_predicted_force_n)},
              {"min_feed_mm_per_min", json_number(summary.min_feed_mm_per_min)},
              {"max_feed_mm_per_min", json_number(summary.max_feed_mm_per_min)},
              {"baseline",
               {{"feed_mm_per_min", json_number(baseline.feed_mm_per_min)},
                {"peak_force_n", json_number(baseline.peak_force_n)},
                {"cycle_time_s", json_number(baseline.cycle_time_s)},
                {"cutting_time_s", json_number(baseline.cutting_time_s)}}},
              {"time_saved_percent", json_number(summary.time_saved_percent)},
              {"engaged_samples", summary.engaged_samples},
              {"force_limited_samples", summary.force_limited_samples},
              {"extrapolated_samples", summary.extrapolated_samples},
              {"over_target_samples", summary.over_target_samples},
              {"short_blocks", summary.short_blocks},
              {"accel_used_mm_per_s2", json_number(summary.accel_used_mm_per_s2)}};
}

// The model's identity (the plan's context), then its members as model_json.hpp writes them.
Json model_json(const PlanSettings& settings, const PlanReportContext& context) {
  const model::ResponseSurfaceModel& model = settings.model;
  Json json{{"id", context.model_id},
            {"version", context.model_version},
            {"database", context.database_path},
            {"tool", context.model_tool},
            {"material", context.model_material},
            {"match", context.model_match},
            {"match_status", context.model_match_status},
            {"differences", context.model_differences},
            {"relative_uncertainty", json_number(context.model_relative_uncertainty)}};
  json.update(model::to_json(model));
  json["kind"] = settings.mechanistic ? "mechanistic" : "response_surface";
  if (!context.model_kind_reason.empty()) json["kind_reason"] = context.model_kind_reason;
  if (settings.mechanistic) json["mechanistic"] = model::to_json(*settings.mechanistic);
  return json;
}

// --- CSV numbers ----------------------------------------------------------------------------------

// Appends `value` with `decimals` decimals, trailing zeros (and a bare point) dropped, "-0" as "0";
// non-finite as nan, inf, -inf.
void append_decimal(std::string& out, double value, int decimals) {
  if (!std::isfinite(value)) {
    out += std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
    return;
  }
  std::array<char, 48> buffer{};
  const auto written =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, decimals);
  const char* begin = buffer.data();
  const char* end = written.ptr;
  if (written.ec != std::errc()) {  // beyond 1e40: no plan produces it, keep it readable anyway
    out += shortest_number_text(value);
    return;
  }
  if (decimals > 0) {
    while (end[-1] == '0') --end;
    if (end[-1] == '.') --end;
  }
  if (end - begin == 2 && begin[0] == '-' && begin[1] == '0') ++begin;
  out.append(begin, end);
}

// --- Reading --------------------------------------------------------------------------------------

// The enum value whose to_string is `text`; `fallback` and a problem when none is.
template <typename Enum, std::size_t N>
Enum enum_from_text(const Node& node, const std::string& key, const std::array<Enum, N>& values, Enum fallback) {
  const std::optional<std::string> text = node.text_if_valid(key);
  if (!text) return fallback;
  std::string allowed;
  for (const Enum value : values) {
    if (to_string(value) == *text) return value;
    allowed += (allowed.empty() ? "'" : ", '") + to_string(value) + "'";
  }
  node.report(node.child_path(key), "= '" + *text + "': must be one of " + allowed);
  return fallback;
}

PlanSummary read_summary(const Node& node) {
  PlanSummary summary;
  summary.cycle_time_s = node.number_or_null("cycle_time_s");
  summary.cutting_time_s = node.number_or_null("cutting_time_s");
  summary.air_time_s = node.number_or_null("air_time_s");
  summary.max_predicted_force_n = node.number_or_null("max_predicted_force_n");
  summary.min_feed_mm_per_min = node.number_or_null("min_feed_mm_per_min");
  summary.max_feed_mm_per_min = node.number_or_null("max_feed_mm_per_min");
  const Node baseline = node.object("baseline");
  summary.baseline.feed_mm_per_min = baseline.number_or_null("feed_mm_per_min");
  summary.baseline.peak_force_n = baseline.number_or_null("peak_force_n");
  summary.baseline.cycle_time_s = baseline.number_or_null("cycle_time_s");
  summary.baseline.cutting_time_s = baseline.number_or_null("cutting_time_s");
  summary.time_saved_percent = node.number_or_null("time_saved_percent");
  summary.engaged_samples = node.count("engaged_samples");
  summary.force_limited_samples = node.count("force_limited_samples");
  summary.extrapolated_samples = node.count("extrapolated_samples");
  summary.over_target_samples = node.count("over_target_samples");
  summary.short_blocks = node.count("short_blocks");
  summary.accel_used_mm_per_s2 = node.number_or_null("accel_used_mm_per_s2");
  return summary;
}

std::vector<PlannedBlock> read_blocks(const Node& list) {
  std::vector<PlannedBlock> blocks;
  for (std::size_t b = 0; b < list.size(); ++b) {
    const Node node = list.item(b);
    PlannedBlock block;
    block.move_index = node.count("move_index");
    block.first_sample = node.count("first_sample");
    block.last_sample = node.count("last_sample");
    block.feed_mm_per_min = node.number_at_least("feed_mm_per_min", 0.0);
    block.length_mm = node.number_at_least("length_mm", 0.0);
    block.min_limit_mm_per_min = node.number_or_null("min_limit_mm_per_min");
    block.duration_s = node.number_at_least("duration_s", 0.0);
    if (block.last_sample < block.first_sample) {
      node.report(node.child_path("last_sample"), "= " + std::to_string(block.last_sample) +
                                                      ": must be ≥ first_sample (" +
                                                      std::to_string(block.first_sample) + ")");
    }
    if (!blocks.empty()) {
      const PlannedBlock& previous = blocks.back();
      const std::string before = "blocks[" + std::to_string(b - 1) + "]";
      if (block.first_sample < previous.last_sample) {
        node.report(node.child_path("first_sample"), "= " + std::to_string(block.first_sample) + ": must be ≥ " +
                                                         before + ".last_sample (" +
                                                         std::to_string(previous.last_sample) + ")");
      }
      if (block.move_index < previous.move_index) {
        node.report(node.child_path("move_index"), "= " + std::to_string(block.move_index) + ": must be ≥ " +
                                                       before + ".move_index (" +
                                                       std::to_string(previous.move_index) + ")");
      }
    }
    blocks.push_back(block);
  }
  return blocks;
}

// The steps of parse_plan_report, in its order.

// The JSON text parsed; text that is not JSON, nests too deep or is not an object throws.
Json parse_report_text(std::string_view json_text, const std::string& source_name) {
  const Json document = parse_json_document<Json>(json_text, source_name);
  if (!document.is_object()) {
    throw InputError(source_name, "= " + json_value_text(document, JsonTextShown::kAsJson) +
                                      ": is not a feedplan plan report (expected a JSON object)");
  }
  return document;
}

// The format first: another document's fields would only give confusing problems. Throws unless the
// document is a plan report of a format_version this code reads; returns that version.
int read_format_version(Reader& reader, const Node& root, const std::string& source_name) {
  const std::string format = root.text("format");
  reader.throw_if_any();
  if (format != kFormatTag) {
    throw InputError("format", "= '" + format + "': must be '" + kFormatTag + "' (" + source_name +
                                   " is not a feedplan plan report)");
  }
  const int format_version = static_cast<int>(root.integer_in("format_version", 1, std::numeric_limits<int>::max()));
  reader.throw_if_any();
  if (format_version > kPlanReportFormatVersion) {
    throw InputError("format_version", "= " + std::to_string(format_version) + ": " + source_name +
                                           " was written by a newer feedplan (this one reads up to " +
                                           std::to_string(kPlanReportFormatVersion) + ")");
  }
  return format_version;
}

// The plan's spec, cycle, tool and material.
void read_origin(const Node& root, PlanReportContext& context) {
  context.spec_path = root.text("spec");
  context.cycle = root.text("cycle");
  const Node tool = root.object("tool");
  context.tool.name = tool.text("name");
  context.tool.diameter_mm = tool.number("diameter_mm");
  context.tool.flutes = tool.count("flutes", 1);
  context.tool.helix_deg = tool.number("helix_deg");
  // Written only for a tool with its own plunge feed (absent: 0, the default); when present, in (0, D].
  if (const auto* given = tool.member("max_plunge_feed_per_tooth_mm", JsonPresence::kOptional)) {
    const double plunge_mm = tool.number("max_plunge_feed_per_tooth_mm");  // reports a value that is not a number
    const double diameter_mm = context.tool.diameter_mm;
    if (given->is_number() && !(plunge_mm > 0.0 && plunge_mm <= diameter_mm)) {
      tool.report(tool.child_path("max_plunge_feed_per_tooth_mm"),
                  "= " + shortest_number_text(plunge_mm) + ": must be in (0, " + shortest_number_text(diameter_mm) +
                      "] mm (a feed per tooth at most the tool diameter)");
    }
    context.tool.max_plunge_feed_per_tooth_mm = plunge_mm;
  }
  context.material = root.text("material");
}

// Which stored model the plan used: the members of "model" besides the model's own.
void read_model_identity(const Node& model, PlanReportContext& context) {
  context.model_id = model.integer_in("id", 0, std::numeric_limits<std::int64_t>::max());
  context.model_version = model.count("version");
  context.database_path = model.text("database");
  context.model_tool = model.text("tool");
  context.model_material = model.text("material");
  context.model_match = model.text("match");
  context.model_match_status = model.text("match_status", JsonPresence::kOptional);
  context.model_differences = model.texts("differences", JsonPresence::kOptional);
  if (model.member("relative_uncertainty", JsonPresence::kOptional)) {
    context.model_relative_uncertainty = model.number("relative_uncertainty");
  }
  context.model_kind_reason = model.text("kind_reason", JsonPresence::kOptional);
}

// The model, target, spindle speed, machine limits, options and force correction.
void read_settings(const Node& root, const Node& model, PlanSettings& settings) {
  settings.model = model::read_model_json(model);
  // Reports written before the mechanistic kind: the response surface.
  const std::string kind = model.member("kind", JsonPresence::kOptional) ? model.text("kind") : "response_surface";
  if (kind == "mechanistic") {
    settings.mechanistic = model::read_mechanistic_json(model.object("mechanistic"));
  } else if (kind != "response_surface") {
    model.report(model.child_path("kind"), "= '" + kind + "': must be response_surface or mechanistic");
  }
  settings.target_force_n = root.number("target_force_n");
  settings.spindle_rpm = root.number("spindle_rpm");
  const Node machine = root.object("machine");
  settings.machine.max_feed_mm_per_min = machine.number("max_feed_mm_per_min");
  settings.machine.min_feed_mm_per_min = machine.number("min_feed_mm_per_min");
  settings.machine.max_accel_mm_per_s2 = machine.number("max_accel_mm_per_s2");
  settings.machine.rapid_feed_mm_per_min = machine.number("rapid_feed_mm_per_min");
  settings.machine.block_time_min_s = machine.number("block_time_min_s");
  const Node options = root.object("options");
  settings.options.mode = enum_from_text(options, "mode", std::array{PlanMode::kSafe, PlanMode::kRegulate},
                                         PlanMode::kSafe);
  settings.options.air_feed_mm_per_min = options.number("air_feed_mm_per_min");
  settings.options.merge_tolerance = options.number("merge_tolerance");
  settings.options.feed_resolution_mm_per_min = options.number("feed_resolution_mm_per_min");
  settings.options.jerk_limit_mm_per_s3 = options.number("jerk_limit_mm_per_s3");
  settings.options.ds_mm = options.number("ds_mm");
  // Reports written before the fields: the planner's defaults (3 decimals; blocks from the command profile).
  if (options.member("feed_step", JsonPresence::kOptional)) settings.options.feed_step = options.number("feed_step");
  if (options.member("min_block_duration_s", JsonPresence::kOptional)) {
    settings.options.min_block_duration_s = options.number("min_block_duration_s");
  }
  if (options.member("coordinate_resolution_mm", JsonPresence::kOptional)) {
    settings.options.coordinate_resolution_mm = options.number("coordinate_resolution_mm");
  }
  if (options.member("max_chip_thickness_mm", JsonPresence::kOptional)) {
    settings.options.max_chip_thickness_mm = options.number("max_chip_thickness_mm");
  }
  settings.force_correction = root.numbers("force_correction", JsonPresence::kOptional);
}

// One entry of path_learning per plan sample, as force_correction has (`samples`).
void check_path_learning_lengths(const Node& learning, const PlanReportContext& context, std::size_t samples) {
  if (context.path_place_correction.size() != samples) {
    learning.report("path_learning.place_correction", "has " + std::to_string(context.path_place_correction.size()) +
                                                          " values: must have " + std::to_string(samples) +
                                                          ", one per plan sample as force_correction");
  }
  if (context.path_measurements.size() != samples) {
    learning.report("path_learning.measurements", "has " + std::to_string(context.path_measurements.size()) +
                                                      " rows: must have " + std::to_string(samples) +
                                                      ", one per plan sample as force_correction");
  }
  if (!context.path_brackets.empty() && context.path_brackets.size() != samples) {
    learning.report("path_learning.brackets", "has " + std::to_string(context.path_brackets.size()) +
                                                  " rows: must have " + std::to_string(samples) +
                                                  ", one per plan sample as force_correction");
  }
}

// Corrections within the learning's bounds, measurements not negative.
void check_path_learning_values(const Node& learning, const PlanReportContext& context) {
  for (std::size_t i = 0; i < context.path_place_correction.size(); ++i) {
    const double c = context.path_place_correction[i];
    if (!(c >= kMinForceCorrection && c <= kMaxForceCorrection)) {
      learning.report("path_learning.place_correction[" + std::to_string(i) + "]",
                      "= " + shortest_number_text(c) + ": must be in [" + shortest_number_text(kMinForceCorrection) +
                          ", " + shortest_number_text(kMaxForceCorrection) + "]");
    }
  }
  for (std::size_t i = 0; i < context.path_measurements.size(); ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      if (context.path_measurements[i][j] < 0.0) {
        learning.report("path_learning.measurements[" + std::to_string(i) + "][" + std::to_string(j) + "]",
                        "= " + shortest_number_text(context.path_measurements[i][j]) + ": must be ≥ 0");
      }
    }
  }
  for (std::size_t i = 0; i < context.path_brackets.size(); ++i) {
    for (std::size_t j = 0; j < 4; ++j) {
      if (context.path_brackets[i][j] < 0.0) {
        learning.report("path_learning.brackets[" + std::to_string(i) + "][" + std::to_string(j) + "]",
                        "= " + shortest_number_text(context.path_brackets[i][j]) + ": must be ≥ 0");
      }
    }
  }
}

// path_learning.history: cycles numbered upwards from 1, a cycle time ≥ 0, and per array one value ≥ 0 per
// plan sample (`samples`).
std::vector<PathHistoryCycle> read_path_history(const Node& learning, std::size_t samples) {
  std::vector<PathHistoryCycle> history;
  const Node list = learning.array("history");
  for (std::size_t k = 0; k < list.size(); ++k) {
    const Node item = list.item(k);
    PathHistoryCycle c;
    c.cycle = static_cast<int>(item.integer_in("cycle", 1, 1000000000));
    if (!history.empty() && c.cycle <= history.back().cycle) {
      item.report(item.child_path("cycle"), "= " + std::to_string(c.cycle) + ": must be larger than the cycle before (" +
                                                std::to_string(history.back().cycle) + ")");
    }
    c.cycle_time_s = item.number_at_least("cycle_time_s", 0.0);
    const auto values = [&](const char* key) {
      std::vector<double> v = item.numbers(key);
      if (v.size() != samples) {
        item.report(item.child_path(key), "has " + std::to_string(v.size()) + " values: must have " +
                                              std::to_string(samples) + ", one per plan sample as force_correction");
      }
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (!(v[i] >= 0.0)) {
          item.report(item.child_path(key) + "[" + std::to_string(i) + "]", "= " + shortest_number_text(v[i]) + ": must be ≥ 0");
          break;
        }
      }
      return v;
    };
    c.feed_mm_per_min = values("feed_mm_per_min");
    c.predicted_n = values("predicted_n");
    c.measured_n = values("measured_n");
    history.push_back(std::move(c));
  }
  return history;
}

// Learning along the path, when the report has it (`samples`: the force_correction entries).
void read_path_learning(const Node& root, std::size_t samples, PlanReportContext& context) {
  if (!root.has("path_learning")) return;
  const Node learning = root.object("path_learning");
  context.path_place_correction = learning.numbers("place_correction", JsonPresence::kOptional);
  context.path_measurements = learning.number_rows<4>("measurements");
  if (learning.has("brackets")) context.path_brackets = learning.number_rows<4>("brackets");
  if (learning.has("learned_model")) {
    const Node learned = learning.object("learned_model");
    const double id = learned.number("id");
    const double version = learned.number("version");
    const auto whole = [](double v) { return v >= 1.0 && v <= 2e9 && v == std::floor(v); };
    if (!whole(id)) learned.report("path_learning.learned_model.id", "= " + shortest_number_text(id) + ": must be a whole number ≥ 1");
    if (!whole(version)) {
      learned.report("path_learning.learned_model.version", "= " + shortest_number_text(version) + ": must be a whole number ≥ 1");
    }
    if (whole(id) && whole(version)) {
      context.path_learned_model_id = static_cast<long long>(id);
      context.path_learned_model_version = static_cast<int>(version);
    }
  }
  if (learning.has("history")) context.path_history = read_path_history(learning, samples);
  check_path_learning_lengths(learning, context, samples);
  check_path_learning_values(learning, context);
}

// The program written: its path, dialect and count of blocks.
void read_program(const Node& root, PlanReport& report) {
  const Node program = root.object("program");
  report.context.program_path = program.text("path");
  report.context.dialect = program.text("dialect");
  report.program_blocks = program.count("blocks");
}

// The report's tool within the ranges a cycle spec allows (the plan came from one): a tool of
// diameter 0 would reach learning and the re-plan.
void check_tool(const geometry::Tool& tool, std::vector<InputProblem>& problems) {
  if (!(std::isfinite(tool.diameter_mm) && tool.diameter_mm > 0.0)) {
    problems.push_back({"tool.diameter_mm", "= " + shortest_number_text(tool.diameter_mm) + ": must be finite and > 0 mm"});
  }
  if (tool.flutes < 1 || tool.flutes > 32) {
    problems.push_back({"tool.flutes", "= " + std::to_string(tool.flutes) + ": must be in [1, 32]"});
  }
  if (!(tool.helix_deg >= 0.0 && tool.helix_deg < 60.0)) {
    problems.push_back({"tool.helix_deg", "= " + shortest_number_text(tool.helix_deg) + ": must be in [0, 60) deg"});
  }
}

// Well-formed numbers may still be out of range: the planner's own checks name the same paths.
void check_settings(const PlanReport& report) {
  std::vector<InputProblem> settings_problems = validate(report.settings, report.context.tool);
  std::erase_if(settings_problems, [](const InputProblem& p) { return p.field == "tool.flutes"; });  // check_tool's
  check_tool(report.context.tool, settings_problems);
  if (!settings_problems.empty()) throw InputError(std::move(settings_problems));
}

}  // namespace

namespace {

Json numbers_json(const std::vector<double>& values) {
  Json out = Json::array();
  for (const double v : values) out.push_back(json_number(v));
  return out;
}

// path_learning.history (path_history.hpp).
Json history_json(const std::vector<PathHistoryCycle>& history) {
  Json out = Json::array();
  for (const PathHistoryCycle& c : history) {
    out.push_back(Json{{"cycle", c.cycle},
                       {"cycle_time_s", json_number(c.cycle_time_s)},
                       {"feed_mm_per_min", numbers_json(c.feed_mm_per_min)},
                       {"predicted_n", numbers_json(c.predicted_n)},
                       {"measured_n", numbers_json(c.measured_n)}});
  }
  return out;
}

}  // namespace

std::string plan_report_json(const PlanResult& result, const PlanSettings& settings, const PlanReportContext& context) {
  const geometry::MachineLimits& machine = settings.machine;
  const PlanOptions& options = settings.options;
  Json root{{"format", kFormatTag}, {"format_version", kPlanReportFormatVersion}};
  root["status"] = to_string(result.status);
  root["messages"] = result.messages;
  root["spec"] = context.spec_path;
  root["cycle"] = context.cycle;
  root["tool"] = Json{{"name", context.tool.name},
                      {"diameter_mm", json_number(context.tool.diameter_mm)},
                      {"flutes", context.tool.flutes},
                      {"helix_deg", json_number(context.tool.helix_deg)}};
  if (context.tool.max_plunge_feed_per_tooth_mm != 0.0) {
    root["tool"]["max_plunge_feed_per_tooth_mm"] = json_number(context.tool.max_plunge_feed_per_tooth_mm);
  }
  root["material"] = context.material;
  root["model"] = model_json(settings, context);
  root["target_force_n"] = json_number(settings.target_force_n);
  root["spindle_rpm"] = json_number(settings.spindle_rpm);
  root["machine"] = Json{{"max_feed_mm_per_min", json_number(machine.max_feed_mm_per_min)},
                         {"min_feed_mm_per_min", json_number(machine.min_feed_mm_per_min)},
                         {"max_accel_mm_per_s2", json_number(machine.max_accel_mm_per_s2)},
                         {"rapid_feed_mm_per_min", json_number(machine.rapid_feed_mm_per_min)},
                         {"block_time_min_s", json_number(machine.block_time_min_s)}};
  root["options"] = Json{{"mode", to_string(options.mode)},
                         {"air_feed_mm_per_min", json_number(options.air_feed_mm_per_min)},
                         {"merge_tolerance", json_number(options.merge_tolerance)},
                         {"feed_resolution_mm_per_min", json_number(options.feed_resolution_mm_per_min)},
                         {"jerk_limit_mm_per_s3", json_number(options.jerk_limit_mm_per_s3)},
                         {"ds_mm", json_number(options.ds_mm)},
                         {"coordinate_resolution_mm", json_number(options.coordinate_resolution_mm)},
                         {"feed_step", json_number(options.feed_step)},
                         {"min_block_duration_s", json_number(options.min_block_duration_s)}};
  if (options.max_chip_thickness_mm > 0.0) {
    root["options"]["max_chip_thickness_mm"] = json_number(options.max_chip_thickness_mm);
  }
  if (!settings.force_correction.empty()) {
    Json correction = Json::array();
    for (double c : settings.force_correction) correction.push_back(json_number(c));
    root["force_correction"] = std::move(correction);
  }
  if (!context.path_place_correction.empty() || !context.path_measurements.empty()) {
    Json place = Json::array();
    for (double c : context.path_place_correction) place.push_back(json_number(c));
    Json measurements = Json::array();
    for (const auto& m : context.path_measurements) {
      measurements.push_back(Json{json_number(m[0]), json_number(m[1]), json_number(m[2]), json_number(m[3])});
    }
    root["path_learning"] = Json{{"place_correction", std::move(place)}, {"measurements", std::move(measurements)}};
    if (!context.path_brackets.empty()) {
      Json brackets = Json::array();
      for (const auto& b : context.path_brackets) {
        brackets.push_back(Json{json_number(b[0]), json_number(b[1]), json_number(b[2]), json_number(b[3])});
      }
      root["path_learning"]["brackets"] = std::move(brackets);
    }
    if (context.path_learned_model_id > 0) {
      root["path_learning"]["learned_model"] = Json{{"id", context.path_learned_model_id},
                                                    {"version", context.path_learned_model_version}};
    }
    if (!context.path_history.empty()) root["path_learning"]["history"] = history_json(context.path_history);
  }
  root["summary"] = summary_json(result.summary);
  root["program"] = Json{{"path", context.program_path},
                         {"dialect", context.dialect},
                         {"blocks", result.program.blocks.size()}};

  // "blocks" comes last, one block per line: a long schedule stays readable and diffs line by line.
  std::string text = root.dump(2);
  text.pop_back();  // the closing brace; dump() writes "\n}" at the end of a non-empty object
  text.pop_back();
  text += ",\n  \"blocks\": [";
  for (std::size_t b = 0; b < result.blocks.size(); ++b) {
    text += b == 0 ? "\n    " : ",\n    ";
    text += block_json(result.blocks[b]).dump();
  }
  text += result.blocks.empty() ? "]\n}\n" : "\n  ]\n}\n";
  return text;
}

std::string plan_samples_csv(const PlanResult& result) {
  std::string csv =
      "s_mm,x_mm,y_mm,engagement_deg,chip_thickness_mm,contact_length_mm,feed_mm_per_min,predicted_force_n,time_s,"
      "z_mm,chip_factor,feed_limit_mm_per_min,limit_reason,command_feed_mm_per_min,block_feed_mm_per_min,block,"
      "engaged,extrapolated\n";
  csv.reserve(csv.size() + 160 * result.samples.size());
  for (const PlannedSample& p : result.samples) {
    const auto field = [&csv](double value, int decimals) {
      append_decimal(csv, value, decimals);
      csv += ',';
    };
    field(p.s_mm, 4);
    field(p.position.x_mm, 4);
    field(p.position.y_mm, 4);
    field(p.engagement_rad * kRadToDeg, 4);
    field(p.chip_thickness_mm, 6);
    field(p.contact_length_mm, 4);
    field(p.feed_mm_per_min, 3);
    field(p.predicted_force_n, 3);
    field(p.time_s, 6);
    field(p.position.z_mm, 4);
    field(p.chip_factor, 6);
    field(p.feed_limit_mm_per_min, 3);
    csv += to_string(p.limit_reason);
    csv += ',';
    field(p.command_feed_mm_per_min, 3);
    field(p.block_feed_mm_per_min, 3);
    csv += std::to_string(p.block_index);
    csv += p.engaged ? ",1," : ",0,";
    csv += p.extrapolated ? "1\n" : "0\n";
  }
  return csv;
}

std::string write_plan_report(const std::filesystem::path& path, const PlanResult& result,
                              const PlanSettings& settings, const PlanReportContext& context) {
  return write_file_atomically(path, plan_report_json(result, settings, context));
}

std::string write_plan_samples_csv(const std::filesystem::path& path, const PlanResult& result) {
  return write_file_atomically(path, plan_samples_csv(result));
}

PlanReport parse_plan_report(std::string_view json_text, const std::string& source_name) {
  const Json document = parse_report_text(json_text, source_name);
  Reader reader;
  const Node root = reader.node(document, "");
  PlanReport report;
  report.format_version = read_format_version(reader, root, source_name);
  report.status = enum_from_text(root, "status",
                                 std::array{PlanStatus::kOk, PlanStatus::kExtrapolated, PlanStatus::kTargetNotMet, PlanStatus::kUnsafe},
                                 PlanStatus::kOk);
  report.messages = root.texts("messages");
  read_origin(root, report.context);
  const Node model = root.object("model");
  read_model_identity(model, report.context);
  read_settings(root, model, report.settings);
  read_path_learning(root, report.settings.force_correction.size(), report.context);
  report.summary = read_summary(root.object("summary"));
  read_program(root, report);
  report.blocks = read_blocks(root.array("blocks"));
  reader.throw_if_any();
  check_settings(report);
  return report;
}

PlanReport read_plan_report(const std::filesystem::path& path) {
  const std::string text = read_input_file(
      path, {"a plan report, JSON", kMaxPlanReportFileBytes, "a plan of 100 000 blocks writes about 20 MiB"});
  return parse_plan_report(text, path.string());
}

}  // namespace feedplan::planner
