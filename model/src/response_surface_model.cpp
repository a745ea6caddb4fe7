#include "feedplan/model/response_surface_model.hpp"

#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/problem_list.hpp"

namespace feedplan::model {
namespace {

//! A problem at `min_field` unless min_value ≤ max_value.
void check_ordered(ProblemList& problems, const ModelCheckOptions& options, const char* min_field, double min_value,
                   const char* max_field, double max_value) {
  if (min_value > max_value) {
    problems.add_value(min_field, shortest_number_text(min_value),
                       "must be ≤ " + options.bound_prefix + max_field + " = " + shortest_number_text(max_value));
  }
}

//! A problem unless the quantity is one the options accept.
void check_quantity(ProblemList& problems, const ModelCheckOptions& options, const std::string& quantity) {
  static const std::string known_quantity = ResponseSurfaceModel{}.quantity;
  if (options.quantity == QuantityRule::kAnyNamed) {
    if (quantity.empty()) problems.add_value("quantity", "''", "must name what the model predicts");
  } else if (quantity != known_quantity) {
    problems.add_value("quantity", "'" + quantity + "'", "must be '" + known_quantity + "'");
  }
}

}  // namespace

std::vector<InputProblem> validate(const ResponseSurfaceModel& model, const ModelCheckOptions& options) {
  ProblemList problems(options.field_prefix);
  for (std::size_t i = 0; i < model.beta.size(); ++i) {
    if (!std::isfinite(model.beta[i])) {
      problems.add_value("beta[" + std::to_string(i) + "]", shortest_number_text(model.beta[i]), "must be finite");
    }
  }
  problems.finite("chip_center_mm", model.chip_center_mm);
  problems.positive("chip_scale_mm", model.chip_scale_mm);
  problems.finite("contact_length_center_mm", model.contact_length_center_mm);
  problems.positive("contact_length_scale_mm", model.contact_length_scale_mm);
  const FittedRange& range = model.range;
  problems.non_negative("range.chip_min_mm", range.chip_min_mm);
  problems.non_negative("range.chip_max_mm", range.chip_max_mm);
  problems.non_negative("range.contact_length_min_mm", range.contact_length_min_mm);
  problems.non_negative("range.contact_length_max_mm", range.contact_length_max_mm);
  check_ordered(problems, options, "range.chip_min_mm", range.chip_min_mm, "range.chip_max_mm", range.chip_max_mm);
  check_ordered(problems, options, "range.contact_length_min_mm", range.contact_length_min_mm,
                "range.contact_length_max_mm", range.contact_length_max_mm);
  problems.non_negative("axial_depth_mm", model.axial_depth_mm);
  problems.non_negative("spindle_rpm", model.spindle_rpm);
  check_quantity(problems, options, model.quantity);
  return problems.take();
}

}  // namespace feedplan::model
