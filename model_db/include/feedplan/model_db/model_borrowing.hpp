#pragma once
// How far the model a plan uses is from the tool and material it plans for: the model match as a status.
// A model is exact when its tool has the diameter, flute count and helix asked for and its material is
// the one asked for; otherwise it is borrowed, and each property that differs is listed with both values
// and how far apart they are. closest_model.hpp chooses the model; this says what choosing it costs.
//
// How far a borrowed model can be off, as a fraction of its force (the `relative` of each difference):
//   - diameter and flute count: at a given chip thickness t_m and contact length L the force grows with
//     the number of teeth in the contact, Z·L/(π·D), so another D or Z changes it by the factor
//     D_a/D_b or Z_a/Z_b: relative = |a − b| / min(a, b) (a Ø10 model for a Ø8 tool: 0.25);
//   - helix: a small effect on the peak (the flute's engagement spreads over the rotation):
//     kHelixRelativePer30Deg per 30° of difference;
//   - another material of the same ISO group: the specific cutting force grows with hardness, at most in
//     proportion: relative = |H_a − H_b| / min(H_a, H_b) on one hardness scale (200 HB for 300 HB: 0.5),
//     kUnknownHardnessRelative when the scales differ or a hardness is not known, at least
//     kOtherMaterialRelative (another alloy of the same hardness still cuts differently);
//   - another ISO group (only when a model is chosen by id): kOtherIsoGroupRelative — forces differ by
//     several times between groups.
// The borrowed fraction δ is the sum of these (the factors compound; the sum is the first-order bound).

#include <string>
#include <vector>

#include "feedplan/model_db/store_records.hpp"

namespace feedplan::model_db {

//! Relative force difference per 30° of helix difference.
inline constexpr double kHelixRelativePer30Deg = 0.05;
//! Relative force difference of another material whose hardness cannot be compared.
inline constexpr double kUnknownHardnessRelative = 0.5;
//! Smallest relative force difference of another material of the same ISO group.
inline constexpr double kOtherMaterialRelative = 0.1;
//! Relative force difference of a material of another ISO group.
inline constexpr double kOtherIsoGroupRelative = 1.0;

//! "exact" or "borrowed".
enum class ModelMatchStatus {
  kExact,     //!< the model's tool and material are the ones asked for
  kBorrowed,  //!< some property differs (ModelBorrowing::differences)
};

//! "exact", "borrowed".
std::string to_string(ModelMatchStatus status);

//! One property in which the model's tool or material differs from the one asked for.
struct ModelDifference {
  std::string property;   //!< "diameter", "flutes", "helix", "hardness", "material" or "ISO group"
  std::string wanted;     //!< the value asked for, with its unit, e.g. "8 mm"
  std::string used;       //!< the model's value, e.g. "10 mm"
  double relative = 0.0;  //!< how far a force can be off for this difference, as a fraction (rule above)
};

//! The match of a model to a tool and material.
struct ModelBorrowing {
  ModelMatchStatus status = ModelMatchStatus::kExact;  //!< exact or borrowed
  std::vector<ModelDifference> differences;            //!< what differs (empty when exact)
  double borrowed_fraction = 0.0;                      //!< δ = Σ relative, the force the model may be off by
};

//! A material asked for that the store does not know (no hardness, no ISO group): the model's material
//! is then another material of unknown hardness.
struct UnknownMaterial {
  std::string name;  //!< as asked
};

//! The match of the model fitted for (`model_tool`, `model_material`) to `tool` in `material`, by the
//! rule at the top of this file. Never fails.
ModelBorrowing model_borrowing(const ToolRecord& tool, const MaterialRecord& material, const ToolRecord& model_tool,
                               const MaterialRecord& model_material);

//! The same when the material asked for is not in the store.
ModelBorrowing model_borrowing(const ToolRecord& tool, const UnknownMaterial& material, const ToolRecord& model_tool,
                               const MaterialRecord& model_material);

//! "exact", or "borrowed: diameter 10 mm for 8 mm (25 %), hardness 200 HB for 300 HB (50 %)" — each
//! difference as the model's value for the one asked for, with its relative force difference.
std::string describe(const ModelBorrowing& borrowing);

}  // namespace feedplan::model_db
