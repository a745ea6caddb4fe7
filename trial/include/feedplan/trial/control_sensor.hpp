#pragma once
// The force a feedback controller on the virtual machine sees: one number per spindle revolution, made
// from one of the machine's sensors the way the source papers' controllers made theirs.
//
// Which force. Seed 002 (Kim & Kim 1996, §4) regulates "the maximum amplitude per spindle revolution",
// and seed 003's model predicts the same per-revolution peak of |F_xy|; seeds 000/001 regulate the force
// of a turning process, which has no tooth ripple, so peak and mean are one there. Every sensor here is
// therefore read as the largest value over the revolution of the force it gives:
//   dynamometer: |F_xy| = sqrt(Fx² + Fy²) of the table dynamometer's reading — the per-revolution peak
//     the planner and `plan --simulate` judge;
//   spindle:     the tangential force F_t = P / (ω r) from the spindle's cutting power P (sim/sensors.hpp),
//     ω the spindle speed and r the tool radius. The power monitor's filter leaves little of the tooth
//     ripple, so this is close to the revolution's mean tangential force — a smaller number than the
//     peak of |F_xy| of the same cut (by a factor the engagement sets): a target for this sensor is a
//     target for that mean tangential force;
//   currents:    |F_xy| from the x and y feed-drive currents through the calibration I = a + b·|F| per
//     axis (learning/current_calibration.hpp), |F_axis| = (I − a) / b, then sqrt(|F_x|² + |F_y|²). The
//     current loop (62 Hz in seed 002) follows the tooth passes only when they are slow (seed 002: 20 Hz);
//     above that the reading tends to the mean force, as current_calibration.hpp explains.
//
// Revolutions are counted by integrating the spindle speed over the samples' times (a revolution ends
// when the spindle has turned one more whole turn since the first sample); with the spindle stopped none
// end.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/learning/current_calibration.hpp"
#include "feedplan/sim/sensors.hpp"

namespace feedplan::trial {

//! Where the controlled force comes from.
enum class ForceSensor {
  kDynamometer,     //!< table dynamometer, per-revolution peak |F_xy|
  kSpindlePower,    //!< spindle cutting power → tangential force
  kServoCurrents,   //!< x and y feed-drive currents → |F_xy| through the calibration
};

//! The sensor's name on the command line: "dynamometer", "spindle", "currents".
std::string_view to_string(ForceSensor sensor);

//! The sensor named `name` (to_string's names), or nothing.
std::optional<ForceSensor> force_sensor_named(std::string_view name);

//! What turns a sensor's reading into a force.
struct ForceSensorSettings {
  ForceSensor sensor = ForceSensor::kDynamometer;  //!< which sensor
  double tool_radius_mm = 0.0;  //!< r of F_t = P / (ω r), mm (finite, > 0; used by kSpindlePower only)
  //! I = a + b·|F| of the x and y axes (b finite and > 0; used by kServoCurrents only).
  learning::CurrentCalibration calibration;
};

//! Every problem with the settings, each named "<field_prefix><field>" with its value and the rule
//! ("sensor.calibration.x.b_a_per_n = 0: must be finite and > 0 A/N"). Empty when usable.
std::vector<InputProblem> validate(const ForceSensorSettings& settings, const std::string& field_prefix = "sensor.");

//! The sensor options the virtual machine needs on to give `sensor`'s reading (the dynamometer is always
//! on; the spindle power monitor or the servo currents are switched on in `options`).
void enable_sensor(ForceSensor sensor, sim::SensorOptions& options);

//! The force one reading gives, N, as the file comment says; NaN when the reading lacks the sensor (a
//! disabled sensor reads NaN) or, for the spindle, when it is not turning.
double sensed_force_n(const ForceSensorSettings& settings, const sim::SensorReading& reading, double spindle_rpm);

//! One spindle revolution as the sensor saw it.
struct SensedRevolution {
  double t_start_s = 0.0;  //!< time the previous revolution ended (the first sample's for the first), s
  double t_end_s = 0.0;    //!< time of the sample that completed it, s
  double force_n = 0.0;    //!< largest sensed force over its samples, N (0 when none was finite)
};

//! Sensed force per revolution from samples taken one at a time.
class RevolutionForceMeter {
 public:
  //! Needs settings that pass validate() (asserted).
  explicit RevolutionForceMeter(const ForceSensorSettings& settings);

  //! Takes the reading at `t_s` (increasing from call to call) with the spindle at `spindle_rpm` since the
  //! previous sample; returns the revolution this sample completes, if any.
  std::optional<SensedRevolution> add(double t_s, double spindle_rpm, const sim::SensorReading& reading);

 private:
  ForceSensorSettings settings_;
  bool started_ = false;
  double last_t_s_ = 0.0;
  double turns_ = 0.0;           // spindle turns since the first sample
  double next_turn_ = 1.0;       // the turn count that ends the current revolution
  double revolution_start_s_ = 0.0;
  double largest_n_ = 0.0;
};

}  // namespace feedplan::trial
