#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include "catalog_rows.hpp"
#include "cutting_test_rows.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "json_fields.hpp"
#include "learning_rows.hpp"
#include "model_rows.hpp"
#include "store_impl.hpp"
#include "utc_time.hpp"

namespace feedplan::model_db {
namespace {

using detail::JsonFields;
using Json = nlohmann::json;

// ---- the document, read and checked before anything is written ----

struct ModelKey {
  std::string tool;
  std::string material;
  int version = 0;
  auto operator<=>(const ModelKey&) const = default;
};

struct IncomingTool {
  std::string path;
  ToolRecord record;
};

struct IncomingMaterial {
  std::string path;
  MaterialRecord record;
};

struct IncomingModel {
  std::string path;
  ModelRecord record;                 // tool_name / material_name as in the document
  std::optional<int> parent_version;  // in the document
};

struct IncomingTest {
  std::string path;
  StoredCuttingTest stored;
};

struct IncomingEntry {
  std::string path;
  ModelKey before;
  std::optional<ModelKey> after;
  LearningEntry entry;
};

struct Document {
  std::vector<IncomingTool> tools;
  std::vector<IncomingMaterial> materials;
  std::vector<IncomingModel> models;
  std::vector<IncomingTest> tests;
  std::vector<IncomingEntry> entries;
};

//! Moves validate() problems ("models.beta[2]") to their place in the document ("models[3].model.beta[2]").
void add_located(std::vector<InputProblem>& to, std::vector<InputProblem> from, const std::string& table,
                 const std::string& path) {
  for (auto& problem : from) {
    std::string field = problem.field.substr(std::min(problem.field.size(), table.size() + 1));
    if (table == "models" && field.rfind("fit.", 0) != 0) field = "model." + field;
    if (table == "cutting_tests" && field == "tool_name") field = "tool";
    if (table == "cutting_tests" && field == "material_name") field = "material";
    to.push_back({path + "." + field, std::move(problem.message)});
  }
}

void check_time(JsonFields& fields, const std::string& path, const std::string& created_at) {
  if (!detail::is_utc_iso8601(created_at)) {
    fields.add(path + ".created_at", "= '" + created_at + "': must be UTC ISO 8601, e.g. 2024-05-01T12:00:00.000Z");
  }
}

ToolRecord read_tool(JsonFields& fields, const Json& json, const std::string& path) {
  ToolRecord tool;
  tool.name = fields.text(json, path, "name");
  tool.diameter_mm = fields.number(json, path, "diameter_mm");
  tool.flutes = fields.integer(json, path, "flutes");
  tool.helix_deg = fields.number(json, path, "helix_deg");
  tool.tool_material = fields.text(json, path, "tool_material", false);
  tool.coating = fields.text(json, path, "coating", false);
  tool.notes = fields.text(json, path, "notes", false);
  return tool;
}

MaterialRecord read_material(JsonFields& fields, const Json& json, const std::string& path) {
  MaterialRecord material;
  material.name = fields.text(json, path, "name");
  const std::string group = fields.text(json, path, "iso_group");
  if (const auto parsed = parse_iso_group(group)) {
    material.iso_group = *parsed;
  } else if (json.contains("iso_group")) {
    fields.add(path + ".iso_group", "= '" + group + "': must be one of P, M, K, N, S, H");
  }
  material.hardness_value = fields.number(json, path, "hardness_value");
  material.hardness_scale = fields.text(json, path, "hardness_scale");
  material.notes = fields.text(json, path, "notes", false);
  return material;
}

IncomingModel read_model(JsonFields& fields, const Json& json, const std::string& path) {
  IncomingModel incoming{path, {}, std::nullopt};
  ModelRecord& record = incoming.record;
  record.tool_name = fields.text(json, path, "tool");
  record.material_name = fields.text(json, path, "material");
  record.version = fields.integer(json, path, "version");
  if (record.version < 1 && json.contains("version")) {
    fields.add(path + ".version", "= " + std::to_string(record.version) + ": must be ≥ 1");
  }
  incoming.parent_version = fields.optional_integer(json, path, "parent_version");
  record.active = fields.boolean(json, path, "active");
  const std::string source = fields.text(json, path, "source");
  if (const auto parsed = parse_model_source(source)) {
    record.source = *parsed;
  } else if (json.contains("source")) {
    fields.add(path + ".source", "= '" + source + "': must be cutting_tests, learned or imported");
  }
  record.created_at = fields.text(json, path, "created_at");
  check_time(fields, path, record.created_at);
  record.note = fields.text(json, path, "note", false);

  const std::string model_path = path + ".model";
  static const Json kNoObject = Json::object();
  const Json* model_json = fields.member(json, path, "model");
  const Json& m = model_json != nullptr ? *model_json : kNoObject;
  model::ResponseSurfaceModel& model = record.model;
  model.beta = fields.fixed_numbers<6>(m, model_path, "beta");
  model.chip_center_mm = fields.number(m, model_path, "chip_center_mm");
  model.chip_scale_mm = fields.number(m, model_path, "chip_scale_mm");
  model.contact_length_center_mm = fields.number(m, model_path, "contact_length_center_mm");
  model.contact_length_scale_mm = fields.number(m, model_path, "contact_length_scale_mm");
  const std::string range_path = model_path + ".range";
  const Json* range_json = fields.member(m, model_path, "range");
  const Json& r = range_json != nullptr ? *range_json : kNoObject;
  model.range.chip_min_mm = fields.number(r, range_path, "chip_min_mm");
  model.range.chip_max_mm = fields.number(r, range_path, "chip_max_mm");
  model.range.contact_length_min_mm = fields.number(r, range_path, "contact_length_min_mm");
  model.range.contact_length_max_mm = fields.number(r, range_path, "contact_length_max_mm");
  model.axial_depth_mm = fields.number(m, model_path, "axial_depth_mm");
  model.spindle_rpm = fields.number(m, model_path, "spindle_rpm");
  model.quantity = fields.text(m, model_path, "quantity");

  const std::string fit_path = path + ".fit";
  const Json* fit_json = fields.member(json, path, "fit");
  const Json& f = fit_json != nullptr ? *fit_json : kNoObject;
  record.fit.n = fields.integer(f, fit_path, "n");
  record.fit.rmse_n = fields.number(f, fit_path, "rmse_n");
  record.fit.r_squared = fields.number(f, fit_path, "r_squared");
  record.fit.covariance = model::Covariance::from_entries(fields.fixed_numbers<36>(f, fit_path, "covariance"));
  record.fit.standard_errors = fields.fixed_numbers<6>(f, fit_path, "standard_errors");
  record.fit.loo_rmse_n = fields.number(f, fit_path, "loo_rmse_n");
  return incoming;
}

StoredCuttingTest read_test(JsonFields& fields, const Json& json, const std::string& path) {
  StoredCuttingTest stored;
  stored.created_at = fields.text(json, path, "created_at");
  check_time(fields, path, stored.created_at);
  CuttingTestRecord& test = stored.test;
  CuttingTestConditions& conditions = test.conditions;
  conditions.tool_name = fields.text(json, path, "tool");
  conditions.material_name = fields.text(json, path, "material");
  conditions.spindle_rpm = fields.number(json, path, "spindle_rpm");
  conditions.feed_mm_per_min = fields.number(json, path, "feed_mm_per_min");
  conditions.radial_depth_mm = fields.number(json, path, "radial_depth_mm");
  conditions.axial_depth_mm = fields.number(json, path, "axial_depth_mm");
  const std::string mode = fields.text(json, path, "mode");
  if (const auto parsed = detail::parse_cut_mode(mode)) {
    conditions.mode = *parsed;
  } else if (json.contains("mode")) {
    fields.add(path + ".mode", "= '" + mode + "': must be down, up or slot");
  }
  test.feed_per_tooth_mm = fields.number(json, path, "feed_per_tooth_mm");
  test.chip_mm = fields.number(json, path, "chip_mm");
  test.contact_length_mm = fields.number(json, path, "contact_length_mm");
  test.peak_mean_n = fields.number(json, path, "peak_mean_n");
  test.peak_std_n = fields.number(json, path, "peak_std_n");
  test.peak_min_n = fields.number(json, path, "peak_min_n");
  test.peak_max_n = fields.number(json, path, "peak_max_n");
  test.revolutions_total = fields.integer(json, path, "revolutions_total");
  test.revolutions_used = fields.integer(json, path, "revolutions_used");
  test.steady_peaks_n = fields.numbers(json, path, "steady_peaks_n");
  test.source = fields.text(json, path, "source", false);
  test.notes = fields.texts(json, path, "notes");
  return stored;
}

ModelKey read_reference(JsonFields& fields, const Json& json, const std::string& path) {
  return {fields.text(json, path, "tool"), fields.text(json, path, "material"), fields.integer(json, path, "version")};
}

IncomingEntry read_entry(JsonFields& fields, const Json& json, const std::string& path) {
  IncomingEntry incoming;
  incoming.path = path;
  static const Json kNoObject = Json::object();
  const Json* before = fields.member(json, path, "model_before");
  incoming.before = read_reference(fields, before != nullptr ? *before : kNoObject, path + ".model_before");
  const Json* after = fields.member(json, path, "model_after", false);
  if (after != nullptr && !after->is_null()) incoming.after = read_reference(fields, *after, path + ".model_after");
  LearningEntry& entry = incoming.entry;
  entry.part_name = fields.text(json, path, "part_name");
  entry.n_samples = fields.integer(json, path, "n_samples");
  entry.error_before_n = fields.number(json, path, "error_before_n");
  entry.error_after_n = fields.number(json, path, "error_after_n");
  entry.created_at = fields.text(json, path, "created_at");
  check_time(fields, path, entry.created_at);
  entry.note = fields.text(json, path, "note", false);
  return incoming;
}

//! Parses and checks the document on its own (references to names not in it are checked later,
//! against the store). Throws InputError with every problem.
Document read_document(std::string_view text, const std::string& source_name) {
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::parse_error& error) {
    throw InputError(source_name, std::string("is not valid JSON: ") + error.what());
  }
  std::vector<InputProblem> problems;
  JsonFields fields(problems);
  if (!root.is_object() || root.value("format", "") != "feedplan-model-db") {
    throw InputError(source_name, "is not a feedplan model database export (expected \"format\": \"feedplan-model-db\")");
  }
  const int format_version = fields.integer(root, "document", "format_version");
  if (!problems.empty()) throw InputError(std::move(problems));
  if (format_version > kExchangeFormatVersion) {
    throw InputError(source_name, "has format_version " + std::to_string(format_version) +
                                      ", newer than this feedplan reads (" + std::to_string(kExchangeFormatVersion) +
                                      "): upgrade feedplan");
  }
  if (format_version < 1) {
    throw InputError("document.format_version", "= " + std::to_string(format_version) + ": must be ≥ 1");
  }

