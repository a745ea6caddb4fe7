#include "feedplan/model_db/model_borrowing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "feedplan/core/number_text.hpp"

namespace feedplan::model_db {
namespace {

// |a − b| / min(a, b): the factor between two quantities a force is proportional to, minus 1.
double relative_difference(double a, double b) {
  const double smaller = std::min(a, b);
  return smaller > 0.0 ? std::abs(a - b) / smaller : kUnknownHardnessRelative;
}

std::string hardness_text(const MaterialRecord& material) {
  return shortest_number_text(material.hardness_value) + " " + material.hardness_scale;
}

void add_tool_differences(const ToolRecord& tool, const ToolRecord& model_tool, ModelBorrowing& out) {
  if (tool.diameter_mm != model_tool.diameter_mm) {
    out.differences.push_back({"diameter", shortest_number_text(tool.diameter_mm) + " mm",
                               shortest_number_text(model_tool.diameter_mm) + " mm",
                               relative_difference(tool.diameter_mm, model_tool.diameter_mm)});
  }
  if (tool.flutes != model_tool.flutes) {
    out.differences.push_back({"flutes", std::to_string(tool.flutes), std::to_string(model_tool.flutes),
                               relative_difference(tool.flutes, model_tool.flutes)});
  }
  if (tool.helix_deg != model_tool.helix_deg) {
    out.differences.push_back({"helix", shortest_number_text(tool.helix_deg) + "°",
                               shortest_number_text(model_tool.helix_deg) + "°",
                               kHelixRelativePer30Deg * std::abs(tool.helix_deg - model_tool.helix_deg) / 30.0});
  }
}

void add_material_differences(const MaterialRecord& material, const MaterialRecord& model_material, ModelBorrowing& out) {
  if (material.name == model_material.name) return;
  out.differences.push_back({"material", material.name, model_material.name, 0.0});
  if (material.iso_group != model_material.iso_group) {
    out.differences.push_back({"ISO group", to_string(material.iso_group), to_string(model_material.iso_group),
                               kOtherIsoGroupRelative});
    return;
  }
  const double hardness = material.hardness_scale == model_material.hardness_scale
                              ? relative_difference(material.hardness_value, model_material.hardness_value)
                              : kUnknownHardnessRelative;
  out.differences.push_back({"hardness", hardness_text(material), hardness_text(model_material),
                             std::max(hardness, kOtherMaterialRelative)});
}

ModelBorrowing finish(ModelBorrowing out) {
  out.status = out.differences.empty() ? ModelMatchStatus::kExact : ModelMatchStatus::kBorrowed;
  for (const ModelDifference& d : out.differences) out.borrowed_fraction += d.relative;
  return out;
}

}  // namespace

std::string to_string(ModelMatchStatus status) { return status == ModelMatchStatus::kExact ? "exact" : "borrowed"; }

ModelBorrowing model_borrowing(const ToolRecord& tool, const MaterialRecord& material, const ToolRecord& model_tool,
                               const MaterialRecord& model_material) {
  ModelBorrowing out;
  add_tool_differences(tool, model_tool, out);
  add_material_differences(material, model_material, out);
  return finish(std::move(out));
}

ModelBorrowing model_borrowing(const ToolRecord& tool, const UnknownMaterial& material, const ToolRecord& model_tool,
                               const MaterialRecord& model_material) {
  ModelBorrowing out;
  add_tool_differences(tool, model_tool, out);
  if (material.name != model_material.name) {
    out.differences.push_back({"material", material.name + " (not in the database: hardness and ISO group unknown)",
                               model_material.name + " (" + hardness_text(model_material) + ", ISO " +
                                   to_string(model_material.iso_group) + ")",
                               kUnknownHardnessRelative});
  }
  return finish(std::move(out));
}

std::string describe(const ModelBorrowing& borrowing) {
  if (borrowing.status == ModelMatchStatus::kExact) return "exact";
  std::string text = "borrowed:";
  const char* separator = " ";
  for (const ModelDifference& d : borrowing.differences) {
    text += separator + d.property + " " + d.used + " for " + d.wanted;
    if (d.relative > 0.0) {
      char percent[32];
      std::snprintf(percent, sizeof percent, " (%.0f %%)", 100.0 * d.relative);
      text += percent;
    }
    separator = ", ";
  }
  return text;
}

}  // namespace feedplan::model_db
