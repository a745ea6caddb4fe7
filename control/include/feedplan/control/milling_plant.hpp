#pragma once
// Seed 004's milling plant (Rubio & De la Sen 2007, §II.A, after Altintas, Manufacturing Automation, 2000):
// the CNC feed drive, a first-order lag from the commanded feed f_c to the actual feed f_a (Eq. 1), in
// series with the chatter-free cutting process, a first-order lag from f_a to the peak force F_p (Eq. 2):
//
//   G_c(s) = F_p(s) / f_c(s) = K_p / ((τ_m s + 1)(τ_c s + 1)),   K_p = K_c a b / (N n)   (Eq. 3)
//
// with K_c the cutting pressure (N/mm²), b the axial depth of cut (mm), a the non-dimensional immersion
// function (0 to about N), N the number of teeth and n the spindle speed (rev/s); feeds in mm/s, so K_p is in
// N·s/mm. The depth changes in steps (seed 004's work-piece, Fig. 1), K_p with it; the rest is fixed.
//
// As a ContinuousSystem the states are the actual feed and the force, both physical, so that a new depth
// changes only the gain in front of the feed and leaves the state where it was:
//   ḟ_a = (f_c − f_a) / τ_m,   Ḟ_p = (K_p f_a − F_p) / τ_c,   y = F_p.

#include <string>
#include <vector>

#include "feedplan/control/continuous_system.hpp"
#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! The numbers of Eqs. 1–3 apart from the depth of cut.
struct MillingPlantParameters {
  double cutting_pressure_n_per_mm2 = 1200.0;  //!< K_c, N/mm² (> 0); seed 004: aluminium, 1200 N/mm²
  //! a(φ_st, φ_ex, N), non-dimensional (> 0). Seed 004 cuts full immersion with 4 teeth but gives no value;
  //! √2 is chosen here: the peak of Σ sin φ_j over the two teeth in cut, 90° apart (sin φ + cos φ).
  double immersion_function = 1.4142135623730951;
  int teeth = 4;                    //!< N (≥ 1); seed 004: a 4-fluted carbide mill
  double spindle_speed_rpm = 715.0;  //!< n, rev/min (> 0); seed 004: 715 rev/min
  //! τ_m of Eq. 3 (τ_s of Eq. 1), s (> 0); seed 004: "assumed to be 0.1 ms".
  double feed_drive_time_constant_s = 1e-4;
  //! τ_c of Eq. 2, s (> 0). Seed 004 gives none. Chosen here as one tooth period, 60/(N n) = 21 ms at
  //! 715 rev/min with 4 teeth: a new feed is fully in the chip once the next tooth has cut.
  double cutting_time_constant_s = 60.0 / (715.0 * 4.0);
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("milling.teeth = 0: must be ≥ 1"). Empty when usable.
std::vector<InputProblem> validate(const MillingPlantParameters& parameters, const std::string& field_prefix = "milling.");

//! K_p = K_c a b / (N n) of Eq. 3, N·s/mm, for the depth of cut `depth_mm`.
double process_gain_n_s_per_mm(const MillingPlantParameters& parameters, double depth_mm);

//! The spindle period 60 / n, s: seed 004's sampling period T ("chosen to be the spindle speed").
double spindle_period_s(const MillingPlantParameters& parameters);

//! Eq. 3 at the depth `depth_mm` as the ContinuousSystem of the file comment (input f_c in mm/s, output
//! F_p in N). Needs parameters that pass validate() (asserted).
ContinuousSystem milling_system(const MillingPlantParameters& parameters, double depth_mm);

}  // namespace feedplan::control