  Document document;
  std::set<std::string> tool_names;
  const Json& tools = fields.array(root, "document", "tools", false);
  for (std::size_t i = 0; i < tools.size(); ++i) {
    const std::string path = "tools[" + std::to_string(i) + "]";
    IncomingTool tool{path, read_tool(fields, tools[i], path)};
    add_located(problems, validate(tool.record), "tools", path);
    if (!tool_names.insert(tool.record.name).second) {
      fields.add(path + ".name", "= '" + tool.record.name + "': appears twice in the document");
    }
    document.tools.push_back(std::move(tool));
  }
  std::set<std::string> material_names;
  const Json& materials = fields.array(root, "document", "materials", false);
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const std::string path = "materials[" + std::to_string(i) + "]";
    IncomingMaterial material{path, read_material(fields, materials[i], path)};
    add_located(problems, validate(material.record), "materials", path);
    if (!material_names.insert(material.record.name).second) {
      fields.add(path + ".name", "= '" + material.record.name + "': appears twice in the document");
    }
    document.materials.push_back(std::move(material));
  }

  const Json& models = fields.array(root, "document", "models", false);
  std::set<ModelKey> model_keys;
  std::map<std::pair<std::string, std::string>, int> active_per_pair;
  for (std::size_t i = 0; i < models.size(); ++i) {
    const std::string path = "models[" + std::to_string(i) + "]";
    IncomingModel model = read_model(fields, models[i], path);
    add_located(problems, validate(model.record), "models", path);
    const ModelRecord& r = model.record;
    if (!model_keys.insert({r.tool_name, r.material_name, r.version}).second) {
      fields.add(path + ".version", "= " + std::to_string(r.version) + ": " + r.tool_name + " in " + r.material_name +
                                        " has this version twice in the document");
    }
    active_per_pair[{r.tool_name, r.material_name}] += r.active ? 1 : 0;
    document.models.push_back(std::move(model));
  }
  for (const auto& model : document.models) {
    const ModelRecord& r = model.record;
    if (model.parent_version &&
        (*model.parent_version >= r.version || model_keys.count({r.tool_name, r.material_name, *model.parent_version}) == 0)) {
      fields.add(model.path + ".parent_version",
                 "= " + std::to_string(*model.parent_version) + ": must be an earlier version of " + r.tool_name +
                     " in " + r.material_name + " in the document (or null)");
    }
  }
  for (const auto& [pair, count] : active_per_pair) {
    if (count != 1) {
      fields.add("models", pair.first + " in " + pair.second + " has " + std::to_string(count) +
                               " active versions: must have exactly one");
    }
  }

