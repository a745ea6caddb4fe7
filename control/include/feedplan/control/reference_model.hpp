#pragma once
// Seed 004's reference model (Rubio & De la Sen 2007, §II.C, Eq. 6): the force the closed loop should give,
//
//   G_m(s) = ω_n² / (s² + 2ξω_n s + ω_n²),
//
// with ξ = 0.75 and a rise time T_r of four spindle periods, ω_n = 2.5 / T_r (seed 004, after Altintas 2000
// and Kuo 1991). It is sampled behind the same β-FROH as the plant (froh_discretisation.hpp), one discrete
// reference model per β. As a ContinuousSystem the states are y and ẏ/ω_n (both in the force's unit):
//   ẏ = ω_n v,   v̇ = ω_n (u − y) − 2ξω_n v.

#include <string>
#include <vector>

#include "feedplan/control/continuous_system.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! The numbers of Eq. 6.
struct ReferenceModelParameters {
  double damping_ratio = 0.75;  //!< ξ (> 0: a ξ ≤ 0 puts the model's poles on or outside the unit circle); seed 004: 0.75
  double rise_time_periods = 4.0;  //!< T_r in sampling periods (> 0); seed 004: four spindle periods
  double natural_frequency_times_rise_time = 2.5;  //!< ω_n T_r, rad (> 0); seed 004: 2.5
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("reference_model.damping_ratio = -0.1: must be finite and > 0"). Empty when usable.
std::vector<InputProblem> validate(const ReferenceModelParameters& parameters,
                                   const std::string& field_prefix = "reference_model.");

//! ω_n = (ω_n T_r) / (rise_time_periods · T), rad/s, for the sampling period `period_s`.
double natural_frequency_rad_per_s(const ReferenceModelParameters& parameters, double period_s);

//! G_m as the ContinuousSystem of the file comment, for the sampling period `period_s`. Needs parameters
//! that pass validate() and a finite period > 0 (asserted).
ContinuousSystem reference_system(const ReferenceModelParameters& parameters, double period_s);

}  // namespace feedplan::control
