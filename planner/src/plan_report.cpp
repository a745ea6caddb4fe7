#include "feedplan/planner/plan_report.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>

#include <nlohmann/json.hpp>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::planner {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kFormatTag = "feedplan-plan";
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

Json model_json(const model::ResponseSurfaceModel& model, const PlanReportContext& context) {
  Json beta = Json::array();
  for (const double b : model.beta) beta.push_back(json_number(b));
  return Json{{"id", context.model_id},
              {"version", context.model_version},
              {"database", context.database_path},
              {"tool", context.model_tool},
              {"material", context.model_material},
              {"match", context.model_match},
              {"beta", std::move(beta)},
              {"chip_center_mm", json_number(model.chip_center_mm)},
              {"chip_scale_mm", json_number(model.chip_scale_mm)},
              {"contact_length_center_mm", json_number(model.contact_length_center_mm)},
              {"contact_length_scale_mm", json_number(model.contact_length_scale_mm)},
              {"range",
               {{"chip_min_mm", json_number(model.range.chip_min_mm)},
                {"chip_max_mm", json_number(model.range.chip_max_mm)},
                {"contact_length_min_mm", json_number(model.range.contact_length_min_mm)},
                {"contact_length_max_mm", json_number(model.range.contact_length_max_mm)}}},
              {"axial_depth_mm", json_number(model.axial_depth_mm)},
              {"spindle_rpm", json_number(model.spindle_rpm)},
              {"quantity", model.quantity}};
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

// A short text of a JSON value for messages.
std::string shown(const Json& value) {
  constexpr std::size_t kLongest = 40;
  std::string text = value.dump();
  if (text.size() > kLongest) text = text.substr(0, kLongest) + "…";
  return text;
}

// A place in the document being read. Every accessor records a problem naming the member's path and the
// value found and returns a neutral value, so that one pass reports everything. A node whose own value
// is absent (already reported) yields neutral values silently for its members.
class Node {
 public:
  Node(const Json* value, std::string path, std::vector<InputProblem>& problems)
      : value_(value), path_(std::move(path)), problems_(&problems) {}

  //! The member `key`, which must be an object.
  Node object(const std::string& key) const { return typed(key, &Json::is_object, "must be an object"); }

  //! The member `key`, which must be an array.
  Node array(const std::string& key) const { return typed(key, &Json::is_array, "must be an array"); }

  //! Elements of this array node (0 when it is absent).
  std::size_t size() const { return value_ != nullptr ? value_->size() : 0; }

  //! Element `index` of this array node, which must be an object.
  Node item(std::size_t index) const {
    const std::string path = path_ + "[" + std::to_string(index) + "]";
    const Json& value = (*value_)[index];
    if (!value.is_object()) {
      report(path, "= " + shown(value) + ": must be an object");
      return Node(nullptr, path, *problems_);
    }
    return Node(&value, path, *problems_);
  }

  //! A finite number.
  double number(const std::string& key) const {
    const Json* value = member(key);
    if (value == nullptr) return 0.0;
    if (value->is_number() && std::isfinite(value->get<double>())) return value->get<double>();
    report(child_path(key), "= " + shown(*value) + ": must be a finite number");
    return 0.0;
  }

  //! A finite number ≥ `min`.
  double number_at_least(const std::string& key, double min) const {
    const double value = number(key);
    if (value < min) report(child_path(key), "= " + shortest_number_text(value) + ": must be ≥ " + shortest_number_text(min));
    return value;
  }

  //! A number, or null for a value the writer could not express (NaN).
  double number_or_null(const std::string& key) const {
    const Json* value = member(key);
    if (value == nullptr || value->is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (value->is_number()) return value->get<double>();
    report(child_path(key), "= " + shown(*value) + ": must be a number or null");
    return std::numeric_limits<double>::quiet_NaN();
  }

  //! An integer in [min, max].
  std::int64_t integer(const std::string& key, std::int64_t min, std::int64_t max) const {
    const Json* value = member(key);
    if (value == nullptr) return min;
    if (value->is_number_unsigned()) {
      const auto n = value->get<std::uint64_t>();
      if (n <= static_cast<std::uint64_t>(max) && static_cast<std::int64_t>(n) >= min) return static_cast<std::int64_t>(n);
    } else if (value->is_number_integer()) {
      const auto n = value->get<std::int64_t>();
      if (n >= min && n <= max) return n;
    }
    report(child_path(key), "= " + shown(*value) + ": must be an integer in [" + std::to_string(min) + ", " +
                                std::to_string(max) + "]");
    return min;
  }

  //! An int ≥ `min`.
  int count(const std::string& key, int min = 0) const {
    return static_cast<int>(integer(key, min, std::numeric_limits<int>::max()));
  }

  //! A string; nothing when it is missing or not a string (reported).
  std::optional<std::string> text_if_valid(const std::string& key) const {
    const Json* value = member(key);
    if (value == nullptr) return std::nullopt;
    if (value->is_string()) return value->get<std::string>();
    report(child_path(key), "= " + shown(*value) + ": must be a string");
    return std::nullopt;
  }

  //! A string ("" when it is missing or not a string, reported).
  std::string text(const std::string& key) const { return text_if_valid(key).value_or(""); }

  //! An array of strings.
  std::vector<std::string> texts(const std::string& key) const {
    const Node list = array(key);
    std::vector<std::string> values;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Json& value = (*list.value_)[i];
      if (value.is_string()) {
        values.push_back(value.get<std::string>());
      } else {
        report(list.path_ + "[" + std::to_string(i) + "]", "= " + shown(value) + ": must be a string");
      }
    }
    return values;
  }

  //! An array of exactly N finite numbers.
  //! An optional array of finite numbers: empty when the member is absent.
  std::vector<double> optional_numbers(const std::string& key) const {
    std::vector<double> values;
    if (value_ == nullptr || value_->find(key) == value_->end()) return values;
    const Node list = array(key);
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Json& value = (*list.value_)[i];
      if (value.is_number() && std::isfinite(value.get<double>())) {
        values.push_back(value.get<double>());
      } else {
        report(list.path_ + "[" + std::to_string(i) + "]", "= " + shown(value) + ": must be a finite number");
      }
    }
    return values;
  }

  template <std::size_t N>
  std::array<double, N> numbers(const std::string& key) const {
    const Node list = array(key);
    std::array<double, N> values{};
    if (list.value_ != nullptr && list.size() != N) {
      report(list.path_, "has " + std::to_string(list.size()) + " elements: must have " + std::to_string(N));
    }
    for (std::size_t i = 0; i < N && i < list.size(); ++i) {
      const Json& value = (*list.value_)[i];
      if (value.is_number() && std::isfinite(value.get<double>())) {
        values[i] = value.get<double>();
      } else {
        report(list.path_ + "[" + std::to_string(i) + "]", "= " + shown(value) + ": must be a finite number");
      }
    }
    return values;
  }

  //! An array of arrays of exactly N finite numbers each.
  template <std::size_t N>
  std::vector<std::array<double, N>> number_rows(const std::string& key) const {
    const Node list = array(key);
    std::vector<std::array<double, N>> rows;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Json& row = (*list.value_)[i];
      const std::string path = list.path_ + "[" + std::to_string(i) + "]";
      std::array<double, N> values{};
      if (!row.is_array() || row.size() != N) {
        report(path, "= " + shown(row) + ": must be an array of " + std::to_string(N) + " numbers");
      } else {
        for (std::size_t j = 0; j < N; ++j) {
          if (row[j].is_number() && std::isfinite(row[j].get<double>())) {
            values[j] = row[j].get<double>();
          } else {
            report(path + "[" + std::to_string(j) + "]", "= " + shown(row[j]) + ": must be a finite number");
          }
        }
      }
      rows.push_back(values);
    }
    return rows;
  }

  //! True when member `key` is there (absence is not a problem).
  bool has(const std::string& key) const { return value_ != nullptr && value_->find(key) != value_->end(); }

  //! The path of member `key`, for problems found by the caller.
  std::string child_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  //! Records a problem.
  void report(std::string field, std::string message) const {
    problems_->push_back({std::move(field), std::move(message)});
  }

 private:
  // The member `key`, or nullptr: reported as missing unless this node itself is absent.
  const Json* member(const std::string& key) const {
    if (value_ == nullptr) return nullptr;
    const auto found = value_->find(key);
    if (found != value_->end()) return &*found;
    report(child_path(key), "is missing");
    return nullptr;
  }

  Node typed(const std::string& key, bool (Json::*is_kind)() const noexcept, const char* expected) const {
    const Json* value = member(key);
    if (value != nullptr && !(value->*is_kind)()) {
      report(child_path(key), "= " + shown(*value) + ": " + expected);
      value = nullptr;
    }
    return Node(value, child_path(key), *problems_);
  }

  const Json* value_;
  std::string path_;
  std::vector<InputProblem>* problems_;
};

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

