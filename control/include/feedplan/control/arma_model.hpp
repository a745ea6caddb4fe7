#pragma once
// The plant model of seed 002 (Kim & Kim 1996, Eq. 17): the per-revolution cutting force f_c answers the
// feed command v_c, both sampled once per spindle revolution, as a second-order ARMA model
//
//   f_c(t) + φ1 f_c(t−1) + φ2 f_c(t−2) = θ0 v_c(t−1) + θ1 v_c(t−2),
//
// written f_c(t) = φ_m(t−1)ᵀ θ_p (Eq. 21) with θ_p = (φ1, φ2, θ0, θ1) and the regressor
// φ_m(t−1) = (−f_c(t−1), −f_c(t−2), v_c(t−1), v_c(t−2)). In the z-domain f_c = B(z)/A(z) v_c with
// A(z) = z² + φ1 z + φ2 and B(z) = θ0 z + θ1. Forces in N, feeds in mm/min, so θ0 and θ1 are in N per
// mm/min and φ1, φ2 have no unit.

#include <array>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! θ_p of Eq. 21.
struct ArmaModel {
  double phi1 = 0.0;    //!< φ1, dimensionless
  double phi2 = 0.0;    //!< φ2, dimensionless
  double theta0 = 0.0;  //!< θ0, N per mm/min: the force one sample after a unit feed command
  double theta1 = 0.0;  //!< θ1, N per mm/min
};

//! θ_p as an array in Eq. 21's order (φ1, φ2, θ0, θ1).
inline std::array<double, 4> parameter_vector(const ArmaModel& model) {
  return {model.phi1, model.phi2, model.theta0, model.theta1};
}

//! The regressor φ_m(t−1) = (−f(t−1), −f(t−2), v(t−1), v(t−2)) of Eq. 21.
inline std::array<double, 4> arma_regressor(double force_1_n, double force_2_n, double feed_1_mm_per_min,
                                            double feed_2_mm_per_min) {
  return {-force_1_n, -force_2_n, feed_1_mm_per_min, feed_2_mm_per_min};
}

//! Every problem with the model, each named "<field_prefix><field>" ("arma.theta0 = nan: must be finite").
//! Every coefficient must be finite and θ0, θ1 not both 0 (the feed must reach the force). Empty when usable.
std::vector<InputProblem> validate(const ArmaModel& model, const std::string& field_prefix = "arma.");

//! The steady force per steady feed, B(1)/A(1) = (θ0 + θ1)/(1 + φ1 + φ2), N per mm/min; infinite when
//! A(1) = 0 (an integrating model).
double steady_gain_n_per_mm_per_min(const ArmaModel& model);

//! Eq. 17 run forward: a simulated plant, optionally with an equation-error disturbance.
class ArmaPlant {
 public:
  //! Starts in steady state for the feed `initial_feed_mm_per_min`: every past feed equal to it and every
  //! past force at steady_gain × feed. Throws InputError with validate()'s problems, and "arma.steady_gain"
  //! when A(1) = 0 (no steady state to start in).
  ArmaPlant(const ArmaModel& model, double initial_feed_mm_per_min);

  //! Applies the feed command v(t) (finite, asserted) and returns the next sample
  //! f(t+1) = −φ1 f(t) − φ2 f(t−1) + θ0 v(t) + θ1 v(t−1) + disturbance_n, N.
  double step(double feed_mm_per_min, double disturbance_n = 0.0);

  //! Replaces the coefficients from the next step on; the past samples are kept (a depth or material
  //! change). Must pass validate() (asserted).
  void set_model(const ArmaModel& model);

  double force_n() const { return force_1_n_; }  //!< the latest force sample f(t), N
  const ArmaModel& model() const { return model_; }

 private:
  ArmaModel model_;
  double force_1_n_ = 0.0, force_2_n_ = 0.0;  // f(t), f(t−1)
  double feed_1_mm_per_min_ = 0.0;            // v(t−1)
};

}  // namespace feedplan::control
