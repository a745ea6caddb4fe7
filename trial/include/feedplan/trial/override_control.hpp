#pragma once
// A feedback controller on the virtual machine's feed override (sim::OverrideLoop): the data acquisition
// reads the sensor every sample period, RevolutionForceMeter makes one force per spindle revolution
// (control_sensor.hpp), and the controller (feedback_controller.hpp) is stepped at its own period; its
// wish, held (or ramped) until its next step, reaches the feed through the override channel (seed 002's feed drive,
// 14 e^(−0.08 s)/(s + 14), sim::FeedOverrideOptions' default).
//
// In cut only. A controller stepped in the air sees no force and winds the feed up to its maximum, to
// enter the material at 150 % (the reason commercial adaptive control switches on at a force threshold).
// Here a revolution is in cut when its sensed force reaches contact_fraction × target (10 %); while the
// latest revolution is not, the controller is not stepped and the override is 100 % — the program's own
// feed on approach, retract and air moves; stepping resumes from the controller's state at the next
// revolution in cut.
//
// Bounds. The override commanded is the controller's wish clamped to [min_ratio, max_ratio]: 10–150 %
// alone (seeds 000/001's 0–150 %, with a floor so that a force the feed cannot bring down — edge forces
// at a vanishing chip — does not stop the machine), 70–130 % in the hybrid, where the feed-forward plan
// carries the geometry and the feedback only trims the model's error. The controllers are told both bounds
// (ControllerSettings' min_ratio and max_ratio become their own override range), so they do not wind up
// against either; give them the same as here.
//
// Between steps the wish is held (a zero-order hold), or, for a law with a hold (ControlLaw::hold, seed
// 004's β-FROH), follows that hold's ramp, clamped to the bounds, until the next step.

#include <memory>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/sim/feed_override.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "feedplan/trial/control_sensor.hpp"
#include "feedplan/trial/feedback_controller.hpp"

namespace feedplan::trial {

//! How the controller is hooked to the machine.
struct OverrideControlSettings {
  ForceSensorSettings sensor;    //!< which sensor and how its reading becomes a force
  double target_force_n = 0.0;   //!< the force to hold, N (finite, > 0): sets the in-cut threshold
  double min_ratio = 0.1;        //!< lowest override commanded (finite, in [0, max_ratio]); hybrid: 0.7
  double max_ratio = 1.5;        //!< highest override commanded (finite, > 0); hybrid: 1.3
  double contact_fraction = 0.1; //!< a revolution is in cut when its force ≥ this × target (finite, in (0, 1))
  //! Period of the data acquisition, s (finite, > 0): the virtual machine calls the loop every this (or
  //! every internal step, when that is longer). 10 kHz, the force log's default rate.
  double sample_period_s = 1e-4;
  //! The override channel; its max_ratio is set to max_ratio and its initial ratio to 1 (100 %).
  sim::FeedOverrideOptions channel;
};

//! Settings of the hybrid: the plan's program with the feedback trimming the override within 70–130 %.
OverrideControlSettings hybrid_override_settings(const ForceSensorSettings& sensor, double target_force_n);

//! Every problem with the settings, each named "<field_prefix><field>" with its value and the rule,
//! the sensor's included. Empty when usable.
std::vector<InputProblem> validate(const OverrideControlSettings& settings, const std::string& field_prefix = "control.");

//! One step of the controller, or a sample at which it was held off (out of cut).
struct ControlStep {
  double t_s = 0.0;               //!< time, s
  double sensed_force_n = 0.0;    //!< the force the controller was given (the latest revolution's), N
  double commanded_ratio = 1.0;   //!< override commanded from now on (after the bounds)
  double applied_ratio = 1.0;     //!< override the machine applied at t_s (the channel's output)
  bool in_cut = false;            //!< false: the controller was not stepped, 100 % commanded
};

//! What the loop saw and did, filled during the run.
struct ControlTrace {
  std::vector<SensedRevolution> revolutions;  //!< every revolution the sensor completed
  std::vector<ControlStep> steps;             //!< every control period (stepped or held off)
};

//! The override loop of the file comment for `law`. `trace`, when not null, receives every revolution and
//! control step (the loop shares it; keep it to read after the run). Throws InputError with validate()'s
//! problems.
sim::OverrideLoop make_override_loop(const OverrideControlSettings& settings, ControlLaw law,
                                     std::shared_ptr<ControlTrace> trace = nullptr);

}  // namespace feedplan::trial
