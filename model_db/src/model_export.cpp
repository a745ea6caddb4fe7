#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "cutting_test_rows.hpp"
#include "learning_rows.hpp"
#include "store_impl.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/model/mechanistic_json.hpp"
#include "feedplan/model/model_json.hpp"
#include "feedplan/model_db/model_exchange.hpp"

namespace feedplan::model_db {
namespace {

using Json = nlohmann::ordered_json;

Json model_reference(const ModelRecord& model) {
  return Json{{"tool", model.tool_name}, {"material", model.material_name}, {"version", model.version}};
}

Json to_json(const ToolRecord& tool) {
  return Json{{"name", tool.name},           {"diameter_mm", tool.diameter_mm},     {"flutes", tool.flutes},
              {"helix_deg", tool.helix_deg}, {"tool_material", tool.tool_material}, {"coating", tool.coating},
              {"notes", tool.notes}};
}

Json to_json(const MaterialRecord& material) {
  return Json{{"name", material.name},
              {"iso_group", to_string(material.iso_group)},
              {"hardness_value", material.hardness_value},
              {"hardness_scale", material.hardness_scale},
              {"notes", material.notes}};
}

Json to_json(const MechanisticFit& fit) {
  std::vector<double> covariance;
  for (const auto& row : fit.covariance) covariance.insert(covariance.end(), row.begin(), row.end());
  Json json = model::to_json(fit.model);
  json["covariance"] = covariance;
  json["signal_rms_residual_n"] = fit.signal_rms_residual_n;
  json["condition_number"] = fit.condition_number;
  json["identified"] = fit.identified;
  json["unidentifiable"] = fit.unidentifiable;
  return json;
}

Json to_json(const ModelRecord& record, const std::optional<int>& parent_version) {
  Json json{{"tool", record.tool_name},
            {"material", record.material_name},
            {"version", record.version},
            {"parent_version", parent_version ? Json(*parent_version) : Json(nullptr)},
            {"active", record.active},
            {"source", to_string(record.source)},
            {"created_at", record.created_at},
            {"note", record.note}};
  json["kind"] = to_string(record.kind);
  json["model"] = model::to_json(record.model);
  if (record.mechanistic) json["mechanistic"] = to_json(*record.mechanistic);
  json["fit"] = Json{{"n", record.fit.n},
                     {"rmse_n", record.fit.rmse_n},
                     {"r_squared", record.fit.r_squared},
                     {"covariance", record.fit.covariance.entries()},
                     {"standard_errors", record.fit.standard_errors},
                     {"loo_rmse_n", record.fit.loo_rmse_n},
                     {"engagement_cv_rmse_n", record.fit.engagement_cv_rmse_n}};
  return json;
}

Json to_json(const StoredCuttingTest& stored) {
  const CuttingTestRecord& test = stored.test;
  const CuttingTestConditions& conditions = test.conditions;
  return Json{{"tool", conditions.tool_name},
              {"material", conditions.material_name},
              {"created_at", stored.created_at},
              {"spindle_rpm", conditions.spindle_rpm},
              {"feed_mm_per_min", conditions.feed_mm_per_min},
              {"radial_depth_mm", conditions.radial_depth_mm},
              {"axial_depth_mm", conditions.axial_depth_mm},
              {"mode", detail::to_text(conditions.mode)},
              {"feed_per_tooth_mm", test.feed_per_tooth_mm},
              {"chip_mm", test.chip_mm},
              {"contact_length_mm", test.contact_length_mm},
              {"peak_mean_n", test.peak_mean_n},
              {"peak_std_n", test.peak_std_n},
              {"peak_min_n", test.peak_min_n},
              {"peak_max_n", test.peak_max_n},
              {"revolutions_total", test.revolutions_total},
              {"revolutions_used", test.revolutions_used},
              {"steady_peaks_n", test.steady_peaks_n},
              {"synchronous_fx_n", test.synchronous_fx_n},
              {"synchronous_fy_n", test.synchronous_fy_n},
              {"source", test.source},
              {"notes", test.notes}};
}

}  // namespace

std::string export_json(const Store& store, const ExportOptions& options) {
  Json document{{"format", "feedplan-model-db"},
                {"format_version", kExchangeFormatVersion},
                {"contents", options.active_models_only ? "active_models" : "all_versions"}};
  Json tools = Json::array();
  for (const auto& tool : store.tools()) tools.push_back(to_json(tool));
  document["tools"] = std::move(tools);
  Json materials = Json::array();
  for (const auto& material : store.materials()) materials.push_back(to_json(material));
  document["materials"] = std::move(materials);

  const std::vector<ModelRecord> all = store.all_models();
  std::map<RowId, const ModelRecord*> by_id;
  for (const auto& model : all) by_id.emplace(model.id, &model);
  std::set<RowId> exported;
  for (const auto& model : all) {
    if (!options.active_models_only || model.active) exported.insert(model.id);
  }
  Json models = Json::array();
  for (const auto& model : all) {
    if (exported.count(model.id) == 0) continue;
    // A parent left out of the document is not named: the importing store could not resolve it.
    const bool parent_exported = model.parent_id && exported.count(*model.parent_id) != 0;
    models.push_back(to_json(model, parent_exported ? model.parent_version : std::nullopt));
  }
  document["models"] = std::move(models);

  if (options.include_cutting_tests) {
    Json tests = Json::array();
    for (const auto& test : store.all_cutting_tests()) tests.push_back(to_json(test));
    document["cutting_tests"] = std::move(tests);
  }
  if (options.include_learning_history) {
    Json history = Json::array();
    for (const auto& entry : store.all_learning_entries()) {
      const bool before_exported = exported.count(entry.model_id_before) != 0;
      const bool after_exported = entry.model_id_after == 0 || exported.count(entry.model_id_after) != 0;
      if (!before_exported || !after_exported) continue;
      Json item{{"model_before", model_reference(*by_id.at(entry.model_id_before))},
                {"model_after", entry.model_id_after == 0 ? Json(nullptr) : model_reference(*by_id.at(entry.model_id_after))},
                {"part_name", entry.part_name},
                {"n_samples", entry.n_samples},
                {"error_before_n", entry.error_before_n},
                {"error_after_n", entry.error_after_n},
                {"created_at", entry.created_at},
                {"note", entry.note}};
      const auto samples = detail::select_samples_of_entry(store.impl().db, entry.id);
      if (!samples.empty()) {
        Json rows = Json::array();
        for (const LearnedSample& sample : samples) {
          rows.push_back(Json{{"chip_mm", sample.chip_mm},
                              {"contact_length_mm", sample.contact_length_mm},
                              {"force_n", sample.force_n},
                              {"weight", sample.weight},
                              {"s_mm", sample.s_mm}});
        }
        item["samples"] = std::move(rows);
      }
      history.push_back(std::move(item));
    }
    document["learning_history"] = std::move(history);
  }
  return document.dump(2) + "\n";
}

void export_to_file(const Store& store, const std::filesystem::path& path, const ExportOptions& options) {
  const std::string problem = write_file_atomically(path, export_json(store, options));
  if (!problem.empty()) throw InputError("", problem);  // the message names the path
}

}  // namespace feedplan::model_db
