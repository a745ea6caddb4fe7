#pragma once
// Prediction intervals for the peak XY force per spindle revolution (docs/method.md §5.8): how far a
// revolution's measured peak may lie from what a model predicts, from two sources of spread.
//
//   fit σ     the coefficients are estimates: their covariance C, propagated to the force through its
//             gradient g in the coefficients, σ_fit² = gᵀ C g (the delta method; exact for the response
//             surface, which is linear in β: g = ψ, seed 003 Eq. 4);
//   spread σ  the peaks scatter from revolution to revolution about their mean even at fixed conditions
//             (runout, chip-load carry-over, vibration): σ_spread = s_rel · F̂, with s_rel the relative
//             standard deviation the cutting tests showed (revolution_spread.hpp).
//
// The interval is F̂ ± z · √(σ_fit² + σ_spread²): with z = 2 about 95 % of revolutions' peaks when both
// parts are Gaussian and C is right. What it does not hold is the bias of a model whose shape is wrong
// (a size effect the model lacks, extrapolation far beyond the tests): C measures the noise only.

#include <array>
#include <span>

#include "feedplan/model/covariance.hpp"
#include "feedplan/model/engaged_section.hpp"
#include "feedplan/model/mechanistic_model.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/model/sensor_response.hpp"

namespace feedplan::model {

//! A predicted peak with its interval and the two standard deviations it is made of.
struct PredictionInterval {
  double predicted_n = 0.0;  //!< F̂, the predicted peak XY force per spindle revolution, N
  double lower_n = 0.0;      //!< F̂ − z·√(fit_sd_n² + spread_sd_n²), N
  double upper_n = 0.0;      //!< F̂ + z·√(fit_sd_n² + spread_sd_n²), N
  double fit_sd_n = 0.0;     //!< standard deviation of F̂ from the coefficients' covariance, N
  double spread_sd_n = 0.0;  //!< revolution-to-revolution standard deviation of the peak, s_rel · F̂, N
};

//! The interval of the response surface at t_m = chip_mm, L = contact_length_mm: F̂ = βᵀψ (predict()),
//! σ_fit = √(ψᵀ C ψ) with ψ the regressors (model_prediction.hpp) and C = `covariance` (of β, N²),
//! σ_spread = revolution_spread_rel · |F̂|. Needs a model that passes validate(), a covariance with finite
//! entries and a non-negative diagonal, t_m and L finite and ≥ 0, revolution_spread_rel finite and ≥ 0,
//! z finite and > 0; otherwise throws feedplan::InputError listing every problem (fields "chip_mm",
//! "contact_length_mm", "revolution_spread_rel", "z", "covariance[k]", and validate()'s "model.…"). A
//! point outside the fitted range is not an error: the interval is then an extrapolation's.
PredictionInterval response_surface_interval(const ResponseSurfaceModel& model, const Covariance& covariance,
                                             double chip_mm, double contact_length_mm, double revolution_spread_rel,
                                             double z = 2.0);

//! The interval of the mechanistic peak (predicted_peak, mechanistic_force.hpp) on `sections` at feed per
//! tooth `feed_per_tooth_mm`. `covariance` is that of (K_tc, K_rc, K_te, K_re), in that order and units
//! (MechanisticIdentification::covariance). At the spindle angle Ω* of the peak, with R the 2×6 XY rows of
//! the regressors and u = (F_x, F_y)/|F_xy| there, the gradient of |F_xy| in the coefficients is uᵀR; its
//! K_tc, K_rc, K_te, K_re entries g give σ_fit = √(gᵀ C g). The peak's angle moves with the coefficients,
//! but |F_xy| is stationary in Ω there (or at a kink every nearby draw shares), so to first order that adds
//! nothing. The size effect and runout of `model` are held fixed (C is conditional on them, as
//! identification reports it). σ_spread = revolution_spread_rel · F̂.
//!
//! Needs a model and cutter that pass validate(model, cutter), sections with finite bottom ≤ top and finite
//! arcs with entry ≤ exit, f_z finite and > 0, a covariance with finite entries and a non-negative
//! diagonal, revolution_spread_rel finite and ≥ 0 and z finite and > 0; otherwise throws
//! feedplan::InputError listing every problem (fields "mechanistic.…", "sections[i].…",
//! "feed_per_tooth_mm", "covariance[i][j]", "revolution_spread_rel", "z"). With nothing engaged the
//! interval is [0, 0].
PredictionInterval mechanistic_peak_interval(const MechanisticModel& model,
                                             const std::array<std::array<double, 4>, 4>& covariance,
                                             std::span<const EngagedSection> sections, const CutterGeometry& cutter,
                                             double feed_per_tooth_mm, double revolution_spread_rel, double z = 2.0);

//! The interval of the peak the dynamometer `sensor` reads at `spindle_rpm` (predicted_sensed_peak,
//! sensed_peak.hpp), for comparing with a cutting test's measured per-revolution peaks when the dynamometer
//! rings. As mechanistic_peak_interval, with the reading's regressors at the angle of its peak in place of
//! the force's (the reading is linear in the coefficients). The sensor is held fixed: `covariance` is
//! conditional on it, as identification reports it. Same requirements, and a sensor that passes
//! validate(sensor) (fields "sensor.…") and spindle_rpm finite and > 0 ("spindle_rpm"); otherwise throws
//! feedplan::InputError listing every problem.
PredictionInterval mechanistic_sensed_peak_interval(const MechanisticModel& model,
                                                    const std::array<std::array<double, 4>, 4>& covariance,
                                                    std::span<const EngagedSection> sections,
                                                    const CutterGeometry& cutter, double feed_per_tooth_mm,
                                                    const SensorResponse& sensor, double spindle_rpm,
                                                    double revolution_spread_rel, double z = 2.0);

//! `interval` with its model part widened to the error the model showed on cutting tests it was not fitted
//! on: the fit σ becomes max(fit σ, cross_validated_rel · |F̂|), with cross_validated_rel the leave-one-out
//! RMS error relative to the tests' mean peak. The covariance measures only the noise of the coefficients;
//! a model whose shape is not quite the machine's (a size effect it lacks, a sensor it does not model) errs
//! by more, and the leave-one-out error is the measured size of that. Throws InputError for
//! cross_validated_rel not finite and ≥ 0 ("cross_validated_rel") or z not finite and > 0 ("z").
PredictionInterval with_cross_validated_error(const PredictionInterval& interval, double cross_validated_rel,
                                              double z = 2.0);

}  // namespace feedplan::model
