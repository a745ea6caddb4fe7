#pragma once
// Which stored model a command plans with: --model-id, else the closest active model for the spec's tool
// and material (model_db/closest_model.hpp), with the reason in words.

#include <cstdint>
#include <optional>
#include <string>

#include "feedplan/cycles/spec.hpp"
#include "feedplan/model_db/model_borrowing.hpp"
#include "feedplan/model_db/store.hpp"
#include "feedplan/model_db/store_records.hpp"
#include "feedplan/planner/force_bound.hpp"

namespace feedplan::cli {

//! The model chosen and why.
struct ChosenModel {
  model_db::ModelRecord record;  //!< the version used
  std::string match;             //!< to_string(ModelMatch) or "by id"
  std::string explanation;       //!< for people
  model_db::ModelBorrowing borrowing;  //!< exact or borrowed: what differs from the spec's tool and material
};

//! The model for `spec`: the version with `model_id` when given, else the closest active one (chosen for
//! the spec's tool values: a stored tool of the same name but another diameter is not an exact match).
//! Throws InputError for an unknown id or material (with the known names); returns nothing, after
//! printing why on stderr, when the database has no model that qualifies.
std::optional<ChosenModel> choose_model(const model_db::Store& store, const cycles::CycleSpec& spec, std::optional<std::int64_t> model_id);

//! The active mechanistic model of `tool_name` in `material_name` (its cutting tests' coefficients, size
//! effect, runout and helix), if the database has one: the force's shape a dynamometer correction may use
//! where the engagement is steady (learning::SensorKernel).
std::optional<model::MechanisticModel> sensor_kernel(const model_db::Store& store, const std::string& tool_name,
                                                     const std::string& material_name);

//! One line for people on the shape a dynamometer's factor is taken from, with or without `kernel`.
std::string describe_sensor_correction(const std::optional<model::MechanisticModel>& kernel);

//! z of the cautious bound F̂ + z·σ a borrowed model is planned on.
inline constexpr double kBorrowedModelSigmas = 2.0;

//! The cautious bound of a model `record` planned with relative uncertainty r > 0: F̂ + z·σ with its fit's
//! covariance and z = kBorrowedModelSigmas (planner/force_bound.hpp); nothing for r = 0.
std::optional<planner::ForceUncertainty> cautious_bound(const model_db::ModelRecord& record, double r);

//! The relative uncertainty r a plan holds F̂ + z·σ at the target with (planner/force_bound.hpp, z =
//! kBorrowedModelSigmas): `requested` (--cautious) when given, else δ / z with δ the fraction
//! the chosen model is borrowed by (model_db/model_borrowing.hpp; 0 for an exact model) — so the bound
//! is at least F̂·(1 + δ) and a model borrowed by δ cannot overshoot by more unseen.
double planning_uncertainty(const ChosenModel& chosen, std::optional<double> requested);

}  // namespace feedplan::cli
