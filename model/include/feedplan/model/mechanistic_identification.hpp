#pragma once
// Identifying the mechanistic model's coefficients from straight cutting tests (docs/method.md §5.7):
// each test's revolution-synchronous average force (force_log/synchronous_average.hpp) is matched, bin
// by bin, with the mechanistic kernel's force (mechanistic_force.hpp) averaged over the same bins.
//
// The force is linear in the coefficients for a known spindle angle, but the angle of the teeth
// against the average's origin (each revolution's start) is unknown: there is no encoder. So each test
// gets its own phase offset Ω₀ (bin b covers the kernel's spindle angles Ω₀ + [b, b + 1)·2π/bins),
// found by a search over a grid of bins × kPhaseStepsPerBin offsets over the revolution, each offset
// scored by the residual of that test's own least-squares fit of the four XY coefficients. With the
// phases fixed, the coefficients come from one least-squares fit over every bin of every test.
//
// Only the force in the XY plane is averaged, so K_ac and K_ae (axial) are not identified: the result
// keeps them at 0 and says so. Runout is identified on request (options.identify_runout): it makes the
// force non-linear in the unknowns, and Ceres refines coefficients, runout and phases together. The
// size effect is identified on request (options.identify_size_effect) by a search over its exponent, each
// try scored by the coefficients' linear fit.
//
// The dynamometer's modes are identified on request too (options.identify_sensor, docs/method.md §5.8): the
// bins are then matched with the kernel's force as the sensor reads it (sensor_response.hpp), the modes
// found first by a search over their natural frequency and damping with the coefficients fitted at each
// try, then refined by Ceres with the coefficients, the phases (and runout and helix when asked).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/engaged_section.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/model/sensor_response.hpp"

