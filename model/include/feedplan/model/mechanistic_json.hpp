#pragma once
// The mechanistic model as JSON: the one writer and reader of its members, shared by the model database's
// exchange file (model_db/model_exchange.hpp) and the plan report (planner/plan_report.hpp). The members,
// in this order:
//   ktc_n_per_mm2, krc_n_per_mm2, kac_n_per_mm2, kte_n_per_mm, kre_n_per_mm, kae_n_per_mm, size_exponent,
//   size_reference_chip_mm, size_min_chip_mm, runout_mm [one per flute, or empty], helix_deg (null: the
//   cutter's)
// Numbers are written so that they read back as the same double; a non-finite number as null, read back
// as a problem.

#include <nlohmann/json.hpp>

#include "feedplan/core/json_fields.hpp"
#include "feedplan/model/mechanistic_model.hpp"

namespace feedplan::model {

//! The model's members as a JSON object, in the order above (a caller adds its own after them).
nlohmann::ordered_json to_json(const MechanisticModel& model);

//! Reads a model from the members of the object at `node`. Every problem goes to the node's reader,
//! named by the member's path ("models[3].mechanistic.ktc_n_per_mm2 is missing"); checks the JSON types
//! only: validate() checks the numbers. `Json` is nlohmann::json or nlohmann::ordered_json.
template <typename Json>
MechanisticModel read_mechanistic_json(const JsonNode<Json>& node);

extern template MechanisticModel read_mechanistic_json(const JsonNode<nlohmann::json>& node);
extern template MechanisticModel read_mechanistic_json(const JsonNode<nlohmann::ordered_json>& node);

}  // namespace feedplan::model