  const Json& tests = fields.array(root, "document", "cutting_tests", false);
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const std::string path = "cutting_tests[" + std::to_string(i) + "]";
    IncomingTest test{path, read_test(fields, tests[i], path)};
    add_located(problems, validate(test.stored.test), "cutting_tests", path);
    document.tests.push_back(std::move(test));
  }
  const Json& entries = fields.array(root, "document", "learning_history", false);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const std::string path = "learning_history[" + std::to_string(i) + "]";
    IncomingEntry entry = read_entry(fields, entries[i], path);
    LearningEntry checked = entry.entry;
    checked.model_id_before = 1;  // references are checked against the models when writing
    add_located(problems, validate(checked), "learning_history", path);
    document.entries.push_back(std::move(entry));
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  return document;
}

// ---- comparing incoming rows with stored ones ----

bool same_content(const ToolRecord& a, const ToolRecord& b) {
  return std::tie(a.name, a.diameter_mm, a.flutes, a.helix_deg, a.tool_material, a.coating, a.notes) ==
         std::tie(b.name, b.diameter_mm, b.flutes, b.helix_deg, b.tool_material, b.coating, b.notes);
}

bool same_content(const MaterialRecord& a, const MaterialRecord& b) {
  return std::tie(a.name, a.iso_group, a.hardness_value, a.hardness_scale, a.notes) ==
         std::tie(b.name, b.iso_group, b.hardness_value, b.hardness_scale, b.notes);
}

