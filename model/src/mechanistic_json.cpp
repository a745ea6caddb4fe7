#include "feedplan/model/mechanistic_json.hpp"

#include <cmath>

namespace feedplan::model {
namespace {

using Json = nlohmann::ordered_json;

// A non-finite number as null, explicitly (see the file comment).
Json json_number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

}  // namespace

Json to_json(const MechanisticModel& m) {
  Json runout = Json::array();
  for (const double r : m.runout_mm) runout.push_back(json_number(r));
  return Json{{"ktc_n_per_mm2", json_number(m.ktc_n_per_mm2)},
              {"krc_n_per_mm2", json_number(m.krc_n_per_mm2)},
              {"kac_n_per_mm2", json_number(m.kac_n_per_mm2)},
              {"kte_n_per_mm", json_number(m.kte_n_per_mm)},
              {"kre_n_per_mm", json_number(m.kre_n_per_mm)},
              {"kae_n_per_mm", json_number(m.kae_n_per_mm)},
              {"size_exponent", json_number(m.size_exponent)},
              {"size_reference_chip_mm", json_number(m.size_reference_chip_mm)},
              {"size_min_chip_mm", json_number(m.size_min_chip_mm)},
              {"runout_mm", std::move(runout)},
              {"helix_deg", m.helix_deg ? json_number(*m.helix_deg) : Json(nullptr)}};
}

template <typename Document>
MechanisticModel read_mechanistic_json(const JsonNode<Document>& node) {
  MechanisticModel m;
  m.ktc_n_per_mm2 = node.number("ktc_n_per_mm2");
  m.krc_n_per_mm2 = node.number("krc_n_per_mm2");
  m.kac_n_per_mm2 = node.number("kac_n_per_mm2");
  m.kte_n_per_mm = node.number("kte_n_per_mm");
  m.kre_n_per_mm = node.number("kre_n_per_mm");
  m.kae_n_per_mm = node.number("kae_n_per_mm");
  m.size_exponent = node.number("size_exponent");
  m.size_reference_chip_mm = node.number("size_reference_chip_mm");
  m.size_min_chip_mm = node.number("size_min_chip_mm");
  m.runout_mm = node.numbers("runout_mm");
  const Document* helix = node.member("helix_deg", JsonPresence::kOptional);
  if (helix != nullptr && !helix->is_null()) m.helix_deg = node.number("helix_deg");
  return m;
}

template MechanisticModel read_mechanistic_json(const JsonNode<nlohmann::json>& node);
template MechanisticModel read_mechanistic_json(const JsonNode<nlohmann::ordered_json>& node);

}  // namespace feedplan::model
