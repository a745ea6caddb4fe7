#include "feedplan/model_db/stale_model_error.hpp"

#include <string>

namespace feedplan::model_db {
namespace {

// Built with append: GCC 12 warns falsely (-Wrestrict) on "v" + std::string when inlined.
std::string version_text(const ModelRecord& record) {
  std::string text = "v";
  return text.append(std::to_string(record.version)).append(" (id ").append(std::to_string(record.id)).append(")");
}

std::string stale_message(const ModelRecord& fitted_from, const ModelRecord& active) {
  const std::string pair = fitted_from.tool_name + " in " + fitted_from.material_name;
  std::string active_text = version_text(active);
  active_text.insert(active_text.size() - 1, ", " + to_string(active.source) + " " + active.created_at);
  return "learning from a plan made with " + pair + " " + version_text(fitted_from) + ", but " + active_text +
         " is the active version now: another learning step or a rollback stored it since. Nothing was stored — "
         "filing this refit as the child of v" + std::to_string(active.version) + " would hide that it never saw what v" +
         std::to_string(active.version) + " holds. Learn from parts cut with the plan of v" +
         std::to_string(active.version) + ", or make v" + std::to_string(fitted_from.version) +
         " active again first (feedplan db rollback --tool \"" + fitted_from.tool_name + "\" --material \"" +
         fitted_from.material_name + "\" --version " + std::to_string(fitted_from.version) + "; v" +
         std::to_string(active.version) + " stays in the history) and run learn again";
}

}  // namespace

StaleModelError::StaleModelError(const ModelRecord& fitted_from, const ModelRecord& active)
    : std::runtime_error(stale_message(fitted_from, active)), fitted_from_(fitted_from), active_(active) {}

}  // namespace feedplan::model_db