bool same_content(const ModelRecord& a, const ModelRecord& b) {
  const auto& x = a.model;
  const auto& y = b.model;
  return std::tie(x.beta, x.chip_center_mm, x.chip_scale_mm, x.contact_length_center_mm, x.contact_length_scale_mm,
                  x.range.chip_min_mm, x.range.chip_max_mm, x.range.contact_length_min_mm,
                  x.range.contact_length_max_mm, x.axial_depth_mm, x.spindle_rpm, x.quantity) ==
             std::tie(y.beta, y.chip_center_mm, y.chip_scale_mm, y.contact_length_center_mm,
                      y.contact_length_scale_mm, y.range.chip_min_mm, y.range.chip_max_mm,
                      y.range.contact_length_min_mm, y.range.contact_length_max_mm, y.axial_depth_mm, y.spindle_rpm,
                      y.quantity) &&
         std::tie(a.fit.n, a.fit.rmse_n, a.fit.r_squared, a.fit.covariance, a.fit.standard_errors, a.fit.loo_rmse_n,
                  a.source, a.created_at, a.note) ==
             std::tie(b.fit.n, b.fit.rmse_n, b.fit.r_squared, b.fit.covariance, b.fit.standard_errors,
                      b.fit.loo_rmse_n, b.source, b.created_at, b.note);
}