namespace feedplan::model {

//! Sub-steps of a bin at which the phase search tries offsets, and at which the kernel's force is
//! averaged over a bin (midpoint rule): 4 — half a degree with 180 bins.
inline constexpr int kPhaseStepsPerBin = 4;

//! Which side of the tool the material is on in a straight cut (M3 spindle).
enum class StraightCutSide {
  kDown,  //!< climb milling: material on the right of the feed, teeth leave at φ = π
  kUp,    //!< conventional milling: material on the left, teeth enter at φ = 0
  kSlot,  //!< full slot: [0, π]
};

//! The engaged arc of a straight cut a_e deep with a tool of radius r (engaged_section.hpp's immersion
//! angles): down [π − acos(1 − a_e/r), π], up [0, acos(1 − a_e/r)], slot [0, π]. Needs r > 0 and
//! 0 < a_e ≤ 2r (asserted); a_e ≥ 2r gives [0, π] on either side.
ImmersionArc straight_cut_arc(StraightCutSide side, double radial_depth_mm, double radius_mm);

//! One straight cutting test as identification needs it.
struct MechanisticCuttingTest {
  CutterGeometry cutter;               //!< the tool
  ImmersionArc arc;                    //!< engaged arc over the whole depth (straight_cut_arc)
  double axial_depth_mm = 0.0;         //!< a_p, mm (> 0)
  double feed_per_tooth_mm = 0.0;      //!< f_z, mm (> 0)
  //! Revolution-synchronous average Fx (along the feed) over equal spindle-angle bins from each
  //! revolution's start, N; at least 8 bins.
  std::vector<double> synchronous_fx_n;
  std::vector<double> synchronous_fy_n;  //!< Fy (left of the feed), same bins, N
  std::string name;                      //!< what the result's messages call it ("tests[2]" when empty)
  //! Spindle speed of the test, rev/min: the harmonics of the revolution lie at multiples of rpm/60 Hz.
  //! Needed (> 0) only with identify_sensor, whose modes are in Hz; 0: not given.
  double spindle_rpm = 0.0;
  //! The test's steady per-revolution peaks of |F_xy| as the sensor read them, N (each finite and > 0). With at
  //! least 2 their mean is matched along with the bins (MechanisticIdentificationOptions::match_peaks); empty:
  //! the bins alone.
  std::vector<double> revolution_peaks_n;
};

//! How to identify.
struct MechanisticIdentificationOptions {
  //! Largest condition number of the column-scaled regressor matrix for which the coefficients count
  //! as identified; above it, the combination of coefficients along the weakest direction is reported.
  double max_condition_number = 1e3;
  //! Relative spread of f_z, (max − min)/max, below which the tests count as one feed.
  double same_feed_tolerance = 0.05;
  //! Also fit the per-tooth runout (all tests must use one cutter, ≥ 2 flutes): the coefficients, the
  //! runout and every test's phase are refined together by Ceres (numeric derivatives), starting from the
  //! fit without runout. Only differences between teeth are seen, and the numbering is the phase's: see
  //! MechanisticIdentification::model.
  bool identify_runout = false;
  //! With identify_runout, also fit the flutes' helix angle (one for all tests, within ±20° of the cutter's
  //! catalogue value): the width of each tooth's force pulse in a narrow cut shows it, and a helix a few
  //! degrees off changes the peak of such a cut by as much as the runout does. The result is
  //! MechanisticModel::helix_deg.
  bool identify_helix = false;
  //! Also fit the size-effect exponent m (MechanisticModel::size_exponent, in [0, 0.6]) with the reference chip
  //! h_ref at the tests' geometric mean f_z, after the runout, helix and sensor: a one-dimensional search of the
  //! coefficients' fit residual over m (with m fixed the force is linear in them). It needs tests at more than
  //! one feed; the exponent shows in how the force grows with the chip, against the edge coefficients.
  bool identify_size_effect = false;
  //! Also fit the dynamometer's two XY modes (SensorResponse: natural frequency, damping, direction), which
  //! make it ring at every tooth pulse: the bins are matched with the kernel's force as the sensor reads it.
  //! Every test needs its spindle_rpm. The result is MechanisticIdentification::sensor; the coefficients are
  //! then those of the force on the tool, not of the reading.
  bool identify_sensor = false;
  //! With identify_sensor: the range searched for the natural frequencies, Hz (a table dynamometer with a
  //! workpiece: its first modes lie between a few hundred hertz and a few kilohertz). The upper end is
  //! lowered to the bins' Nyquist frequency (bins/2 · rpm/60) of the test with the lowest, above which the
  //! synchronous averages hold no harmonic; the result says so.
  double sensor_min_frequency_hz = 300.0;
  double sensor_max_frequency_hz = 3000.0;  //!< upper end of that range, Hz
  //! Match the tests' mean per-revolution peaks along with the bins, where tests have them (last step, with
  //! the runout, helix, size effect, sensor and phases held): the mean of the peaks a sensor reads is not the
  //! peak of the synchronous average — noise, the scatter of a real cut from one revolution to the next and
  //! a dynamometer that rings all raise it — and that mean is what a plan holds. The bins then decide what
  //! the peaks leave free. Weights: the bins by their residual variance, each peak by its standard error
  //! and the scatter of the peaks about the model beyond it (estimated).
  bool match_peaks = true;
};

//! Whether the tests could separate the coefficients.
enum class IdentificationStatus {
  kIdentified,       //!< the four XY coefficients are determined by the tests
  kIllConditioned,   //!< a fit was made, but some combination of coefficients is poorly determined
};

//! The fitted model, how well it fits, and what the tests cannot tell.
struct MechanisticIdentification {
  //! K_tc, K_rc, K_te, K_re fitted; K_ac = K_ae = 0 (not identifiable from Fx, Fy); with identify_size_effect
  //! the size effect (else none), the coefficients then holding at its reference chip. With
  //! identify_runout, runout_mm per tooth with the smallest at 0, tooth 0 being the tooth at the kernel's
  //! tooth-0 position at the first test's phase (without an encoder the physical tooth is not known, so the
  //! runout is known up to a rotation of the tooth numbers); else empty.
  MechanisticModel model;
  bool runout_converged = false;  //!< with identify_runout: Ceres reported a usable solution
  std::string runout_report;      //!< with identify_runout: Ceres' one-line summary
  //! With identify_sensor: the dynamometer's modes the tests show, in the tests' force frame; else empty.
  //! The bins are fitted through it, and the covariance is conditional on it.
  std::optional<SensorResponse> sensor;
  bool sensor_converged = false;  //!< with identify_sensor: Ceres reported a usable solution
  std::string sensor_report;      //!< with identify_sensor: Ceres' one-line summary
  IdentificationStatus status = IdentificationStatus::kIdentified;
  //! Covariance of (K_tc, K_rc, K_te, K_re), σ²·(AᵀA)⁻¹ with A the regressors at the found phases and
  //! σ² the residual variance (sum of squares over rows − 4), or with peaks matched that of the weighted
  //! fit to bins and peaks; units N²/mm⁴, N²/mm³, N²/mm².
  std::array<std::array<double, 4>, 4> covariance{};
  double rms_residual_n = 0.0;         //!< RMS of the bin residuals over all tests and both axes, N
  double condition_number = 0.0;       //!< of the regressor matrix with columns scaled to unit norm
  std::vector<double> phase_rad;       //!< per test, the spindle angle Ω₀ of the kernel at bin 0's start, rad
  std::vector<double> test_rms_residual_n;  //!< per test, RMS bin residual, N (of the bins' own fit)
  int tests_peak_matched = 0;          //!< tests whose mean peak was matched (0: the bins alone)
  double peak_rms_residual_n = 0.0;    //!< with peaks matched: RMS of measured − predicted mean peak, N
  double peak_scatter_n = 0.0;         //!< with peaks matched: their scatter about the model beyond their standard errors, N
  double matched_rms_residual_n = 0.0;  //!< with peaks matched: RMS of the bin residuals at the final coefficients, N
  //! What the tests cannot identify, in words ("K_ac, K_ae: the tests hold only Fx, Fy …").
  std::vector<std::string> unidentifiable;
};

//! Every problem with the tests: at least one; per test, a cutter that passes validate(), an arc with
//! entry < exit, a_p and f_z finite and > 0, Fx and Fy of equal length, at least 8 bins, all finite; with
//! `identify_runout`, every test with the first test's flute count, at least 2; with `identify_sensor`,
//! every test's spindle_rpm finite and > 0; every revolution peak finite and > 0.
std::vector<InputProblem> validate(const std::vector<MechanisticCuttingTest>& tests, bool identify_runout = false,
                                   bool identify_sensor = false);

//! Every problem with the options: with identify_sensor, a frequency range with 0 < min < max, finite.
std::vector<InputProblem> validate(const MechanisticIdentificationOptions& options);

//! Fits K_tc, K_rc, K_te, K_re (and, on request, the runout, helix and sensor) to the tests' synchronous
//! averages, each test with its own phase (see the file comment). The covariance is conditional on the
//! phases, runout and sensor found. Throws InputError with both validate()s' problems. Always returns a fit; when the tests
//! leave a combination of coefficients poorly determined (condition number above the option's, e.g.
//! every test at one feed, where cutting and edge terms are told apart only by the pulse's shape) the
//! status is kIllConditioned and `unidentifiable` says which combination and why.
MechanisticIdentification identify_mechanistic(const std::vector<MechanisticCuttingTest>& tests,
                                               const MechanisticIdentificationOptions& options = {});

//! K_tc, K_rc, K_te, K_re refitted to `tests` by identify_mechanistic's last, linear step, with each test's
//! spindle-angle phase (`phase_rad`, one per test, as MechanisticIdentification::phase_rad) and `fixed`'s
//! runout and size effect held: a leave-one-out check refits this way, where searching the phases and the
//! runout again for every left-out test would cost a whole identification each. The tests' peaks are matched
//! as identification matches them (`match_peaks`). Returns `fixed` with the four coefficients replaced. Throws InputError with validate()'s problems, or for a phase count that
//! is not the test count.
MechanisticModel refit_coefficients(const std::vector<MechanisticCuttingTest>& tests,
                                    const std::vector<double>& phase_rad, const MechanisticModel& fixed,
                                    bool match_peaks = true);

}  // namespace feedplan::model
