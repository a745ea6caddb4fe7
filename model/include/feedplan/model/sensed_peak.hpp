#pragma once
// The peak a dynamometer reads (docs/method.md §5.8): the mechanistic kernel's force over one revolution
// (mechanistic_force.hpp), through the sensor's modes (sensor_response.hpp), and the largest |F_xy| of
// that reading. It is what a cutting test's measured per-revolution peak is to be compared with when
// the dynamometer rings; the kernel's own peak (predicted_peak) is the force on the tool.
//
// Sampling. The kernel's regressors are evaluated at kSensedPeakSamples spindle angles over the
// revolution, each of the six coefficient columns of Fx and Fy is passed through the sensor as a periodic
// signal (sensed_revolution: its harmonics up to kSensedPeakSamples / 2, i.e. 360 times the revolution
// frequency, far above any dynamometer mode), and the reading is their sum weighted by the coefficients —
// the reading is linear in the coefficients as the force is. The largest samples' local maxima are then
// refined by golden-section search on the reading's Fourier series, which passes through the samples and
// is smooth between them.

#include <array>
#include <span>

#include "feedplan/model/engaged_section.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/model/sensor_response.hpp"

namespace feedplan::model {

//! Spindle angles at which the kernel is sampled over a revolution for the sensed peak: 0.5° apart.
inline constexpr int kSensedPeakSamples = 720;

//! The peak of the sensor's reading over one revolution, where it is reached, and its gradient.
struct SensedPeak {
  double force_n = 0.0;            //!< largest |F_xy| of the steady reading over one revolution, N
  double spindle_angle_rad = 0.0;  //!< the kernel's spindle angle Ω (mechanistic_force.hpp) at which it is read, in [0, 2π)
  //! The reading's regressors at that angle: reading (x, y) = regressors · (K_tc, K_rc, K_ac, K_te, K_re, K_ae),
  //! rows x and y, columns in MechanisticCoefficient order (mm² for the cutting, mm for the edge columns).
  std::array<std::array<double, 6>, 2> regressors{};
  double force_peak_n = 0.0;  //!< for comparison, the largest |F_xy| of the force itself at the same samples, N
};

//! The peak of what `sensor` reads over a revolution at `spindle_rpm` while the kernel's force of `model`
//! acts on `sections` at feed per tooth `feed_per_tooth_mm` (file comment). Needs a model and cutter that
//! pass validate(model, cutter), a sensor that passes validate(sensor), f_z and spindle_rpm finite and > 0
//! (asserted; validate once, not per call). 0 with nothing engaged.
SensedPeak predicted_sensed_peak(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                 const CutterGeometry& cutter, double feed_per_tooth_mm, const SensorResponse& sensor,
                                 double spindle_rpm);

}  // namespace feedplan::model