bool same_content(const StoredCuttingTest& a, const StoredCuttingTest& b) {
  const auto& s = a.test;
  const auto& t = b.test;
  const auto& c = s.conditions;
  const auto& d = t.conditions;
  return std::tie(a.created_at, c.spindle_rpm, c.feed_mm_per_min, c.radial_depth_mm, c.axial_depth_mm, c.mode) ==
             std::tie(b.created_at, d.spindle_rpm, d.feed_mm_per_min, d.radial_depth_mm, d.axial_depth_mm, d.mode) &&
         std::tie(s.feed_per_tooth_mm, s.chip_mm, s.contact_length_mm, s.peak_mean_n, s.peak_std_n, s.peak_min_n,
                  s.peak_max_n, s.revolutions_total, s.revolutions_used, s.steady_peaks_n, s.source, s.notes) ==
             std::tie(t.feed_per_tooth_mm, t.chip_mm, t.contact_length_mm, t.peak_mean_n, t.peak_std_n, t.peak_min_n,
                      t.peak_max_n, t.revolutions_total, t.revolutions_used, t.steady_peaks_n, t.source, t.notes);
}

bool same_content(const LearningEntry& a, const LearningEntry& b) {
  return std::tie(a.model_id_before, a.model_id_after, a.part_name, a.n_samples, a.error_before_n, a.error_after_n,
                  a.created_at, a.note) == std::tie(b.model_id_before, b.model_id_after, b.part_name, b.n_samples,
                                                    b.error_before_n, b.error_after_n, b.created_at, b.note);
}

//! "diameter_mm: stored 10, incoming 12; notes: stored '', incoming 'x'".
std::string differences(const ToolRecord& stored, const ToolRecord& incoming) {
  std::vector<std::string> parts;
  const auto number = [&](const char* name, double a, double b) {
    if (a != b) parts.push_back(std::string(name) + ": stored " + shortest_number_text(a) + ", incoming " + shortest_number_text(b));
  };
  const auto text = [&](const char* name, const std::string& a, const std::string& b) {
    if (a != b) parts.push_back(std::string(name) + ": stored '" + a + "', incoming '" + b + "'");
  };
  number("diameter_mm", stored.diameter_mm, incoming.diameter_mm);
  number("flutes", stored.flutes, incoming.flutes);
  number("helix_deg", stored.helix_deg, incoming.helix_deg);
  text("tool_material", stored.tool_material, incoming.tool_material);
  text("coating", stored.coating, incoming.coating);
  text("notes", stored.notes, incoming.notes);
  std::string joined;
  for (const auto& part : parts) joined += (joined.empty() ? "" : "; ") + part;
  return joined;
}

std::string differences(const MaterialRecord& stored, const MaterialRecord& incoming) {
  std::vector<std::string> parts;
  if (stored.iso_group != incoming.iso_group) {
    parts.push_back("iso_group: stored " + to_string(stored.iso_group) + ", incoming " + to_string(incoming.iso_group));
  }
  if (stored.hardness_value != incoming.hardness_value || stored.hardness_scale != incoming.hardness_scale) {
    parts.push_back("hardness: stored " + shortest_number_text(stored.hardness_value) + " " + stored.hardness_scale +
                    ", incoming " + shortest_number_text(incoming.hardness_value) + " " + incoming.hardness_scale);
  }
  if (stored.notes != incoming.notes) parts.push_back("notes: stored '" + stored.notes + "', incoming '" + incoming.notes + "'");
  std::string joined;
  for (const auto& part : parts) joined += (joined.empty() ? "" : "; ") + part;
  return joined;
}

// ---- writing, inside one transaction ----

class Importer {
 public:
  Importer(Store::Impl& impl, const ImportOptions& options) : impl_(impl), db_(impl.db), options_(options) {}

  ImportSummary run(const Document& document) {
    detail::WriteTransaction transaction(db_);
    for (const auto& tool : document.tools) import_tool(tool);
    for (const auto& material : document.materials) import_material(material);
    throw_problems();
    import_models(document.models);
    throw_problems();
    for (const auto& test : document.tests) import_test(test);
    throw_problems();
    for (const auto& entry : document.entries) import_entry(entry);
    throw_problems();
    transaction.commit();
    return std::move(summary_);
  }