model::ResponseSurfaceModel read_model(const Node& node) {
  model::ResponseSurfaceModel model;
  model.beta = node.numbers<6>("beta");
  model.chip_center_mm = node.number("chip_center_mm");
  model.chip_scale_mm = node.number("chip_scale_mm");
  model.contact_length_center_mm = node.number("contact_length_center_mm");
  model.contact_length_scale_mm = node.number("contact_length_scale_mm");
  const Node range = node.object("range");
  model.range.chip_min_mm = range.number("chip_min_mm");
  model.range.chip_max_mm = range.number("chip_max_mm");
  model.range.contact_length_min_mm = range.number("contact_length_min_mm");
  model.range.contact_length_max_mm = range.number("contact_length_max_mm");
  model.axial_depth_mm = node.number("axial_depth_mm");
  model.spindle_rpm = node.number("spindle_rpm");
  model.quantity = node.text("quantity");
  return model;
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
  root["material"] = context.material;
  root["model"] = model_json(settings.model, context);
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
                         {"ds_mm", json_number(options.ds_mm)}};
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
  Json document;
  try {
    document = Json::parse(json_text.begin(), json_text.end());
  } catch (const Json::parse_error& error) {
    throw InputError(source_name, std::string("is not valid JSON: ") + error.what());
  }
  std::vector<InputProblem> problems;
  const auto fail_if_any = [&problems]() {
    if (!problems.empty()) throw InputError(std::move(problems));
  };
  if (!document.is_object()) {
    throw InputError(source_name, "= " + shown(document) + ": is not a feedplan plan report (expected a JSON object)");
  }
  const Node root(&document, "", problems);

  // The format first: another document's fields would only give confusing problems.
  const std::string format = root.text("format");
  fail_if_any();
  if (format != kFormatTag) {
    throw InputError("format", "= '" + format + "': must be '" + kFormatTag + "' (" + source_name +
                                   " is not a feedplan plan report)");
  }
  PlanReport report;
  report.format_version = static_cast<int>(root.integer("format_version", 1, std::numeric_limits<int>::max()));
  fail_if_any();
  if (report.format_version > kPlanReportFormatVersion) {
    throw InputError("format_version", "= " + std::to_string(report.format_version) + ": " + source_name +
                                           " was written by a newer feedplan (this one reads up to " +
                                           std::to_string(kPlanReportFormatVersion) + ")");
  }

  report.status = enum_from_text(root, "status",
                                 std::array{PlanStatus::kOk, PlanStatus::kExtrapolated, PlanStatus::kTargetNotMet},
                                 PlanStatus::kOk);
  report.messages = root.texts("messages");

  PlanReportContext& context = report.context;
  context.spec_path = root.text("spec");
  context.cycle = root.text("cycle");
  const Node tool = root.object("tool");
  context.tool.name = tool.text("name");
  context.tool.diameter_mm = tool.number("diameter_mm");
  context.tool.flutes = tool.count("flutes", 1);
  context.tool.helix_deg = tool.number("helix_deg");
  context.material = root.text("material");

  const Node model = root.object("model");
  context.model_id = model.integer("id", 0, std::numeric_limits<std::int64_t>::max());
  context.model_version = model.count("version");
  context.database_path = model.text("database");
  context.model_tool = model.text("tool");
  context.model_material = model.text("material");
  context.model_match = model.text("match");

  PlanSettings& settings = report.settings;
  settings.model = read_model(model);
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
  settings.force_correction = root.optional_numbers("force_correction");
  if (root.has("path_learning")) {
    const Node learning = root.object("path_learning");
    context.path_place_correction = learning.optional_numbers("place_correction");
    context.path_measurements = learning.number_rows<4>("measurements");
    const std::size_t n = settings.force_correction.size();
    if (context.path_place_correction.size() != n) {
      learning.report("path_learning.place_correction", "has " + std::to_string(context.path_place_correction.size()) +
                                                            " values: must have " + std::to_string(n) +
                                                            ", one per plan sample as force_correction");
    }
    if (context.path_measurements.size() != n) {
      learning.report("path_learning.measurements", "has " + std::to_string(context.path_measurements.size()) +
                                                        " rows: must have " + std::to_string(n) +
                                                        ", one per plan sample as force_correction");
    }
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
  }

  report.summary = read_summary(root.object("summary"));
  const Node program = root.object("program");
  context.program_path = program.text("path");
  context.dialect = program.text("dialect");
  report.program_blocks = program.count("blocks");
  report.blocks = read_blocks(root.array("blocks"));
  fail_if_any();

  // Well-formed numbers may still be out of range: the planner's own checks name the same paths.
  std::vector<InputProblem> settings_problems = validate(settings, context.tool);
  if (!settings_problems.empty()) throw InputError(std::move(settings_problems));
  return report;
}

PlanReport read_plan_report(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path.string(), "cannot be read: no such file (expected a plan report, JSON)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot be read");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(path.string(), "cannot be read (read error)");
  return parse_plan_report(text, path.string());
}

}  // namespace feedplan::planner
