#pragma once
// The source papers' feedback force controllers (control/), chosen by name and set up for a run on the
// virtual machine: each becomes a ControlLaw, a step from the force sensed to the override ratio, with the
// period it is stepped at.
//
//   integral             seeds 000/001's conventional ACC (control/integral_force_controller.hpp), every 0.1 s
//   variable-gain        seeds 000/001's variable-gain AC (control/variable_gain_controller.hpp), every 0.1 s,
//                        continuous override
//   variable-gain-lathe  the same with seed 001's lathe override: 15 % steps
//   robust-servo         seed 002's adaptive robust servo (control/adaptive_robust_servo.hpp), once per
//                        spindle revolution — or every n-th revolution, n the fewest spanning 0.1 s, when a
//                        revolution is shorter: seed 002's ARMA model (Eq. 17) has room for a feed-drive dead
//                        time (0.08 s) shorter than the sample period only, and its poles were placed for
//                        100 ms samples
//   model-reference      seed 004's model-reference controller (control/froh_model_reference_controller.hpp)
//                        under a zero-order hold; multi-model-1 the same with scheme 1's bank of β-FROH
//                        models, multi-model-2 with scheme 2's neighbour search — once per revolution, or
//                        every n-th revolution spanning 0.1 s (model_reference_law.hpp says why and how
//                        its known plant is set)
//
// Units. The controllers think in a feed relative to a programmed feed; here that feed is expressed in
// percent of the program's own feed (100 = the F words as written), so the override ratio they return is
// their feed / 100 whatever the program. Their equations are linear in the feed's unit except for the
// robust servo's RLS start (its covariance was sized for feeds and forces of a few hundred, seed 002's
// 500 N at 360 mm/min), which percent keeps in that range for any program.
//
// Gains. The controllers start from the process gain K_p0 = target / 100 N per percent — the program's
// feed cuts at the target: true of a plan's program (that is what it was planned for) and the premise a
// programmer writes a constant feed on. The papers leave their gains in sensor units; here:
//   integral: K_c = K / K_p0 with the loop gain K (default 3 /s). The override reaches the feed through
//     seed 002's drive (dead time 0.08 s, lag 1/14 s) and the sensor reports a revolution after it ends;
//     with the 0.1 s hold that is about 0.2 s of delay, and 3 /s leaves a phase margin of about 45°
//     (crossover at 3 rad/s: −90° − 3·0.2 rad − atan(3/14)). A fixed gain that is right at K_p0 is K·K_p/K_p0
//     on a process of gain K_p — seeds 000/001's point.
//   variable-gain: K as above; the estimator and adaptation rates c1, c2 of Eqs. 4–5 set as time constants
//     (K_m follows the process gain within about 1 s, K_c follows K / K_m within about 0.5 s):
//     c1 = 1 / (1 s × 100 %), c2 = 1 / (0.5 s × K_p0).
//   robust-servo: seed 002's poles, its RLS settings (control/arma_estimator.hpp) and a starting model of
//     seed 002's feed drive sampled at the servo's period with the gain K_p0 (control/feed_drive.hpp's
//     arma_equivalent), made at its first step, when the period is known.

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::trial {

//! The controllers by name.
enum class ControllerKind {
  kIntegral,           //!< "integral"
  kVariableGain,       //!< "variable-gain"
  kVariableGainLathe,  //!< "variable-gain-lathe"
  kRobustServo,        //!< "robust-servo"
  kModelReference,     //!< "model-reference"
  kMultiModel1,        //!< "multi-model-1"
  kMultiModel2,        //!< "multi-model-2"
};

//! Every controller name, in ControllerKind's order.
inline constexpr std::array<std::string_view, 7> kControllerNames = {
    "integral", "variable-gain", "variable-gain-lathe", "robust-servo", "model-reference", "multi-model-1", "multi-model-2"};

//! The controller's name.
std::string_view to_string(ControllerKind kind);

//! The controller named `name` (kControllerNames), or nothing.
std::optional<ControllerKind> controller_named(std::string_view name);

//! The feed, in percent of the program's, an override ratio of 1 means for every controller here.
inline constexpr double kProgrammedFeedPercent = 100.0;

//! The robust servo's shortest sample period, s (see the file comment).
inline constexpr double kRobustServoMinPeriodS = 0.1;

//! A controller ready to run: the force sensed (N, finite) and the time since its previous step (s, > 0)
//! in, the override ratio wished for out.
struct ControlLaw {
  std::function<double(double measured_force_n, double dt_s)> step;  //!< one step of the controller
  //! Time between steps, s; with per_revolution, the shortest span of whole revolutions between steps.
  double period_s = 0.1;
  //! Stepped at the end of every n-th spindle revolution (n the fewest spanning period_s), with the largest
  //! revolution force of the n; false: every period_s, with the latest revolution's force.
  bool per_revolution = false;
  //! When set, the override between two steps: the ratio a fraction (in [0, 1]) of the last step's time step
  //! after it (seed 004's β-FROH ramp); unset: the step's ratio held (a zero-order hold).
  std::function<double(double fraction_of_period)> hold;
};

//! What a controller is set up with.
struct ControllerSettings {
  ControllerKind kind = ControllerKind::kRobustServo;  //!< which controller
  double target_force_n = 0.0;   //!< the force to hold, N (finite, > 0)
  double max_ratio = 1.5;        //!< the largest override the controller may ask for (finite, > 0; seeds 000/001: 1.5)
  //! The lowest override (finite, in [0, max_ratio]): the controllers stay above it and do not wind up
  //! below it (control/override_range.hpp). Set it to the override loop's own floor.
  double min_ratio = 0.0;
  double loop_gain_per_s = 3.0;  //!< K of the integral and variable-gain controllers, 1/s (finite, ≥ 0; 0: no feedback)
  //! The machine's spindle speed, rev/min: the model-reference controllers' known plant (finite, > 0 for
  //! them; unused by the others).
  double spindle_rpm = 0.0;
  int flutes = 0;  //!< the tool's flutes: the model-reference controllers' known plant (≥ 1 for them)
};

//! Whether `kind` is one of seed 004's model-reference controllers (they need spindle_rpm and flutes).
bool is_model_reference(ControllerKind kind);

//! Every problem with the settings, each named "<field_prefix><field>" with its value and the rule. Empty
//! when usable.
std::vector<InputProblem> validate(const ControllerSettings& settings, const std::string& field_prefix = "controller.");

//! The controller of the file comment. Throws InputError with validate()'s problems, and with the
//! controller's own (control/) when they reject the parameters made from the settings.
ControlLaw make_control_law(const ControllerSettings& settings);

}  // namespace feedplan::trial
