#include "learning_pair.hpp"

#include <cmath>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::cli {
namespace {

std::string quoted(const std::string& text) { return "\"" + text + "\""; }

std::string tool_text(double diameter_mm, int flutes, double helix_deg) {
  return "Ø" + shortest_number_text(diameter_mm) + " " + std::to_string(flutes) + "-flute " +
         shortest_number_text(helix_deg) + "° helix";
}

// The spec's tool as registered; InputError with the way to register it when it is not, or differs.
void require_spec_tool(const model_db::Store& store, const std::string& db_path, const cycles::CycleSpec& spec,
                       const std::string& borrowed_from) {
  const geometry::Tool& tool = spec.tool;
  const auto registered = store.find_tool(tool.name);
  const std::string spec_tool = tool_text(tool.diameter_mm, tool.flutes, tool.helix_deg);
  if (!registered) {
    throw InputError("tool.name", "= " + quoted(tool.name) + ": the plan borrowed the model of " + borrowed_from +
                                      "; what is learned from this tool's cut is filed under the tool itself, which " +
                                      db_path + " does not have. Register it, then learn again: feedplan db add-tool " +
                                      quoted(tool.name) + " --diameter-mm " + shortest_number_text(tool.diameter_mm) +
                                      " --flutes " + std::to_string(tool.flutes) + " --helix-deg " +
                                      shortest_number_text(tool.helix_deg) + " --db " + db_path);
  }
  const bool same = std::abs(registered->diameter_mm - tool.diameter_mm) < 1e-9 && registered->flutes == tool.flutes &&
                    std::abs(registered->helix_deg - tool.helix_deg) < 1e-9;
  if (!same) {
    throw InputError("tool.name", "= " + quoted(tool.name) + ": the spec's tool is a " + spec_tool + ", but " + db_path +
                                      " has that name for a " +
                                      tool_text(registered->diameter_mm, registered->flutes, registered->helix_deg) +
                                      ", whose model the plan borrowed; give the spec's tool a name of its own "
                                      "(tool.name), register it with feedplan db add-tool, and plan and cut again");
  }
}

void require_spec_material(const model_db::Store& store, const std::string& db_path, const cycles::CycleSpec& spec,
                           const std::string& borrowed_from) {
  if (store.find_material(spec.material)) return;
  throw InputError("material", "= " + quoted(spec.material) + ": the plan borrowed the model of " + borrowed_from +
                                   "; what is learned from this cut is filed under the spec's material, which " + db_path +
                                   " does not have. Register it with its ISO group and hardness, then learn again: "
                                   "feedplan db add-material " + quoted(spec.material) +
                                   " --iso-group P|M|K|N|S|H --hardness \"<value> HB\" --db " + db_path);
}

}  // namespace

LearningPair learning_pair(const model_db::Store& store, const std::string& db_path, const cycles::CycleSpec& spec,
                           const model_db::ModelRecord& planned, const std::string& match_status) {
  const bool own_pair = planned.tool_name == spec.tool.name && planned.material_name == spec.material;
  const bool borrowed = match_status == "borrowed" || (match_status.empty() && !own_pair);
  if (!borrowed) return {planned.tool_name, planned.material_name, false};
  const std::string borrowed_from =
      planned.tool_name + " in " + planned.material_name + " v" + std::to_string(planned.version);
  // A spec tool named like the model's but of another geometry is refused here: its name is taken.
  require_spec_tool(store, db_path, spec, borrowed_from);
  require_spec_material(store, db_path, spec, borrowed_from);
  return {spec.tool.name, spec.material, true};
}

}  // namespace feedplan::cli
