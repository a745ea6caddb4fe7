#include <algorithm>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include "catalog_rows.hpp"
#include "cutting_test_rows.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/json_document.hpp"
#include "feedplan/core/json_fields.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/model/mechanistic_json.hpp"
#include "feedplan/model/model_json.hpp"
#include "feedplan/model_db/model_exchange.hpp"
#include "learning_rows.hpp"
#include "model_rows.hpp"
#include "store_impl.hpp"
#include "utc_time.hpp"
#include "write_transaction.hpp"

namespace feedplan::model_db {
namespace {

using Json = nlohmann::json;
using Reader = JsonFieldReader<Json>;
using Node = JsonNode<Json>;

// How the exchange file phrases problems (core/json_fields.hpp): values as 'text', each member of a
// missing object named, array lengths after the elements, bad list elements read as 0.
constexpr JsonFieldRules kExchangeRules{JsonTextShown::kSingleQuoted, JsonObjectRule::kEachMemberMissing,
                                        JsonLengthRule::kCountNumbersLast, JsonBadElement::kReadAsZero};

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
  std::vector<LearnedSample> samples;  //!< the per-revolution samples the step learned from (may be none)
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

void check_time(const Node& node, const std::string& created_at) {
  if (!detail::is_utc_iso8601(created_at)) {
    node.report(node.child_path("created_at"),
                "= '" + created_at + "': must be UTC ISO 8601, e.g. 2024-05-01T12:00:00.000Z");
  }
}

ToolRecord read_tool(const Node& node) {
  ToolRecord tool;
  tool.name = node.text("name");
  tool.diameter_mm = node.number("diameter_mm");
  tool.flutes = node.integer("flutes");
  tool.helix_deg = node.number("helix_deg");
  tool.tool_material = node.text("tool_material", JsonPresence::kOptional);
  tool.coating = node.text("coating", JsonPresence::kOptional);
  tool.notes = node.text("notes", JsonPresence::kOptional);
  return tool;
}

MaterialRecord read_material(const Node& node) {
  MaterialRecord material;
  material.name = node.text("name");
  const std::string group = node.text("iso_group");
  if (const auto parsed = parse_iso_group(group)) {
    material.iso_group = *parsed;
  } else if (node.has("iso_group")) {
    node.report(node.child_path("iso_group"), "= '" + group + "': must be one of P, M, K, N, S, H");
  }
  material.hardness_value = node.number("hardness_value");
  material.hardness_scale = node.text("hardness_scale");
  material.notes = node.text("notes", JsonPresence::kOptional);
  return material;
}

ModelFitStatistics read_fit(const Node& node) {
  ModelFitStatistics fit;
  fit.n = node.integer("n");
  fit.rmse_n = node.number("rmse_n");
  fit.r_squared = node.number("r_squared");
  fit.covariance = model::Covariance::from_entries(node.fixed_numbers<36>("covariance"));
  fit.standard_errors = node.fixed_numbers<6>("standard_errors");
  fit.loo_rmse_n = node.number("loo_rmse_n");
  if (node.has("engagement_cv_rmse_n")) fit.engagement_cv_rmse_n = node.number("engagement_cv_rmse_n");
  return fit;
}

MechanisticFit read_mechanistic(const Node& node) {
  MechanisticFit fit;
  fit.model = model::read_mechanistic_json(node);
  const std::array<double, 16> covariance = node.fixed_numbers<16>("covariance");
  for (std::size_t i = 0; i < 16; ++i) fit.covariance[i / 4][i % 4] = covariance[i];
  fit.signal_rms_residual_n = node.number("signal_rms_residual_n");
  fit.condition_number = node.number("condition_number");
  fit.identified = node.boolean("identified");
  fit.unidentifiable = node.texts("unidentifiable", JsonPresence::kOptional);
  return fit;
}

IncomingModel read_model(const Node& node) {
  IncomingModel incoming{node.path(), {}, std::nullopt};
  ModelRecord& record = incoming.record;
  record.tool_name = node.text("tool");
  record.material_name = node.text("material");
  record.version = node.integer("version");
  if (record.version < 1 && node.has("version")) {
    node.report(node.child_path("version"), "= " + std::to_string(record.version) + ": must be ≥ 1");
  }
  incoming.parent_version = node.optional_integer("parent_version");
  record.active = node.boolean("active");
  const std::string source = node.text("source");
  if (const auto parsed = parse_model_source(source)) {
    record.source = *parsed;
  } else if (node.has("source")) {
    node.report(node.child_path("source"), "= '" + source + "': must be cutting_tests, learned or imported");
  }
  record.created_at = node.text("created_at");
  check_time(node, record.created_at);
  record.note = node.text("note", JsonPresence::kOptional);
  // Exports before the mechanistic kind hold response surfaces only and no "kind".
  const std::string kind = node.has("kind") ? node.text("kind") : to_string(ModelKind::kResponseSurface);
  if (const auto parsed = parse_model_kind(kind)) {
    record.kind = *parsed;
  } else {
    node.report(node.child_path("kind"), "= '" + kind + "': must be response_surface or mechanistic");
  }
  record.model = model::read_model_json(node.object("model"));
  if (record.kind == ModelKind::kMechanistic) record.mechanistic = read_mechanistic(node.object("mechanistic"));
  record.fit = read_fit(node.object("fit"));
  return incoming;
}

StoredCuttingTest read_test(const Node& node) {
  StoredCuttingTest stored;
  stored.created_at = node.text("created_at");
  check_time(node, stored.created_at);
  CuttingTestRecord& test = stored.test;
  CuttingTestConditions& conditions = test.conditions;
  conditions.tool_name = node.text("tool");
  conditions.material_name = node.text("material");
  conditions.spindle_rpm = node.number("spindle_rpm");
  conditions.feed_mm_per_min = node.number("feed_mm_per_min");
  conditions.radial_depth_mm = node.number("radial_depth_mm");
  conditions.axial_depth_mm = node.number("axial_depth_mm");
  const std::string mode = node.text("mode");
  if (const auto parsed = detail::parse_cut_mode(mode)) {
    conditions.mode = *parsed;
  } else if (node.has("mode")) {
    node.report(node.child_path("mode"), "= '" + mode + "': must be down, up or slot");
  }
  test.feed_per_tooth_mm = node.number("feed_per_tooth_mm");
  test.chip_mm = node.number("chip_mm");
  test.contact_length_mm = node.number("contact_length_mm");
  test.peak_mean_n = node.number("peak_mean_n");
  test.peak_std_n = node.number("peak_std_n");
  test.peak_min_n = node.number("peak_min_n");
  test.peak_max_n = node.number("peak_max_n");
  test.revolutions_total = node.integer("revolutions_total");
  test.revolutions_used = node.integer("revolutions_used");
  test.steady_peaks_n = node.numbers("steady_peaks_n");
  test.synchronous_fx_n = node.numbers("synchronous_fx_n", JsonPresence::kOptional);
  test.synchronous_fy_n = node.numbers("synchronous_fy_n", JsonPresence::kOptional);
  test.source = node.text("source", JsonPresence::kOptional);
  test.notes = node.texts("notes", JsonPresence::kOptional);
  return stored;
}

ModelKey read_reference(const Node& node) {
  return {node.text("tool"), node.text("material"), node.integer("version")};
}

IncomingEntry read_entry(const Node& node) {
  IncomingEntry incoming;
  incoming.path = node.path();
  incoming.before = read_reference(node.object("model_before"));
  const Json* after = node.member("model_after", JsonPresence::kOptional);
  if (after != nullptr && !after->is_null()) incoming.after = read_reference(node.object("model_after"));
  LearningEntry& entry = incoming.entry;
  entry.part_name = node.text("part_name");
  entry.n_samples = node.integer("n_samples");
  entry.error_before_n = node.number("error_before_n");
  entry.error_after_n = node.number("error_after_n");
  entry.created_at = node.text("created_at");
  check_time(node, entry.created_at);
  entry.note = node.text("note", JsonPresence::kOptional);
  const Node samples = node.array("samples", JsonPresence::kOptional);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Node sample = samples.item(i, "samples[" + std::to_string(i) + "]");
    incoming.samples.push_back({sample.number("chip_mm"), sample.number("contact_length_mm"), sample.number("force_n"),
                                sample.number_at_least("weight", std::numeric_limits<double>::min()),
                                sample.number("s_mm")});
  }
  return incoming;
}

// ---- the steps of read_document ----

//! The JSON text parsed; text that is not JSON, nests too deep or is JSON of another format throws.
Json parse_exchange_text(std::string_view text, const std::string& source_name) {
  Json root = parse_json_document<Json>(text, source_name);
  const auto format = root.is_object() ? root.find("format") : root.end();
  if (format == root.end() || !format->is_string() || format->get<std::string>() != "feedplan-model-db") {
    throw InputError(source_name, "is not a feedplan model database export (expected \"format\": \"feedplan-model-db\")");
  }
  return root;
}

//! Throws unless the document's format_version is one this code reads (1 up to kExchangeFormatVersion).
void check_format_version(Reader& reader, const Node& root, const std::string& source_name) {
  const int format_version = root.integer("format_version");
  reader.throw_if_any();
  if (format_version > kExchangeFormatVersion) {
    throw InputError(source_name, "has format_version " + std::to_string(format_version) +
                                      ", newer than this feedplan reads (" + std::to_string(kExchangeFormatVersion) +
                                      "): upgrade feedplan");
  }
  if (format_version < 1) {
    throw InputError("document.format_version", "= " + std::to_string(format_version) + ": must be ≥ 1");
  }
}

//! The list `key` of the document, its items named "key[i]" (without the document's name).
template <typename Item, typename ReadItem>
std::vector<Item> read_list(const Node& root, const std::string& key, ReadItem&& read_item) {
  const Node list = root.array(key, JsonPresence::kOptional);
  std::vector<Item> items;
  for (std::size_t i = 0; i < list.size(); ++i) {
    items.push_back(read_item(list.item(i, key + "[" + std::to_string(i) + "]")));
  }
  return items;
}

//! "<path>.name = '<name>': appears twice in the document" for each name given before.
void check_unique_name(Reader& reader, std::set<std::string>& names, const std::string& path,
                       const std::string& name) {
  if (!names.insert(name).second) reader.add(path + ".name", "= '" + name + "': appears twice in the document");
}

std::vector<IncomingTool> read_tools(Reader& reader, const Node& root) {
  std::set<std::string> names;
  return read_list<IncomingTool>(root, "tools", [&](const Node& node) {
    IncomingTool tool{node.path(), read_tool(node)};
    add_located(reader.problems, validate(tool.record), "tools", tool.path);
    check_unique_name(reader, names, tool.path, tool.record.name);
    return tool;
  });
}

std::vector<IncomingMaterial> read_materials(Reader& reader, const Node& root) {
  std::set<std::string> names;
  return read_list<IncomingMaterial>(root, "materials", [&](const Node& node) {
    IncomingMaterial material{node.path(), read_material(node)};
    add_located(reader.problems, validate(material.record), "materials", material.path);
    check_unique_name(reader, names, material.path, material.record.name);
    return material;
  });
}

//! The models, each checked on its own and for a version given twice.
std::vector<IncomingModel> read_models(Reader& reader, const Node& root) {
  std::set<ModelKey> keys;
  return read_list<IncomingModel>(root, "models", [&](const Node& node) {
    IncomingModel model = read_model(node);
    add_located(reader.problems, validate(model.record), "models", model.path);
    const ModelRecord& r = model.record;
    if (!keys.insert({r.tool_name, r.material_name, r.version}).second) {
      reader.add(model.path + ".version", "= " + std::to_string(r.version) + ": " + r.tool_name + " in " +
                                              r.material_name + " has this version twice in the document");
    }
    return model;
  });
}

//! Each parent_version names an earlier version of the same pair and kind in the document, and each pair
//! has exactly one active version of each kind it has.
void check_model_history(Reader& reader, const std::vector<IncomingModel>& models) {
  std::map<ModelKey, ModelKind> keys;
  std::map<std::tuple<std::string, std::string, ModelKind>, int> active_per_pair;
  for (const auto& model : models) {
    const ModelRecord& r = model.record;
    keys.emplace(ModelKey{r.tool_name, r.material_name, r.version}, r.kind);
    active_per_pair[{r.tool_name, r.material_name, r.kind}] += r.active ? 1 : 0;
  }
  for (const auto& model : models) {
    const ModelRecord& r = model.record;
    if (!model.parent_version) continue;
    const auto parent = keys.find({r.tool_name, r.material_name, *model.parent_version});
    if (*model.parent_version >= r.version || parent == keys.end() || parent->second != r.kind) {
      reader.add(model.path + ".parent_version",
                 "= " + std::to_string(*model.parent_version) + ": must be an earlier " + to_string(r.kind) +
                     " version of " + r.tool_name + " in " + r.material_name + " in the document (or null)");
    }
  }
  for (const auto& [pair, count] : active_per_pair) {
    if (count != 1) {
      reader.add("models", std::get<0>(pair) + " in " + std::get<1>(pair) + " has " + std::to_string(count) +
                               " active " + to_string(std::get<2>(pair)) + " versions: must have exactly one");
    }
  }
}

std::vector<IncomingTest> read_tests(Reader& reader, const Node& root) {
  return read_list<IncomingTest>(root, "cutting_tests", [&](const Node& node) {
    IncomingTest test{node.path(), read_test(node)};
    add_located(reader.problems, validate(test.stored.test), "cutting_tests", test.path);
    return test;
  });
}

std::vector<IncomingEntry> read_entries(Reader& reader, const Node& root) {
  return read_list<IncomingEntry>(root, "learning_history", [&](const Node& node) {
    IncomingEntry entry = read_entry(node);
    LearningEntry checked = entry.entry;
    checked.model_id_before = 1;  // references are checked against the models when writing
    add_located(reader.problems, validate(checked), "learning_history", entry.path);
    return entry;
  });
}

//! Parses and checks the document on its own (references to names not in it are checked later,
//! against the store). Throws InputError with every problem.
Document read_document(std::string_view text, const std::string& source_name) {
  const Json json = parse_exchange_text(text, source_name);
  Reader reader(kExchangeRules);
  const Node root = reader.node(json, "document");
  check_format_version(reader, root, source_name);
  Document document;
  document.tools = read_tools(reader, root);
  document.materials = read_materials(reader, root);
  document.models = read_models(reader, root);
  check_model_history(reader, document.models);
  document.tests = read_tests(reader, root);
  document.entries = read_entries(reader, root);
  reader.throw_if_any();
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

bool same_content(const MechanisticFit& a, const MechanisticFit& b) {
  const auto& x = a.model;
  const auto& y = b.model;
  return std::tie(x.ktc_n_per_mm2, x.krc_n_per_mm2, x.kac_n_per_mm2, x.kte_n_per_mm, x.kre_n_per_mm, x.kae_n_per_mm,
                  x.size_exponent, x.size_reference_chip_mm, x.size_min_chip_mm, x.runout_mm, x.helix_deg, a.covariance,
                  a.signal_rms_residual_n, a.condition_number, a.identified, a.unidentifiable) ==
         std::tie(y.ktc_n_per_mm2, y.krc_n_per_mm2, y.kac_n_per_mm2, y.kte_n_per_mm, y.kre_n_per_mm, y.kae_n_per_mm,
                  y.size_exponent, y.size_reference_chip_mm, y.size_min_chip_mm, y.runout_mm, y.helix_deg, b.covariance,
                  b.signal_rms_residual_n, b.condition_number, b.identified, b.unidentifiable);
}

bool same_content(const ModelRecord& a, const ModelRecord& b) {
  if (a.kind != b.kind || a.mechanistic.has_value() != b.mechanistic.has_value()) return false;
  if (a.mechanistic && !same_content(*a.mechanistic, *b.mechanistic)) return false;
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
                  a.fit.engagement_cv_rmse_n, a.source, a.created_at, a.note) ==
             std::tie(b.fit.n, b.fit.rmse_n, b.fit.r_squared, b.fit.covariance, b.fit.standard_errors,
                      b.fit.loo_rmse_n, b.fit.engagement_cv_rmse_n, b.source, b.created_at, b.note);
}

bool same_content(const StoredCuttingTest& a, const StoredCuttingTest& b) {
  const auto& s = a.test;
  const auto& t = b.test;
  const auto& c = s.conditions;
  const auto& d = t.conditions;
  return std::tie(a.created_at, c.spindle_rpm, c.feed_mm_per_min, c.radial_depth_mm, c.axial_depth_mm, c.mode) ==
             std::tie(b.created_at, d.spindle_rpm, d.feed_mm_per_min, d.radial_depth_mm, d.axial_depth_mm, d.mode) &&
         std::tie(s.feed_per_tooth_mm, s.chip_mm, s.contact_length_mm, s.peak_mean_n, s.peak_std_n, s.peak_min_n,
                  s.peak_max_n, s.revolutions_total, s.revolutions_used, s.steady_peaks_n, s.synchronous_fx_n,
                  s.synchronous_fy_n, s.source, s.notes) ==
             std::tie(t.feed_per_tooth_mm, t.chip_mm, t.contact_length_mm, t.peak_mean_n, t.peak_std_n, t.peak_min_n,
                      t.peak_max_n, t.revolutions_total, t.revolutions_used, t.steady_peaks_n, t.synchronous_fx_n,
                      t.synchronous_fy_n, t.source, t.notes);
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
    std::set<ModelKind> had_active;
    for (const auto& [version, model] : stored) {
      if (model.active) had_active.insert(model.kind);
    }
    std::map<ModelKind, std::pair<RowId, bool>> incoming_active;  // per kind: id, and whether this import wrote it
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
      if (record.active) incoming_active[record.kind] = {id, written};
    }
    for (const auto& [kind, active] : incoming_active) {
      const auto [active_id, active_written] = active;
      const bool activate = had_active.count(kind) == 0 || options_.on_name_clash == NameClash::kReplace ||
                            (active_written && options_.on_name_clash == NameClash::kFail);
      if (activate && detail::activate_model(db_, ids->tool_id, ids->material_id, active_id,
                                             ActivationReason::kImported, detail::utc_now_iso8601())) {
        row_written("import.activate");
      }
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
    const RowId id = detail::insert_learning_entry(db_, entry, entry.created_at);
    detail::insert_learned_samples(db_, id, incoming.samples);
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

// Bytes an export file may hold (10 000 model versions are about 20 MiB).
constexpr std::size_t kMaxExportFileBytes = std::size_t{256} << 20;

ImportSummary import_from_file(Store& store, const std::filesystem::path& path, const ImportOptions& options) {
  const std::string text = read_input_file(path, {"a model database export, JSON", kMaxExportFileBytes,
                                                  "an export of 10 000 model versions is about 20 MiB"});
  return import_json(store, text, options, path.string());
}

}  // namespace feedplan::model_db
