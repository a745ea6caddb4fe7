#pragma once
// The plant of seeds 000/001 (Ulsoy, Koren, Rasmussen 1982; Ulsoy & Koren, UM-MEAM-82-7), which their
// variable-gain simulations run: a CNC feed servo followed by the cutting process.
//
//   Eq. 2, feed servo:      f̈ + 2ξω_n ḟ + ω_n² f = K_s u        (u: the command, f: the feed)
//   Eq. 1, cutting process: τ Ḟ_c + F_c = K_p f
//
// The papers keep the force F_c in sensor units and leave every number out. Here the feed and the command
// are in mm/min, F_c in N, K_s = servo_dc_gain · ω_n² (so a held command u gives the feed servo_dc_gain·u),
// and K_p comes from the specific cutting force of the material: a depth of cut a at n rev/min and a feed
// v_f mm/min cut a chip of a · v_f / n mm², so
//
//   K_p = k_s · a / n   N per mm/min.
//
// The seeds' K_p "depends on the depth-of-cut, the spindle speed, … and the feed itself"; the feed
// dependence (k_s falling with chip thickness) is left out: Eq. 1 is linear, and the papers call it a
// model "for control system analysis and design".
//
// Sampling. The controller holds its command over each period Δt (zero-order hold), so the plant is
// discretised exactly: with the state x = (f, ḟ, F_c) and ẋ = A x + B u,
//   x_{k+1} = Φ x_k + Γ u_k,   Φ = e^{AΔt},   Γ = ∫₀^Δt e^{As} ds B,
// both read off the exponential of the augmented matrix [[A, B], [0, 0]] Δt. A depth change takes effect
// at the start of the next period (the seeds' Fig. 4 changes the depth in steps).

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! The numbers the seeds leave out, with where each default comes from.
struct TurningProcessParameters {
  //! k_s, N/mm² (> 0): force per chip area. The seeds give none; 2000 N/mm² is the order of Kienzle's
  //! specific cutting force k_c1.1 for plain carbon steels in the machining handbooks (about 1.5–2.2 kN/mm²
  //! for C45).
  double specific_cutting_force_n_per_mm2 = 2000.0;
  //! n, rev/min (> 0): the spindle speed, which turns the feed rate into a feed per revolution.
  double spindle_rpm = 500.0;
  //! τ of Eq. 1, s (≥ 0; 0: the force follows the feed at once). The seeds give none. A new feed or depth
  //! is fully in the chip after one spindle revolution, so τ is taken as one revolution: 0.12 s at
  //! 500 rev/min (a choice made here, not a number from the seeds or their references).
  double process_time_constant_s = 0.12;
  //! ω_n of Eq. 2, rad/s (> 0). The seeds give none; 30 rad/s (4.8 Hz) is about twice the 2.3 Hz
  //! velocity-loop bandwidth seed 002 measured on a FANUC feed drive, so that the servo mostly settles
  //! within the seeds' Δt = 0.1 s, as the seeds' choice of sampling period presumes.
  double servo_natural_frequency_rad_per_s = 30.0;
  //! ξ of Eq. 2 (> 0). The seeds give none; 0.7, the common design damping of a position servo.
  double servo_damping_ratio = 0.7;
  //! K_s / ω_n², feed per command in steady state (> 0): 1 when the command is the feed in mm/min.
  double servo_dc_gain = 1.0;
};

//! Every problem with the parameters, each named "<field_prefix><field>" with its value and the rule
//! ("turning.spindle_rpm = 0: must be finite and > 0"). Empty when they are usable.
std::vector<InputProblem> validate(const TurningProcessParameters& parameters,
                                   const std::string& field_prefix = "turning.");

//! K_p = k_s · a / n of the file comment, N per mm/min, for a depth of cut `depth_mm`.
double process_gain_n_per_mm_per_min(const TurningProcessParameters& parameters, double depth_mm);

//! Seed 000/001 Eqs. 1–2 stepped at a fixed period under a held command.
class TurningProcess {
 public:
  //! Starts in steady state for the command `initial_command_mm_per_min` at depth `depth_mm`: feed =
  //! servo_dc_gain · command, F_c = K_p · feed, at time 0. Throws InputError with validate()'s problems,
  //! and with "turning.period_s" / "turning.depth_mm" / "turning.initial_command_mm_per_min" when the
  //! period is not finite and > 0 or the depth or command not finite and ≥ 0.
  TurningProcess(const TurningProcessParameters& parameters, double period_s, double depth_mm,
                 double initial_command_mm_per_min);

  //! Changes the depth of cut from the next step on (finite and ≥ 0, asserted); the state is kept.
  void set_depth_mm(double depth_mm);

  //! Holds `command_mm_per_min` (finite, asserted) over one period and returns F_c at its end, N.
  double step(double command_mm_per_min);

  double force_n() const { return x_[2]; }               //!< F_c now, N
  double feed_mm_per_min() const { return x_[0]; }       //!< the feed f now, mm/min
  double depth_mm() const { return depth_mm_; }          //!< the depth of cut in effect, mm
  double period_s() const { return period_s_; }          //!< Δt, s
  double time_s() const { return static_cast<double>(steps_) * period_s_; }  //!< steps taken × Δt, s

 private:
  void discretise();

  TurningProcessParameters parameters_;
  double period_s_ = 0.0;
  double depth_mm_ = 0.0;
  double x_[3] = {0.0, 0.0, 0.0};      // f, ḟ, F_c
  double phi_[3][3] = {};              // Φ
  double gamma_[3] = {};               // Γ
  long long steps_ = 0;
};

}  // namespace feedplan::control
