#pragma once
// What the machine's sensors read when the true cutting force acts (docs/method.md §6.4). The virtual
// machine computes the true force (Fx, Fy, Fz) every internal step and passes it to Sensors::update,
// which returns the readings of a table dynamometer, an optional spindle-deflection sensor and the
// optional feed-drive servo currents.
//
// Every sensor is a second-order low pass
//     H(s) = ω_n² / (s² + 2 ζ ω_n s + ω_n²)
// with DC gain 1, followed by white Gaussian noise. `bandwidth_hz` is always the −3 dB frequency;
// ω_n follows from it and the damping ratio ζ:
//     ω_n = ω_bw / sqrt(1 − 2ζ² + sqrt((1 − 2ζ²)² + 1)).
// ζ = 1/√2 (the default) is the maximally flat Butterworth filter with ω_n = ω_bw. A small ζ
// (e.g. 0.05) models a piezoelectric dynamometer's mechanical resonance: the gain first rises to a
// peak of 1/(2ζ sqrt(1 − ζ²)) near ω_n, then falls through −3 dB at bandwidth_hz, which then lies
// about 1.55 ω_n up.
//
// Discretisation: bilinear (Tustin) transform with prewarping at the bandwidth frequency, for the
// step given to the constructor. So the discrete filter has exactly DC gain 1 and exactly −3 dB at
// bandwidth_hz; elsewhere the frequency axis is warped, negligibly below a tenth of the sample rate.
// The bandwidth must lie below the Nyquist frequency 1 / (2 step_s).
//
// Noise: each sensor has its own std::mt19937_64, seeded from `seed` and the sensor's index, and
// standard normal numbers made from it by the Box–Muller transform (not std::normal_distribution,
// whose algorithm differs between standard libraries), so a run is reproducible on every platform.
//
// Servo currents (seed 002, Kim & Kim 1996, Eqs. 12–14): I_q = a + b·F per axis, F in N, I in A.
// Reading of seed 002: Eq. 11 (K_t I_q = sgn(Ω) T_f + K_f) makes a the friction current of the
// moving axis and b·F the part that balances the cutting force along the axis; the regression of
// Fig. 4 relates current and force magnitudes in steady cutting. Here the linear current-loop
// dynamics act on the signed axis force, and the static map uses its magnitude:
//     I_axis = a + b · |LP(F_axis)|   (+ noise).
// The axis direction of motion is not known to the sensors, so a is applied as is (a moving axis).
// The 62 Hz bandwidth is seed 002's (§5 conclusion 1). Seed 002's Eq. 16, as printed,
// 255 (s + 139) / (s² + 155 s + 35500), has −3 dB at 68 Hz but a +6.3 dB peak at 28 Hz, which
// contradicts its own "within 8 %" agreement at 20 Hz tooth frequency (Fig. 6); so the current
// loop uses the same flat second-order low pass as the other sensors.
//
// Spindle power: the power the cutting draws from the spindle motor, P = M ω with M the torque of the
// tangential forces (milling_forces.hpp) and ω the spindle speed, as a load monitor on the spindle drive
// reads it — with the drive's idle power tared off (what such monitors display as cutting power), low
// passed by the monitor's filter. Its 20 Hz default is a choice made here: spindle load monitors filter the
// drive's power over some 10 ms so that the reading does not follow the tooth passes, which makes the
// reading close to the mean power of a revolution at the spindle speeds of milling.

#include <cstdint>
#include <random>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::sim {

//! Table dynamometer under the workpiece (always on).
struct DynamometerOptions {
  double bandwidth_hz = 3000.0;            //!< −3 dB frequency, Hz
  double damping_ratio = 0.7071067811865476;  //!< ζ of the second-order low pass, in (0, 2]; 1/√2 = flat
  double noise_n = 0.0;                    //!< RMS white noise added to each axis, N
};

//! Spindle-deflection (spindle-integrated force) sensor: sees Fx and Fy only.
struct SpindleSensorOptions {
  bool enabled = false;                       //!< read the spindle sensor at all
  double bandwidth_hz = 350.0;                //!< −3 dB frequency, Hz (docs/method.md §6.4)
  double damping_ratio = 0.7071067811865476;  //!< ζ of the second-order low pass, in (0, 2]
  double noise_n = 0.0;                       //!< RMS white noise added to each axis, N
};

//! Spindle load monitor: the cutting power the spindle drive delivers.
struct SpindlePowerOptions {
  bool enabled = false;                        //!< read the spindle power at all
  double bandwidth_hz = 20.0;                  //!< −3 dB frequency of the monitor's filter, Hz (see the top)
  double damping_ratio = 0.7071067811865476;   //!< ζ of the second-order low pass, in (0, 2]
  double noise_w = 0.0;                        //!< RMS white noise added to the reading, W
};

