#include "feedplan/model/model_prediction.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace feedplan::model {
namespace {

//! Outside [min, max] by more than kRangeRelativeTolerance · max(|min|, |max|); NaN is outside.
bool outside(double value, double min_value, double max_value) {
  const double tolerance = kRangeRelativeTolerance * std::max(std::abs(min_value), std::abs(max_value));
  return !(value >= min_value - tolerance && value <= max_value + tolerance);
}

}  // namespace

std::array<double, 6> regressors(const ResponseSurfaceModel& model, double chip_mm, double contact_length_mm) {
  assert(model.chip_scale_mm > 0.0 && model.contact_length_scale_mm > 0.0);
  const double x1 = (chip_mm - model.chip_center_mm) / model.chip_scale_mm;
  const double x2 = (contact_length_mm - model.contact_length_center_mm) / model.contact_length_scale_mm;
  return {1.0, x1, x2, x1 * x1, x2 * x2, x1 * x2};
}

bool chip_outside(const FittedRange& range, double chip_mm) {
  return outside(chip_mm, range.chip_min_mm, range.chip_max_mm);
}

bool contact_length_outside(const FittedRange& range, double contact_length_mm) {
  return outside(contact_length_mm, range.contact_length_min_mm, range.contact_length_max_mm);
}

ForcePrediction predict(const ResponseSurfaceModel& model, double chip_mm, double contact_length_mm) {
  const std::array<double, 6> psi = regressors(model, chip_mm, contact_length_mm);
  ForcePrediction prediction;
  for (std::size_t i = 0; i < psi.size(); ++i) prediction.force_n += model.beta[i] * psi[i];
  prediction.chip_outside = chip_outside(model.range, chip_mm);
  prediction.contact_length_outside = contact_length_outside(model.range, contact_length_mm);
  return prediction;
}

}  // namespace feedplan::model
