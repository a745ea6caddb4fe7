#include "feedplan/planner/force_bound.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/model/model_prediction.hpp"

namespace feedplan::planner {

double force_standard_deviation_n(const model::ResponseSurfaceModel& model, const ForceUncertainty& uncertainty,
                                  double chip_mm, double contact_length_mm) {
  const std::array<double, 6> psi = model::regressors(model, chip_mm, contact_length_mm);
  double variance = 0.0;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) variance += psi[i] * uncertainty.covariance[static_cast<std::size_t>(6 * i + j)] * psi[j];
  }
  const double relative_n = uncertainty.relative * model::predict(model, chip_mm, contact_length_mm).force_n;
  return std::sqrt(std::max(variance, 0.0) + relative_n * relative_n);
}

}  // namespace feedplan::planner