//! Static characteristic I = a + b·|F| of one feed axis.
struct ServoCurrentAxis {
  double a_amp = 0.0;         //!< current with the axis moving and no cutting force, A
  double b_amp_per_n = 0.0;   //!< current per newton of cutting force along the axis, A/N (> 0)
};

//! Feed-drive servo currents as force sensors (seed 002).
struct ServoCurrentOptions {
  bool enabled = false;                        //!< compute the currents at all
  ServoCurrentAxis x{4.12, 0.00362};           //!< x axis, seed 002 Eq. 12
  ServoCurrentAxis y{7.24, 0.00450};           //!< y axis, seed 002 Eq. 13
  ServoCurrentAxis z{18.5, 0.00289};           //!< z axis, seed 002 Eq. 14
  double bandwidth_hz = 62.0;                  //!< −3 dB frequency of the current loop, Hz (seed 002)
  double damping_ratio = 0.7071067811865476;   //!< ζ of the second-order low pass, in (0, 2]
  double noise_amp = 0.0;                      //!< RMS white noise added to each current, A
};

//! Everything the sensors need besides the simulation step.
struct SensorOptions {
  DynamometerOptions dynamometer;       //!< table dynamometer
  SpindleSensorOptions spindle_sensor;  //!< spindle-deflection sensor
  ServoCurrentOptions servo_current;    //!< feed-drive currents
  SpindlePowerOptions spindle_power;    //!< spindle load monitor
  std::uint64_t seed = 1;               //!< seed of the noise generators; same seed → same readings
};

//! What the sensors read at one step. Readings of a disabled sensor are NaN.
struct SensorReading {
  double dynamometer_fx_n = 0.0;  //!< dynamometer, x, N
  double dynamometer_fy_n = 0.0;  //!< dynamometer, y, N
  double dynamometer_fz_n = 0.0;  //!< dynamometer, z, N
  double spindle_fx_n = 0.0;      //!< spindle sensor, x, N (NaN when disabled)
  double spindle_fy_n = 0.0;      //!< spindle sensor, y, N (NaN when disabled)
  double ix_a = 0.0;              //!< x-axis servo current, A (NaN when disabled)
  double iy_a = 0.0;              //!< y-axis servo current, A (NaN when disabled)
  double iz_a = 0.0;              //!< z-axis servo current, A (NaN when disabled)
  double spindle_power_w = 0.0;   //!< cutting power of the spindle, W (NaN when disabled)
};

//! Problems with `options` that do not depend on the step: every bandwidth finite and > 0, every
//! damping ratio in (0, 2], every noise (N, A or W) finite and ≥ 0, each current axis with a finite a_amp ≥ 0
//! and b_amp_per_n finite and > 0. Fields are named "sensors.dynamometer.bandwidth_hz" etc.; a disabled
//! sensor is not checked. Empty when all is well.
std::vector<InputProblem> validate(const SensorOptions& options);

//! validate(options) plus the checks that need the simulation step: `step_s` finite and > 0, and the
//! bandwidth of every enabled sensor below the Nyquist frequency 1 / (2 step_s).
std::vector<InputProblem> validate(const SensorOptions& options, double step_s);

//! The sensors of one simulated run. Filters start at rest (zero force).
class Sensors {
 public:
  //! Sets up the filters for a fixed step `step_s` (s) between update() calls. Throws
  //! feedplan::InputError with every problem validate(options, step_s) finds.
  Sensors(const SensorOptions& options, double step_s);

  //! Advances every sensor by one step with the true force (N) and the true cutting power of the spindle
  //! (W) acting during it and returns the readings at the end of the step.
  SensorReading update(double fx_n, double fy_n, double fz_n, double spindle_power_w = 0.0);

  //! The step the filters were discretised for, s.
  double step_s() const { return step_s_; }

 private:
  // One second-order section, transposed direct form II.
  struct Biquad {
    double b0 = 0, b1 = 0, b2 = 0, a1 = 0, a2 = 0;  // y[n] = b0 x[n] + s1; a0 normalised to 1
    double s1 = 0, s2 = 0;                          // state
    double step(double x);
  };
  // A standard normal source for one sensor.
  struct Noise {
    std::mt19937_64 engine;
    double spare = 0;
    bool has_spare = false;
    double next();
  };

  static Biquad low_pass(double bandwidth_hz, double damping_ratio, double step_s);

  SensorOptions options_;
  double step_s_ = 0;
  Biquad dynamometer_[3];
  Biquad spindle_[2];
  Biquad current_[3];
  Biquad power_;
  Noise dynamometer_noise_;
  Noise spindle_noise_;
  Noise current_noise_;
  Noise power_noise_;
};

}  // namespace feedplan::sim