 private:
  void throw_problems() {
    if (!problems_.empty()) throw InputError(std::move(problems_));
  }

  void row_written(const char* step) { impl_.after_step(step); }

  template <typename Record, typename Select>
  std::string free_name(const std::string& name, Select select, const Record& incoming, bool& identical_found) {
    for (int n = 1;; ++n) {
      const std::string candidate = name + (n == 1 ? " (imported)" : " (imported " + std::to_string(n) + ")");
      const auto existing = select(db_, candidate);
      if (!existing) return candidate;
      Record renamed = incoming;
      renamed.name = candidate;
      if (same_content(*existing, renamed)) {
        identical_found = true;
        return candidate;
      }
    }
  }

  void import_tool(const IncomingTool& incoming) {
    const ToolRecord& tool = incoming.record;
    const auto existing = detail::select_tool(db_, tool.name);
    if (!existing) {
      detail::insert_tool(db_, tool);
      ++summary_.tools_added;
      row_written("import.tools");
    } else if (same_content(*existing, tool)) {
      ++summary_.tools_skipped;
    } else if (options_.on_name_clash == NameClash::kFail) {
      problems_.push_back({incoming.path + ".name", "= '" + tool.name + "' already exists with different content (" +
                                                        differences(*existing, tool) +
                                                        "); import with rename or replace"});
    } else if (options_.on_name_clash == NameClash::kReplace) {
      detail::update_tool(db_, existing->id, tool);
      ++summary_.tools_replaced;
      summary_.messages.push_back("tool '" + tool.name + "' replaced (" + differences(*existing, tool) + ")");
      row_written("import.tools");
    } else {
      bool identical = false;
      ToolRecord renamed = tool;
      renamed.name = free_name(tool.name, detail::select_tool, tool, identical);
      if (!identical) {
        detail::insert_tool(db_, renamed);
        row_written("import.tools");
      }
      ++summary_.tools_renamed;
      tool_names_[tool.name] = renamed.name;
      summary_.messages.push_back("tool '" + tool.name + "' imported as '" + renamed.name + "' (" +
                                  differences(*existing, tool) + ")");
    }
  }

  void import_material(const IncomingMaterial& incoming) {
    const MaterialRecord& material = incoming.record;
    const auto existing = detail::select_material(db_, material.name);
    if (!existing) {
      detail::insert_material(db_, material);
      ++summary_.materials_added;
      row_written("import.materials");
    } else if (same_content(*existing, material)) {
      ++summary_.materials_skipped;
    } else if (options_.on_name_clash == NameClash::kFail) {
      problems_.push_back({incoming.path + ".name", "= '" + material.name +
                                                        "' already exists with different content (" +
                                                        differences(*existing, material) +
                                                        "); import with rename or replace"});
    } else if (options_.on_name_clash == NameClash::kReplace) {
      detail::update_material(db_, existing->id, material);
      ++summary_.materials_replaced;
      summary_.messages.push_back("material '" + material.name + "' replaced (" + differences(*existing, material) + ")");
      row_written("import.materials");
    } else {
      bool identical = false;
      MaterialRecord renamed = material;
      renamed.name = free_name(material.name, detail::select_material, material, identical);
      if (!identical) {
        detail::insert_material(db_, renamed);
        row_written("import.materials");
      }
      ++summary_.materials_renamed;
      material_names_[material.name] = renamed.name;
      summary_.messages.push_back("material '" + material.name + "' imported as '" + renamed.name + "' (" +
                                  differences(*existing, material) + ")");
    }
  }

  std::string tool_name(const std::string& document_name) const {
    const auto found = tool_names_.find(document_name);
    return found != tool_names_.end() ? found->second : document_name;
  }

  std::string material_name(const std::string& document_name) const {
    const auto found = material_names_.find(document_name);
    return found != material_names_.end() ? found->second : document_name;
  }

