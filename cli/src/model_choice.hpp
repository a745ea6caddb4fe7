#pragma once
// Which stored model a command plans with: --model-id, else the closest active model for the spec's tool
// and material (model_db/closest_model.hpp), with the reason in words.

#include <cstdint>
#include <optional>
#include <string>

#include "feedplan/cycles/spec.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/model_db/store_records.hpp"

namespace feedplan::cli {

//! The model chosen and why.
struct ChosenModel {
  model_db::ModelRecord record;  //!< the version used
  std::string match;             //!< to_string(ModelMatch) or "by id"
  std::string explanation;       //!< for people
};

//! The model for `spec`: the version with `model_id` when it is not 0, else the closest active one.
//! Throws InputError for an unknown id or material (with the known names); returns nothing, after
//! printing why on stderr, when the database has no model that qualifies.
std::optional<ChosenModel> choose_model(const model_db::Store& store, const cycles::CycleSpec& spec, std::int64_t model_id);

}  // namespace feedplan::cli
