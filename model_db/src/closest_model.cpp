#include "feedplan/model_db/closest_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "feedplan/core/number_text.hpp"

namespace feedplan::model_db {
namespace {

std::string describe(const ToolRecord& tool) {
  return "Ø" + shortest_number_text(tool.diameter_mm) + " " + std::to_string(tool.flutes) + "-flute (" + tool.name + ")";
}

std::string hardness_text(const MaterialRecord& material) {
  return shortest_number_text(material.hardness_value) + " " + material.hardness_scale;
}

//! "nearest diameter 10 vs 8 mm, flutes 4 vs 3, helix 30 vs 35°": how the chosen tool differs.
std::string tool_difference(const ToolRecord& wanted, const ToolRecord& used) {
  std::string text = used.diameter_mm == wanted.diameter_mm
                         ? "same diameter " + shortest_number_text(used.diameter_mm) + " mm"
                         : "nearest diameter " + shortest_number_text(used.diameter_mm) + " vs " +
                               shortest_number_text(wanted.diameter_mm) + " mm";
  text += used.flutes == wanted.flutes
              ? ", same flute count " + std::to_string(used.flutes)
              : ", flutes " + std::to_string(used.flutes) + " vs " + std::to_string(wanted.flutes);
  if (used.helix_deg != wanted.helix_deg) {
    text += ", helix " + shortest_number_text(used.helix_deg) + " vs " + shortest_number_text(wanted.helix_deg) + "°";
  }
  return text;
}

std::string material_difference(const MaterialRecord& wanted, const MaterialRecord& used) {
  return "same ISO group " + to_string(used.iso_group) + ", hardness " + hardness_text(used) + " vs " +
         hardness_text(wanted);
}

std::string rounded(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

struct Candidate {
  const ModelRecord* model = nullptr;
  const ToolRecord* tool = nullptr;
  const MaterialRecord* material = nullptr;
  ModelMatch match = ModelMatch::kExact;
  double distance = 0.0;
};

bool better(const Candidate& a, const Candidate& b) {
  return std::tie(a.match, a.distance, a.tool->name, a.material->name) <
         std::tie(b.match, b.distance, b.tool->name, b.material->name);
}

}  // namespace

std::string to_string(ModelMatch match) {
  switch (match) {
    case ModelMatch::kExact: return "exact";
    case ModelMatch::kSameMaterialOtherTool: return "same material, other tool";
    case ModelMatch::kSameIsoGroupExactTool: return "same tool, other material of the same ISO group";
    case ModelMatch::kSameIsoGroupOtherTool: return "other tool, other material of the same ISO group";
  }
  return "?";
}

double tool_distance(const ToolRecord& wanted, const ToolRecord& candidate) {
  const double largest = std::max(wanted.diameter_mm, candidate.diameter_mm);
  const double diameter = largest > 0.0 ? std::abs(wanted.diameter_mm - candidate.diameter_mm) / largest : 0.0;
  const double flutes = wanted.flutes != candidate.flutes ? kFluteMismatchWeight : 0.0;
  const double helix = kHelixWeight * std::abs(wanted.helix_deg - candidate.helix_deg) / 30.0;
  return diameter + flutes + helix;
}

std::optional<double> material_distance(const MaterialRecord& wanted, const MaterialRecord& candidate) {
  if (wanted.name == candidate.name) return 0.0;
  if (wanted.iso_group != candidate.iso_group) return std::nullopt;
  if (wanted.hardness_scale != candidate.hardness_scale) return kUnknownHardnessDistance;
  const double largest = std::max(wanted.hardness_value, candidate.hardness_value);
  return largest > 0.0 ? std::abs(wanted.hardness_value - candidate.hardness_value) / largest : 0.0;
}

ClosestModel closest_model(const Store& store, std::string_view tool_name, std::string_view material_name) {
  // active_model() throws the InputError (with the known names) for an unknown tool or material.
  (void)store.active_model(tool_name, material_name);
  return closest_model(store, *store.find_tool(tool_name), *store.find_material(material_name));
}

ClosestModel closest_model(const Store& store, const ToolRecord& tool, const MaterialRecord& material) {
  std::map<std::string, ToolRecord> tools;
  for (auto& t : store.tools()) tools.emplace(t.name, t);
  std::map<std::string, MaterialRecord> materials;
  for (auto& m : store.materials()) materials.emplace(m.name, m);
  const std::vector<ModelRecord> models = store.active_models();

  std::optional<Candidate> best;
  std::map<std::string, int> models_per_group;
  for (const ModelRecord& model : models) {
    const ToolRecord& candidate_tool = tools.at(model.tool_name);
    const MaterialRecord& candidate_material = materials.at(model.material_name);
    ++models_per_group[to_string(candidate_material.iso_group)];
    const auto material_part = material_distance(material, candidate_material);
    if (!material_part) continue;
    const bool same_tool = candidate_tool.name == tool.name;
    const bool same_material = candidate_material.name == material.name;
    Candidate candidate{&model, &candidate_tool, &candidate_material, ModelMatch::kExact, 0.0};
    if (same_material) {
      candidate.match = same_tool ? ModelMatch::kExact : ModelMatch::kSameMaterialOtherTool;
    } else {
      candidate.match = same_tool ? ModelMatch::kSameIsoGroupExactTool : ModelMatch::kSameIsoGroupOtherTool;
    }
    candidate.distance = (same_tool ? 0.0 : tool_distance(tool, candidate_tool)) + *material_part;
    if (!best || better(candidate, *best)) best = candidate;
  }

  ClosestModel result;
  const std::string asked = describe(tool) + " in " + material.name;
  if (!best) {
    result.status = ClosestModelStatus::kNoModel;
    if (models.empty()) {
      result.explanation = "no model for " + asked + ": the model database has no models yet";
    } else {
      std::string groups;
      for (const auto& [group, count] : models_per_group) {
        groups += (groups.empty() ? "" : ", ") + group + " (" + std::to_string(count) + ")";
      }
      result.explanation = "no model for " + asked + " nor for any material of ISO group " +
                           to_string(material.iso_group) + "; models exist only for ISO groups " + groups +
                           ", and a model for another group would mislead the plan";
    }
    return result;
  }
  result.status = ClosestModelStatus::kFound;
  result.model = *best->model;
  result.match = best->match;
  result.distance = best->distance;
  result.model_tool = *best->tool;
  result.model_material = *best->material;
  const std::string version = " v" + std::to_string(best->model->version);
  const std::string used = describe(*best->tool) + " in " + best->material->name + version;
  switch (best->match) {
    case ModelMatch::kExact:
      result.explanation = "using " + used + " (exact match)";
      break;
    case ModelMatch::kSameMaterialOtherTool:
      result.explanation = "no model for " + asked + "; using " + used + " (same material, " +
                           tool_difference(tool, *best->tool) + "; distance " + rounded(best->distance) + ")";
      break;
    case ModelMatch::kSameIsoGroupExactTool:
      result.explanation = "no model for " + asked + "; using " + used + " (same tool, " +
                           material_difference(material, *best->material) + "; distance " +
                           rounded(best->distance) + ")";
      break;
    case ModelMatch::kSameIsoGroupOtherTool:
      result.explanation = "no model for " + asked + "; using " + used + " (" +
                           material_difference(material, *best->material) + ", " +
                           tool_difference(tool, *best->tool) + "; distance " + rounded(best->distance) + ")";
      break;
  }
  return result;
}

}  // namespace feedplan::model_db
