#include "feedplan/trial/correction_step.hpp"

#include <algorithm>
#include <cmath>

namespace feedplan::trial {

double next_force_correction(double c, double r, const CorrectionTry& previous) {
  const double proportional = c * r;
  if (!(previous.ratio > 0.0) || !(previous.correction > 0.0)) return proportional;
  const double d_ln_r = std::log(r / previous.ratio);
  const double d_ln_c = std::log(c / previous.correction);
  if (std::abs(d_ln_r) < kMinLogRatioChange || d_ln_c == 0.0) return proportional;
  const double sensitivity = -d_ln_r / d_ln_c;
  if (!(sensitivity > 0.0 && sensitivity < kFloorSensitivity)) return proportional;
  return c * std::exp(std::log(r) / std::max(sensitivity, kMinSensitivity));
}

}  // namespace feedplan::trial
