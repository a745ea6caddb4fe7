#pragma once
// What a dynamometer reads of a periodic cutting force (docs/method.md §5.8): a dynamometer is a structure
// with modes, and its reading of a force that repeats every spindle revolution is the force's harmonics
// multiplied by its frequency response.
//
// Model. The top plate with the workpiece is a mass on the stiffness of the piezo stack. In the XY plane it
// has two modes, along two perpendicular directions — the principal axes of the stiffness (with the plate's
// mass the same in every direction, the modes are orthogonal) — at an angle θ from the force frame's x axis.
// The sensor reads the force in its springs, K u, of the plate's displacement u under the cutting force F:
// from M ü + C u̇ + K u = F, with the damping proportional (diagonal in the modes), a harmonic force of
// angular frequency ω is read as
//   R(ω) = Σ_m H_m(ω) d_m d_mᵀ F(ω),   H_m(ω) = ω_m² / (ω_m² − ω² + 2i ζ_m ω_m ω),
//   d_0 = (cos θ, sin θ),  d_1 = (−sin θ, cos θ),
// for a force F e^{iωt}. So the gain is 1 at DC (Σ d_m d_mᵀ = I: a calibrated dynamometer reads a static
// force right), |H_m| peaks near ω_m at 1/(2ζ_m √(1 − ζ_m²)), and above the modes the reading falls off as
// 1/ω². With θ = 0 each axis has its own mode (Fx read through mode 0, Fy through mode 1); θ ≠ 0 couples
// them, as on the Kistler recordings, where Fx shows the frequency of the Fy mode and vice versa. Fz is
// not modelled: the modes are those of the XY plane.
//
// Periodic force. A force sampled at n equal steps over one revolution is a Fourier series of the
// revolution: harmonic k (k = 0 … n/2) lies at k · rpm / 60 Hz. The steady reading — the response once
// the transient of the start of the cut has died out, what a synchronous average over many revolutions
// holds — multiplies each harmonic by R(2π k rpm / 60). The harmonic k = n/2 of an even n, which equal
// samples cannot tell from its phase, is taken as a cosine through the samples.

#include <array>
#include <complex>
#include <span>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::model {

//! One second-order mode of the dynamometer.
struct SensorMode {
  double natural_frequency_hz = 1000.0;  //!< f_m = ω_m / 2π, Hz (> 0)
  double damping_ratio = 0.05;           //!< ζ_m, in (0, 1): a mode that rings
};

//! The dynamometer's two XY modes, with gain 1 at DC.
struct SensorResponse {
  //! modes[0] along the direction θ = mode_angle_deg from the x axis (along x when θ = 0), modes[1]
  //! perpendicular to it (along y when θ = 0).
  std::array<SensorMode, 2> modes{};
  double mode_angle_deg = 0.0;  //!< θ, deg, finite: the direction of modes[0], counter-clockwise from +x
};

//! The 2×2 complex gain R(ω) of the file comment at one frequency: reading = gain · force.
struct SensorGain {
  std::array<std::array<std::complex<double>, 2>, 2> xy{};  //!< [reading axis x, y][force axis x, y]
};

//! Every problem with the sensor, each named "<field_prefix><field>" with its value and the rule
//! ("sensor.modes[1].damping_ratio = 1.2: must be in (0, 1)"): natural frequencies finite and > 0, damping
//! ratios in (0, 1), a finite angle. Empty when the sensor is usable.
std::vector<InputProblem> validate(const SensorResponse& sensor, const std::string& field_prefix = "sensor.");

//! R(2π frequency_hz) of the file comment. Needs a sensor that passes validate() and a finite frequency
//! ≥ 0 (asserted).
SensorGain sensor_gain(const SensorResponse& sensor, double frequency_hz);

//! A force in the XY plane sampled at equal spindle-angle steps over one revolution, N.
struct RevolutionForce {
  std::vector<double> fx_n;  //!< x, N, n samples
  std::vector<double> fy_n;  //!< y, N, the same n samples
};

//! The steady reading of the sensor at the same n samples when the force `fx_n`, `fy_n` (n ≥ 2 samples
//! each, at equal steps over one revolution, the same points for both) repeats every revolution at
//! `spindle_rpm`: each harmonic multiplied by sensor_gain() at its frequency (file comment). Exact for a
//! force whose harmonics above n/2 vanish; otherwise those fold onto the lower ones, as in any sampling.
//! Needs a sensor that passes validate(), spindle_rpm finite and > 0 and equal sample counts (asserted).
//! Cost: a fast Fourier transform there and back per axis, O(n log n).
RevolutionForce sensed_revolution(const SensorResponse& sensor, double spindle_rpm, std::span<const double> fx_n,
                                  std::span<const double> fy_n);

}  // namespace feedplan::model
