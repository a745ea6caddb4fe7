#pragma once
// Choosing the model to plan with when the store may have none for exactly this tool in this material:
// the closest active model by a documented rule, with the reason in words, so the planner can say
// what it used ("no model for Ø8 3-flute in S50C; using Ø10 4-flute in S50C (same material, …)").
//
// The rule. Only active versions are candidates. Candidates fall into tiers, and any candidate of a
// better tier wins over every candidate of a worse one, whatever their distances:
//   1. kExact                   — the tool and the material asked for;
//   2. kSameMaterialOtherTool   — the material asked for, another tool;
//   3. kSameIsoGroupExactTool   — the tool asked for, another material of the same ISO 513 group;
//   4. kSameIsoGroupOtherTool   — another tool, another material of the same ISO group.
// A model for a material of another ISO group is never offered: cutting forces differ by several
// times between groups (aluminium vs titanium), so such a plan would be wrong, not approximate.
// Inside a tier the smallest distance wins (ties: tool name, then material name):
//
//   distance = tool_distance + material_distance
//   tool_distance = |D_a − D_b| / max(D_a, D_b)                  (diameter, relative; weight 1)
//                 + kFluteMismatchWeight · [Z_a ≠ Z_b]           (0.3: the same flute count is preferred)
//                 + kHelixWeight · |β_a − β_b| / 30°             (0.1 per 30° of helix difference)
//   material_distance = 0                                        (same material)
//                     = |H_a − H_b| / max(H_a, H_b)              (same ISO group, same hardness scale)
//                     = kUnknownHardnessDistance                 (same ISO group, different scales: 0.5)
//
// So a Ø10 4-flute tool stands in for a Ø8 3-flute one at 0.2 + 0.3 = 0.5, a Ø6 3-flute one at 0.25.

#include <optional>
#include <string>
#include <string_view>

#include "feedplan/model_db/store.hpp"
#include "feedplan/model_db/store_records.hpp"

namespace feedplan::model_db {

//! Weight of a different flute count in the tool distance.
inline constexpr double kFluteMismatchWeight = 0.3;
//! Weight of the helix difference, per 30° of difference.
inline constexpr double kHelixWeight = 0.1;
//! Material distance when two materials of one ISO group give hardness on different scales.
inline constexpr double kUnknownHardnessDistance = 0.5;

//! How the chosen model relates to the tool and material asked for (best first).
enum class ModelMatch {
  kExact,                  //!< this tool in this material
  kSameMaterialOtherTool,  //!< this material, the nearest other tool
  kSameIsoGroupExactTool,  //!< this tool, the nearest material of the same ISO group
  kSameIsoGroupOtherTool,  //!< the nearest tool and material of the same ISO group
};

//! "exact", "same material, other tool", …
std::string to_string(ModelMatch match);

//! Whether a model was found.
enum class ClosestModelStatus {
  kFound,    //!< `model` holds the model to use
  kNoModel,  //!< no active model qualifies (the store is empty, or has models only for other ISO groups)
};

//! The outcome of closest_model().
struct ClosestModel {
  ClosestModelStatus status = ClosestModelStatus::kNoModel;  //!< found or not
  std::optional<ModelRecord> model;        //!< the active version chosen (when found)
  ModelMatch match = ModelMatch::kExact;   //!< how it relates to the request (when found)
  double distance = 0.0;                   //!< tool_distance + material_distance (0 for kExact)
  ToolRecord model_tool;                   //!< the chosen model's tool (when found)
  MaterialRecord model_material;           //!< the chosen model's material (when found)
  //! One sentence for people: what was asked, what is used and why, or why nothing was found.
  std::string explanation;
};

//! The tool distance of the rule above (0 for the same geometry).
double tool_distance(const ToolRecord& wanted, const ToolRecord& candidate);

//! The material distance of the rule above, or nothing when the ISO groups differ.
std::optional<double> material_distance(const MaterialRecord& wanted, const MaterialRecord& candidate);

//! The closest active model for a tool and a material stored in `store`, by the rule above. Throws
//! InputError when the tool or material name is not in the store (with the known names). No model at
//! all is not an error: status kNoModel and an explanation.
ClosestModel closest_model(const Store& store, std::string_view tool_name, std::string_view material_name);

//! The same for a tool and material described by value (they need not be stored, e.g. a tool given in
//! a cycle spec); an exact match is by name.
ClosestModel closest_model(const Store& store, const ToolRecord& tool, const MaterialRecord& material);

}  // namespace feedplan::model_db
