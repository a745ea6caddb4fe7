#pragma once
// The response-surface model as JSON: the one writer and reader of its members, shared by the model
// database's exchange file (model_db/model_exchange.hpp) and the plan report (planner/plan_report.hpp).
// The members, in this order:
//   beta [β0, β1, β2, β11, β22, β12], chip_center_mm, chip_scale_mm, contact_length_center_mm,
//   contact_length_scale_mm, range {chip_min_mm, chip_max_mm, contact_length_min_mm,
//   contact_length_max_mm}, axial_depth_mm, spindle_rpm, quantity
// Numbers are written so that they read back as the same double. JSON has no NaN or infinity: a
// non-finite number is written as null (nlohmann would write null for it too), and read back as a
// problem.

#include <nlohmann/json.hpp>

#include "feedplan/core/json_fields.hpp"
#include "feedplan/model/response_surface_model.hpp"

namespace feedplan::model {

//! The model's members as a JSON object, in the order above. A caller that adds members of its own
//! (the plan report's model id, version, database) puts them first and appends these with update().
nlohmann::ordered_json to_json(const ResponseSurfaceModel& model);

//! The fitted range as its JSON object {chip_min_mm, chip_max_mm, contact_length_min_mm,
//! contact_length_max_mm}.
nlohmann::ordered_json to_json(const FittedRange& range);

//! Reads a model from the members of the object at `node` (those above; any other member is left to
//! the caller). Every problem goes to the node's reader, named by the member's path
//! ("models[3].model.beta[2] = null: must be a finite number", "model.range.chip_max_mm is missing");
//! a missing or ill-typed member reads as 0 or "". Checks the JSON types only: validate() checks the
//! numbers. `Json` is nlohmann::json or nlohmann::ordered_json.
template <typename Json>
ResponseSurfaceModel read_model_json(const JsonNode<Json>& node);

extern template ResponseSurfaceModel read_model_json(const JsonNode<nlohmann::json>& node);
extern template ResponseSurfaceModel read_model_json(const JsonNode<nlohmann::ordered_json>& node);

}  // namespace feedplan::model
