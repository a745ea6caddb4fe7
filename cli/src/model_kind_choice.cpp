#include "model_kind_choice.hpp"

#include <cmath>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/model_db/engagement_groups.hpp"

namespace feedplan::cli {

namespace mdb = feedplan::model_db;

namespace {

// Contact lengths within this fraction of the fitted range's ends count as inside it.
constexpr double kContactLengthMargin = 0.05;

std::string one_decimal(double v) { return shortest_number_text(std::round(v * 10) / 10); }

// The mechanistic version that can plan for `surface`'s material: the one of `surface`'s tool, else the one
// whose tool is nearest `tool` in diameter (the cutting mechanics transfer between cutters of one material);
// with its tested tool.
struct MechanisticCandidate {
  mdb::ModelRecord record;
  std::optional<mdb::ToolRecord> tested;
};

std::optional<MechanisticCandidate> find_mechanistic(const mdb::Store& store, const mdb::ModelRecord& surface,
                                                     const geometry::Tool& tool) {
  if (std::optional<mdb::ModelRecord> own =
          store.active_model(surface.tool_name, surface.material_name, mdb::ModelKind::kMechanistic)) {
    return MechanisticCandidate{std::move(*own), store.find_tool(surface.tool_name)};
  }
  std::optional<MechanisticCandidate> nearest;
  for (const mdb::ToolRecord& t : store.tools()) {
    std::optional<mdb::ModelRecord> m = store.active_model(t.name, surface.material_name, mdb::ModelKind::kMechanistic);
    if (!m) continue;
    if (!nearest || std::abs(t.diameter_mm - tool.diameter_mm) < std::abs(nearest->tested->diameter_mm - tool.diameter_mm)) {
      nearest = MechanisticCandidate{std::move(*m), t};
    }
  }
  return nearest;
}

// True when the mechanistic version was identified on a cutter other than `tool`.
bool other_cutter(const MechanisticCandidate& m, const geometry::Tool& tool) {
  const model::MechanisticModel& model = m.record.mechanistic->model;
  if (!model.runout_mm.empty() && model.runout_mm.size() != static_cast<std::size_t>(tool.flutes)) return true;
  if (!m.tested) return true;
  return std::abs(m.tested->diameter_mm - tool.diameter_mm) > 1e-9 || m.tested->flutes != tool.flutes ||
         std::abs(m.tested->helix_deg - tool.helix_deg) > 1e-9;
}

// δ of the material: the chosen model's differences other than the cutter's.
double material_borrowed_fraction(const mdb::ModelBorrowing& borrowing) {
  double fraction = 0.0;
  for (const mdb::ModelDifference& d : borrowing.differences) {
    if (d.property != "diameter" && d.property != "flutes" && d.property != "helix") fraction += d.relative;
  }
  return fraction;
}

// `choice` planning with `m` for `tool` (`chosen`'s material); returns the words saying how it was fitted to
// the cutter ("" when identified on this cutter).
std::string plan_mechanistic(const ChosenModel& chosen, const geometry::Tool& tool, MechanisticCandidate m,
                             ModelKindChoice& choice) {
  const bool other = other_cutter(m, tool);
  const double scale = m.tested && m.tested->diameter_mm > 0.0 ? tool.diameter_mm / m.tested->diameter_mm : 1.0;
  choice.max_chip_thickness_mm = m.record.model.range.chip_max_mm * scale;
  choice.borrowed_fraction = material_borrowed_fraction(chosen.borrowing) + (other ? kOtherCutterRelative : 0.0);
  std::string words;
  if (other) {
    model::MechanisticModel& model = m.record.mechanistic->model;
    model.runout_mm.clear();
    model.helix_deg.reset();
    words = "; identified on " + m.record.tool_name + ": its cutting and edge coefficients, with this cutter's helix " +
            shortest_number_text(tool.helix_deg) + "° and no runout";
  }
  choice.mechanistic = std::move(m.record);
  return words;
}

}  // namespace

double planning_uncertainty(const ModelKindChoice& kind, std::optional<double> requested) {
  return requested ? *requested : kind.borrowed_fraction / kBorrowedModelSigmas;
}

double extrapolated_contact_share(const model::ResponseSurfaceModel& surface, const geometry::EngagementProfile& engagement) {
  const double low = surface.range.contact_length_min_mm * (1.0 - kContactLengthMargin);
  const double high = surface.range.contact_length_max_mm * (1.0 + kContactLengthMargin);
  std::size_t engaged = 0, outside = 0;
  for (const geometry::EngagementSample& s : engagement.samples) {
    if (!s.cutting || !(s.engagement_rad > 0.0)) continue;
    ++engaged;
    if (s.contact_length_mm < low || s.contact_length_mm > high) ++outside;
  }
  return engaged == 0 ? 0.0 : static_cast<double>(outside) / static_cast<double>(engaged);
}

ModelKindChoice choose_model_kind(const mdb::Store& store, const ChosenModel& chosen, const geometry::Tool& tool,
                                  const std::string& requested, std::optional<double> extrapolated_share) {
  if (!requested.empty() && requested != "mechanistic" && requested != "response-surface") {
    throw InputError("--model-kind", "= '" + requested + "': must be mechanistic or response-surface");
  }
  const mdb::ModelRecord& surface = chosen.record;
  ModelKindChoice choice;
  choice.borrowed_fraction = chosen.borrowing.borrowed_fraction;
  if (requested == "response-surface") {
    choice.reason = "response surface, as asked (--model-kind)";
    return choice;
  }
  std::optional<MechanisticCandidate> mechanistic = find_mechanistic(store, surface, tool);
  if (requested == "mechanistic") {
    if (!mechanistic) {
      throw InputError("--model-kind", "= mechanistic: no tool has a mechanistic version in " + surface.material_name +
                                           " (fit one: feedplan db fit --kind mechanistic)");
    }
    const int version = mechanistic->record.version;
    const std::string cutter = plan_mechanistic(chosen, tool, std::move(*mechanistic), choice);
    choice.reason = "mechanistic v" + std::to_string(version) + ", as asked (--model-kind)" + cutter;
    return choice;
  }
  if (!mechanistic) {
    choice.reason = "response surface: no tool has a mechanistic version in " + surface.material_name;
    return choice;
  }
  const bool same_tool = mechanistic->record.tool_name == surface.tool_name;
  const std::string versions = " (response surface v" + std::to_string(surface.version) +
                               (same_tool ? "" : " of " + surface.tool_name) + ", mechanistic v" +
                               std::to_string(mechanistic->record.version) +
                               (same_tool ? "" : " of " + mechanistic->record.tool_name) + ")";
  if (extrapolated_share && *extrapolated_share > kExtrapolatedShareForMechanistic) {
    const auto& range = surface.model.range;
    const std::string cutter = plan_mechanistic(chosen, tool, std::move(*mechanistic), choice);
    choice.reason = "mechanistic: the path's contact lengths leave the response surface's fitted " +
                    one_decimal(range.contact_length_min_mm) + "–" + one_decimal(range.contact_length_max_mm) +
                    " mm at " + one_decimal(100.0 * *extrapolated_share) +
                    " % of its engaged samples, where the cutting mechanics still hold" + versions + cutter;
    return choice;
  }
  if (!same_tool) {
    choice.reason = std::string("response surface: ") +
                    (extrapolated_share ? "the path stays inside its fitted engagement, and " : "") +
                    "the mechanistic version" + versions + " is of another tool (--model-kind mechanistic plans with it)";
    return choice;
  }
  const double surface_n = surface.fit.engagement_cv_rmse_n, mechanistic_n = mechanistic->record.fit.engagement_cv_rmse_n;
  if (!(surface_n > 0.0 && mechanistic_n > 0.0)) {
    choice.reason = "response surface: the versions" + versions + " have no leave-one-engagement-out error to "
                    "compare the kinds by (fitted on fewer than " +
                    std::to_string(mdb::kMinCrossValidationEngagements) + " radial depths, or before feedplan "
                    "computed it: refit with feedplan db fit); --model-kind mechanistic plans with the cutting "
                    "mechanics";
    return choice;
  }
  const std::string figures = "leave-one-engagement-out error on the cutting tests " + one_decimal(mechanistic_n) +
                              " N mechanistic, " + one_decimal(surface_n) + " N response surface" + versions;
  if (mechanistic_n < surface_n) {
    const std::string cutter = plan_mechanistic(chosen, tool, std::move(*mechanistic), choice);
    choice.reason = "mechanistic, which predicts engagements it was not fitted on better: " + figures + cutter;
    return choice;
  }
  choice.reason = "response surface, which predicts engagements it was not fitted on better: " + figures;
  return choice;
}

}  // namespace feedplan::cli
