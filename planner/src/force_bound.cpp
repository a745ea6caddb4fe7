#include "feedplan/planner/force_bound.hpp"

#include <cassert>
#include <cmath>

#include "feedplan/model_db/model_prediction.hpp"

namespace feedplan::planner {

double force_standard_deviation_n(const model_db::ResponseSurfaceModel& model, const std::array<double, 36>& covariance,
                                  double chip_mm, double contact_length_mm) {
  const std::array<double, 6> psi = model_db::regressors(model, chip_mm, contact_length_mm);
  double variance = 0.0;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) variance += psi[i] * covariance[static_cast<std::size_t>(6 * i + j)] * psi[j];
  }
  return std::sqrt(std::max(variance, 0.0));
}

std::array<double, 36> transferred_covariance(const model_db::ResponseSurfaceModel& model,
                                              const std::array<double, 36>& fit_covariance, double relative_uncertainty) {
  assert(relative_uncertainty >= 0.0);
  std::array<double, 36> covariance = fit_covariance;
  for (std::size_t j = 0; j < 6; ++j) {
    const double sigma = relative_uncertainty * std::abs(model.beta[j]);
    covariance[7 * j] += sigma * sigma;
  }
  return covariance;
}

}  // namespace feedplan::planner
