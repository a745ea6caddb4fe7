#include "feedplan/planner/force_bound.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/model/model_prediction.hpp"

namespace feedplan::planner {

double force_standard_deviation_n(const model::ResponseSurfaceModel& model, const ForceUncertainty& uncertainty,
                                  double chip_mm, double contact_length_mm) {
  const std::array<double, 6> psi = model::regressors(model, chip_mm, contact_length_mm);
  const double variance = uncertainty.covariance.quadratic_form(psi);
  const double relative_n = uncertainty.relative * model::predict(model, chip_mm, contact_length_mm).force_n;
  return std::sqrt(std::max(variance, 0.0) + relative_n * relative_n);
}

}  // namespace feedplan::planner
