#pragma once
// The four coefficients identification fits, K_tc, K_rc, K_te, K_re (private to the model module): writing
// them into a model, and the gradient of a predicted peak |F_xy| in them (shared by the prediction interval
// and the peak matching).

#include <array>
#include <cmath>

#include "feedplan/model/mechanistic_force.hpp"

namespace feedplan::model::detail {

//! The columns of ForceRegressors::rows of K_tc, K_rc, K_te, K_re.
inline constexpr int kIdentifiedColumns[4] = {kKtc, kKrc, kKte, kKre};

//! `model` with K_tc, K_rc, K_te, K_re from k(0) … k(3) (any vector indexable by ()).
template <class Vector>
void set_identified_coefficients(MechanisticModel& model, const Vector& k) {
  model.ktc_n_per_mm2 = k(0);
  model.krc_n_per_mm2 = k(1);
  model.kte_n_per_mm = k(2);
  model.kre_n_per_mm = k(3);
}

//! ∂|F_xy|/∂(K_tc, K_rc, K_te, K_re) = uᵀR at one spindle angle: R the XY regressor rows there (`row_x`,
//! `row_y`, MechanisticCoefficient columns), u the unit XY force of `model` there. Zero with no force.
inline std::array<double, 4> peak_gradient(const std::array<double, 6>& row_x, const std::array<double, 6>& row_y,
                                           const MechanisticModel& model) {
  const std::array<double, 6> k = coefficients(model);
  double fx_n = 0.0, fy_n = 0.0;
  for (int c = 0; c < 6; ++c) {
    fx_n += row_x[c] * k[c];
    fy_n += row_y[c] * k[c];
  }
  const double magnitude_n = std::hypot(fx_n, fy_n);
  std::array<double, 4> g{};
  if (!(magnitude_n > 0.0)) return g;
  for (int i = 0; i < 4; ++i) {
    g[i] = (fx_n * row_x[kIdentifiedColumns[i]] + fy_n * row_y[kIdentifiedColumns[i]]) / magnitude_n;
  }
  return g;
}

}  // namespace feedplan::model::detail
