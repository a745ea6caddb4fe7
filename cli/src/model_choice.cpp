#include "model_choice.hpp"

#include <iostream>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/learning/sensor_dynamics.hpp"
#include "feedplan/model_db/closest_model.hpp"

namespace feedplan::cli {

namespace mdb = model_db;

namespace {

// The tool as the spec gives it: the model must fit these values, whatever the tool is called.
mdb::ToolRecord spec_tool(const cycles::CycleSpec& spec) {
  mdb::ToolRecord tool;
  tool.name = spec.tool.name;
  tool.diameter_mm = spec.tool.diameter_mm;
  tool.flutes = spec.tool.flutes;
  tool.helix_deg = spec.tool.helix_deg;
  return tool;
}

// How the model `record` fits the spec's tool (its values) and material (from the store, when known).
mdb::ModelBorrowing borrowing_of(const mdb::Store& store, const cycles::CycleSpec& spec, const mdb::ModelRecord& record) {
  const mdb::ToolRecord model_tool = *store.find_tool(record.tool_name);
  const mdb::MaterialRecord model_material = *store.find_material(record.material_name);
  if (const auto material = store.find_material(spec.material)) {
    return mdb::model_borrowing(spec_tool(spec), *material, model_tool, model_material);
  }
  return mdb::model_borrowing(spec_tool(spec), mdb::UnknownMaterial{spec.material}, model_tool, model_material);
}

std::optional<ChosenModel> model_by_id(const mdb::Store& store, const cycles::CycleSpec& spec, std::int64_t model_id) {
  auto record = store.model_by_id(model_id);
  if (!record) {
    throw InputError("--model-id", "= " + std::to_string(model_id) + ": no model with this id in " +
                                       store.path().string() + " (see feedplan db list)");
  }
  if (record->kind != mdb::ModelKind::kResponseSurface) {
    throw InputError("--model-id", "= " + std::to_string(model_id) + ": is a " + mdb::to_string(record->kind) +
                                       " version; plan takes a response-surface version (see feedplan db list)");
  }
  mdb::ModelBorrowing borrowing = borrowing_of(store, spec, *record);
  return ChosenModel{*record, "by id", "model id " + std::to_string(model_id) + " as asked (--model-id)",
                     std::move(borrowing)};
}

}  // namespace

std::optional<ChosenModel> choose_model(const mdb::Store& store, const cycles::CycleSpec& spec,
                                        std::optional<std::int64_t> model_id) {
  if (model_id) return model_by_id(store, spec, *model_id);
  if (spec.material.empty()) throw InputError("material", "is required to choose a force model, e.g. material: S50C");
  const auto material = store.find_material(spec.material);
  if (!material) {
    std::string known;
    for (const auto& m : store.materials()) known += (known.empty() ? "" : ", ") + m.name;
    throw InputError("material", "= '" + spec.material + "': not in the model database " + store.path().string() +
                                     " (known: " + (known.empty() ? "none" : known) + ")");
  }
  const mdb::ClosestModel closest = mdb::closest_model(store, spec_tool(spec), *material);
  if (closest.status != mdb::ClosestModelStatus::kFound) {
    std::cerr << "feedplan: failed: no force model to plan with: " << closest.explanation << "\n"
              << "  add cutting tests and fit one (feedplan db import-test, feedplan db fit), or pass --model-id\n";
    return std::nullopt;
  }
  mdb::ModelBorrowing borrowing = mdb::model_borrowing(spec_tool(spec), *material, closest.model_tool, closest.model_material);
  return ChosenModel{*closest.model, mdb::to_string(closest.match), closest.explanation, std::move(borrowing)};
}

double planning_uncertainty(const ChosenModel& chosen, std::optional<double> requested) {
  return requested ? *requested : chosen.borrowing.borrowed_fraction / kBorrowedModelSigmas;
}

std::optional<planner::ForceUncertainty> cautious_bound(const model_db::ModelRecord& record, double r) {
  if (!(r > 0.0)) return std::nullopt;
  planner::ForceUncertainty uncertainty;
  uncertainty.covariance = record.fit.covariance;
  uncertainty.sigmas = kBorrowedModelSigmas;
  uncertainty.relative = r;
  return uncertainty;
}

std::optional<model::MechanisticModel> sensor_kernel(const model_db::Store& store, const std::string& tool_name,
                                                     const std::string& material_name) {
  const std::optional<model_db::ModelRecord> record =
      store.active_model(tool_name, material_name, model_db::ModelKind::kMechanistic);
  if (!record || !record->mechanistic) return std::nullopt;
  return record->mechanistic->model;
}

std::string describe_sensor_correction(const std::optional<model::MechanisticModel>& kernel) {
  const std::string cap = shortest_number_text(learning::kMaxSensorPeakGain);
  return kernel ? "dynamometer correction: the chip's shape's factor, at most " + cap +
                      " — more where the engagement is steady and the mechanistic model's force gives more on every "
                      "machine it may be (helix ±" + shortest_number_text(learning::kKernelHelixDoubtDeg) +
                      "°, edge forces halved or doubled)"
                : "dynamometer correction: the chip's shape's factor, at most " + cap +
                      " (no mechanistic model of this tool and material in the database; with one, fitted from its "
                      "cutting tests by feedplan db fit --kind mechanistic, a steady cut read through a soft "
                      "dynamometer can take off more)";
}

}  // namespace feedplan::cli
