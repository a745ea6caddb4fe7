#pragma once
// The bin-averaged regressors of a cutting test as a dynamometer reads them (mechanistic identification with
// identify_sensor, private to the model module): the kernel's regressor columns at every sub-step of the
// bins (substep_regressors) are a periodic signal of the revolution; the sensor multiplies its harmonics
// by its response (sensor_response.hpp), and the bins average the reading over their sub-steps — in that
// order, as the real dynamometer rings before the synchronous average bins its reading.
//
// Both steps are linear and the same for every phase, runout and helix, so they are two fixed matrices per
// test: the Fourier transform F from the M = bins · kPhaseStepsPerBin sub-step samples to the harmonics
// k = 0 … M/2 (revolution_series.hpp's convention), and the bin average E from the harmonics to the bins,
// E_bk = a_k · (1/S) Σ_s e^{2πi k (b S + s) / M} with S = kPhaseStepsPerBin. Then rows = Re(E · G · F · R),
// G the sensor's gain at each harmonic. With G = I this is phase_rows exactly (the series passes through
// every sample).
//
// Nyquist. The bins resolve harmonics below bins / 2 of the revolution: a mode above bins/2 · rpm/60 Hz
// shapes what the bins hold only through the harmonics below it, and is not identified
// (MechanisticIdentificationOptions::sensor_max_frequency_hz is capped there).

#include <Eigen/Dense>

#include "feedplan/model/mechanistic_identification.hpp"
#include "feedplan/model/sensor_response.hpp"

namespace feedplan::model::detail {

//! The two matrices of one test (file comment) and its revolution frequency.
class SensedBinning {
 public:
  //! Needs a test that passes validate() with spindle_rpm > 0 (asserted).
  explicit SensedBinning(const MechanisticCuttingTest& test);

  //! The harmonics k = 0 … M/2 (rows) of the test's sub-step regressors (columns 0 … 3 Fx, 4 … 7 Fy) at
  //! phase Ω₀ with `model`'s size effect, runout and helix.
  Eigen::MatrixXcd spectrum(const MechanisticCuttingTest& test, double phase_rad, const MechanisticModel& model) const;

  //! The bin rows (phase_rows' layout: rows 0 … bins − 1 Fx, then Fy; columns K_tc, K_rc, K_te, K_re) of a
  //! spectrum read through `sensor`.
  Eigen::MatrixXd rows(const Eigen::MatrixXcd& spectrum, const SensorResponse& sensor) const;

  //! The Nyquist frequency of the bins, bins/2 · rpm/60, Hz: no harmonic at or above it is resolved.
  double nyquist_hz() const { return 0.5 * bins_ * revolution_hz_; }

 private:
  int bins_ = 0;
  double revolution_hz_ = 0.0;
  Eigen::MatrixXcd transform_;    //!< F: (M/2 + 1) × M
  Eigen::MatrixXcd bin_average_;  //!< E: bins × (M/2 + 1)
};

}  // namespace feedplan::model::detail