  //! The store's ids of a pair named in the document (after renames), or a problem at `path`.
  std::optional<detail::PairIds> pair(const std::string& tool, const std::string& material, const std::string& path) {
    std::vector<InputProblem> unknown;
    const auto ids = detail::pair_ids(db_, tool_name(tool), material_name(material), path + ".", unknown);
    for (auto& problem : unknown) {
      // pair_ids names the fields tool_name / material_name; the document calls them tool / material.
      if (problem.field.size() > 5 && problem.field.compare(problem.field.size() - 5, 5, "_name") == 0) {
        problem.field.resize(problem.field.size() - 5);
      }
      problems_.push_back(std::move(problem));
    }
    if (!unknown.empty()) return std::nullopt;
    return ids;
  }

  void import_models(const std::vector<IncomingModel>& models) {
    // Pairs in document order of first appearance; versions ascending inside each pair (a parent is
    // always an earlier version, so it is written, or matched, before its children).
    std::vector<std::pair<std::string, std::string>> pairs;
    std::map<std::pair<std::string, std::string>, std::vector<const IncomingModel*>> by_pair;
    for (const auto& model : models) {
      const auto key = std::make_pair(model.record.tool_name, model.record.material_name);
      if (by_pair.count(key) == 0) pairs.push_back(key);
      by_pair[key].push_back(&model);
    }
    for (const auto& key : pairs) {
      auto& list = by_pair[key];
      std::sort(list.begin(), list.end(),
                [](const IncomingModel* a, const IncomingModel* b) { return a->record.version < b->record.version; });
      import_pair(list);
    }
  }

  void import_pair(const std::vector<const IncomingModel*>& list) {
    const IncomingModel& first = *list.front();
    const auto ids = pair(first.record.tool_name, first.record.material_name, first.path);
    if (!ids) return;
    std::map<int, ModelRecord> stored;
    int max_version = 0;
    for (auto& model : detail::select_models_for(db_, ids->tool_id, ids->material_id)) {
      max_version = std::max(max_version, model.version);
      stored.emplace(model.version, std::move(model));
    }
    const bool had_active = std::any_of(stored.begin(), stored.end(), [](const auto& v) { return v.second.active; });
    std::optional<RowId> incoming_active;
    bool incoming_active_written = false;
    for (const IncomingModel* incoming : list) {
      const ModelRecord& record = incoming->record;
      const ModelKey key{record.tool_name, record.material_name, record.version};
      const auto match = stored.find(record.version);
      RowId id = 0;
      bool written = false;
      if (match != stored.end() && same_content(match->second, record)) {
        id = match->second.id;
        ++summary_.models_skipped;
      } else if (match != stored.end() && options_.on_name_clash == NameClash::kFail) {
        problems_.push_back({incoming->path + ".version",
                             "= " + std::to_string(record.version) + ": " + tool_name(record.tool_name) + " in " +
                                 material_name(record.material_name) + " already has a different version " +
                                 std::to_string(record.version) + " (created " + match->second.created_at +
                                 "); import with rename or replace to append it as a new version"});
        continue;
      } else {
        ModelRecord row = record;
        row.version = record.version > max_version ? record.version : max_version + 1;
        if (row.version != record.version) {
          ++summary_.models_renumbered;
          summary_.messages.push_back(tool_name(record.tool_name) + " in " + material_name(record.material_name) +
                                      " v" + std::to_string(record.version) + " imported as v" +
                                      std::to_string(row.version));
        }
        max_version = row.version;
        row.parent_id.reset();
        if (incoming->parent_version) {
          const auto parent = written_models_.find({record.tool_name, record.material_name, *incoming->parent_version});
          if (parent != written_models_.end()) row.parent_id = parent->second;
        }
        id = detail::insert_model_row(db_, ids->tool_id, ids->material_id, row);
        ++summary_.models_added;
        written = true;
        row_written("import.models");
      }
      written_models_[key] = id;
      if (record.active) {
        incoming_active = id;
        incoming_active_written = written;
      }
    }
    if (!incoming_active) return;
    const bool activate = !had_active || options_.on_name_clash == NameClash::kReplace ||
                          (incoming_active_written && options_.on_name_clash == NameClash::kFail);
    if (activate && detail::activate_model(db_, ids->tool_id, ids->material_id, *incoming_active,
                                           ActivationReason::kImported, detail::utc_now_iso8601())) {
      row_written("import.activate");
    }
  }

