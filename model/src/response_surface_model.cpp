#include "feedplan/model/response_surface_model.hpp"

#include <cmath>
#include <string>

#include "feedplan/core/number_text.hpp"

namespace feedplan::model {
namespace {

//! Collects problems as "<prefix><field> = <value>: <rule>"; field names are built only on failure.
class ModelProblems {
 public:
  explicit ModelProblems(const ModelCheckOptions& options) : options_(options) {}

  void add(const std::string& field, const std::string& value_text, const std::string& rule) {
    list_.push_back({options_.field_prefix + field, "= " + value_text + ": " + rule});
  }
  void finite(const char* field, double value) {
    if (!std::isfinite(value)) add(field, shortest_number_text(value), "must be finite");
  }
  void positive(const char* field, double value) {
    if (!std::isfinite(value) || value <= 0.0) add(field, shortest_number_text(value), "must be finite and > 0");
  }
  void non_negative(const char* field, double value) {
    if (!std::isfinite(value) || value < 0.0) add(field, shortest_number_text(value), "must be finite and ≥ 0");
  }
  void ordered(const char* min_field, double min_value, const char* max_field, double max_value) {
    if (min_value > max_value) {
      add(min_field, shortest_number_text(min_value),
          "must be ≤ " + options_.bound_prefix + max_field + " = " + shortest_number_text(max_value));
    }
  }
  void quantity(const std::string& quantity) {
    static const std::string known_quantity = ResponseSurfaceModel{}.quantity;
    if (options_.quantity == QuantityRule::kAnyNamed) {
      if (quantity.empty()) add("quantity", "''", "must name what the model predicts");
    } else if (quantity != known_quantity) {
      add("quantity", "'" + quantity + "'", "must be '" + known_quantity + "'");
    }
  }
  std::vector<InputProblem> take() { return std::move(list_); }

 private:
  const ModelCheckOptions& options_;
  std::vector<InputProblem> list_;
};

}  // namespace

std::vector<InputProblem> validate(const ResponseSurfaceModel& model, const ModelCheckOptions& options) {
  ModelProblems problems(options);
  for (std::size_t i = 0; i < model.beta.size(); ++i) {
    if (!std::isfinite(model.beta[i])) {
      problems.add("beta[" + std::to_string(i) + "]", shortest_number_text(model.beta[i]), "must be finite");
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
  problems.ordered("range.chip_min_mm", range.chip_min_mm, "range.chip_max_mm", range.chip_max_mm);
  problems.ordered("range.contact_length_min_mm", range.contact_length_min_mm, "range.contact_length_max_mm",
                   range.contact_length_max_mm);
  problems.non_negative("axial_depth_mm", model.axial_depth_mm);
  problems.non_negative("spindle_rpm", model.spindle_rpm);
  problems.quantity(model.quantity);
  return problems.take();
}

}  // namespace feedplan::model
