#include "feedplan/model/model_json.hpp"

#include <cmath>

namespace feedplan::model {
namespace {

using Json = nlohmann::ordered_json;

// A non-finite number as null, explicitly (see the file comment of model_json.hpp).
Json json_number(double value) { return std::isfinite(value) ? Json(value) : Json(nullptr); }

}  // namespace

Json to_json(const FittedRange& range) {
  return Json{{"chip_min_mm", json_number(range.chip_min_mm)},
              {"chip_max_mm", json_number(range.chip_max_mm)},
              {"contact_length_min_mm", json_number(range.contact_length_min_mm)},
              {"contact_length_max_mm", json_number(range.contact_length_max_mm)}};
}

Json to_json(const ResponseSurfaceModel& model) {
  Json beta = Json::array();
  for (const double b : model.beta) beta.push_back(json_number(b));
  return Json{{"beta", std::move(beta)},
              {"chip_center_mm", json_number(model.chip_center_mm)},
              {"chip_scale_mm", json_number(model.chip_scale_mm)},
              {"contact_length_center_mm", json_number(model.contact_length_center_mm)},
              {"contact_length_scale_mm", json_number(model.contact_length_scale_mm)},
              {"range", to_json(model.range)},
              {"axial_depth_mm", json_number(model.axial_depth_mm)},
              {"spindle_rpm", json_number(model.spindle_rpm)},
              {"quantity", model.quantity}};
}

template <typename Document>
ResponseSurfaceModel read_model_json(const JsonNode<Document>& node) {
  ResponseSurfaceModel model;
  model.beta = node.template fixed_numbers<6>("beta");
  model.chip_center_mm = node.number("chip_center_mm");
  model.chip_scale_mm = node.number("chip_scale_mm");
  model.contact_length_center_mm = node.number("contact_length_center_mm");
  model.contact_length_scale_mm = node.number("contact_length_scale_mm");
  const JsonNode<Document> range = node.object("range");
  model.range.chip_min_mm = range.number("chip_min_mm");
  model.range.chip_max_mm = range.number("chip_max_mm");
  model.range.contact_length_min_mm = range.number("contact_length_min_mm");
  model.range.contact_length_max_mm = range.number("contact_length_max_mm");
  model.axial_depth_mm = node.number("axial_depth_mm");
  model.spindle_rpm = node.number("spindle_rpm");
  model.quantity = node.text("quantity");
  return model;
}

template ResponseSurfaceModel read_model_json(const JsonNode<nlohmann::json>& node);
template ResponseSurfaceModel read_model_json(const JsonNode<nlohmann::ordered_json>& node);

}  // namespace feedplan::model