  void import_test(const IncomingTest& incoming) {
    const auto& conditions = incoming.stored.test.conditions;
    const auto ids = pair(conditions.tool_name, conditions.material_name, incoming.path);
    if (!ids) return;
    // Stored tests of the pair by time stamp: an identical test has the same created_at.
    auto& stored = tests_by_pair_[{ids->tool_id, ids->material_id}];
    if (!stored) {
      stored.emplace();
      for (auto& test : detail::select_cutting_tests(db_, ids->tool_id, ids->material_id)) {
        stored->emplace(test.created_at, std::move(test));
      }
    }
    const auto [first, last] = stored->equal_range(incoming.stored.created_at);
    for (auto existing = first; existing != last; ++existing) {
      if (same_content(existing->second, incoming.stored)) {
        ++summary_.cutting_tests_skipped;
        return;
      }
    }
    CuttingTestRecord test = incoming.stored.test;
    test.conditions.tool_name = tool_name(conditions.tool_name);
    test.conditions.material_name = material_name(conditions.material_name);
    detail::insert_cutting_test(db_, ids->tool_id, ids->material_id, test, incoming.stored.created_at);
    ++summary_.cutting_tests_added;
    row_written("import.cutting_tests");
  }

  //! The store's id of a model version named in the document: one this import wrote or matched, else
  //! one already stored under that (renamed) tool, material and version.
  std::optional<RowId> model_id(const ModelKey& key, const std::string& path) {
    const auto written = written_models_.find(key);
    if (written != written_models_.end()) return written->second;
    const auto ids = pair(key.tool, key.material, path);
    if (!ids) return std::nullopt;
    for (const auto& model : detail::select_models_for(db_, ids->tool_id, ids->material_id)) {
      if (model.version == key.version) return model.id;
    }
    problems_.push_back({path + ".version", "= " + std::to_string(key.version) + ": no such version of " +
                                                tool_name(key.tool) + " in " + material_name(key.material) +
                                                " in the document or the store"});
    return std::nullopt;
  }

  void import_entry(const IncomingEntry& incoming) {
    const auto before = model_id(incoming.before, incoming.path + ".model_before");
    std::optional<RowId> after = 0;
    if (incoming.after) after = model_id(*incoming.after, incoming.path + ".model_after");
    if (!before || !after) return;
    LearningEntry entry = incoming.entry;
    entry.model_id_before = *before;
    entry.model_id_after = *after;
    if (!stored_entries_) stored_entries_ = detail::select_learning_entries(db_, 0, 0);
    for (const auto& existing : *stored_entries_) {
      if (same_content(existing, entry)) {
        ++summary_.learning_entries_skipped;
        return;
      }
    }
    detail::insert_learning_entry(db_, entry, entry.created_at);
    ++summary_.learning_entries_added;
    row_written("import.learning_history");
  }

  Store::Impl& impl_;
  detail::Connection& db_;
  const ImportOptions& options_;
  ImportSummary summary_;
  std::vector<InputProblem> problems_;
  std::map<std::string, std::string> tool_names_;      // document name → stored name (renames)
  std::map<std::string, std::string> material_names_;  // document name → stored name (renames)
  std::map<ModelKey, RowId> written_models_;           // document key → stored id
  std::map<std::pair<RowId, RowId>, std::optional<std::multimap<std::string, StoredCuttingTest>>> tests_by_pair_;
  std::optional<std::vector<LearningEntry>> stored_entries_;
};

}  // namespace

ImportSummary import_json(Store& store, std::string_view json_text, const ImportOptions& options,
                          const std::string& source_name) {
  const Document document = read_document(json_text, source_name);
  return Importer(store.impl(), options).run(document);
}

ImportSummary import_from_file(Store& store, const std::filesystem::path& path, const ImportOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path.string(), "cannot be read: no such file (expected a model database export, JSON)");
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw InputError(path.string(), "cannot be read");
  return import_json(store, text.str(), options, path.string());
}

}  // namespace feedplan::model_db
