#include "model_choice.hpp"

#include <iostream>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model_db/closest_model.hpp"

namespace feedplan::cli {

namespace mdb = model_db;

std::optional<ChosenModel> choose_model(const mdb::Store& store, const cycles::CycleSpec& spec, std::int64_t model_id) {
  if (model_id != 0) {
    auto record = store.model_by_id(model_id);
    if (!record) {
      throw InputError("--model-id", "= " + std::to_string(model_id) + ": no model with this id in " +
                                         store.path().string() + " (see feedplan db list)");
    }
    return ChosenModel{*record, "by id", "model id " + std::to_string(model_id) + " as asked (--model-id)"};
  }
  if (spec.material.empty()) throw InputError("material", "is required to choose a force model, e.g. material: S50C");
  const auto material = store.find_material(spec.material);
  if (!material) {
    std::string known;
    for (const auto& m : store.materials()) known += (known.empty() ? "" : ", ") + m.name;
    throw InputError("material", "= '" + spec.material + "': not in the model database " + store.path().string() +
                                     " (known: " + (known.empty() ? "none" : known) + ")");
  }
  mdb::ToolRecord tool;
  if (auto stored = store.find_tool(spec.tool.name)) {
    tool = *stored;
  } else {
    tool.name = spec.tool.name;
    tool.diameter_mm = spec.tool.diameter_mm;
    tool.flutes = spec.tool.flutes;
    tool.helix_deg = spec.tool.helix_deg;
  }
  const mdb::ClosestModel closest = mdb::closest_model(store, tool, *material);
  if (closest.status != mdb::ClosestModelStatus::kFound) {
    std::cerr << "feedplan: failed: no force model to plan with: " << closest.explanation << "\n"
              << "  add cutting tests and fit one (feedplan db import-test, feedplan db fit), or pass --model-id\n";
    return std::nullopt;
  }
  return ChosenModel{*closest.model, mdb::to_string(closest.match), closest.explanation};
}


}  // namespace feedplan::cli
