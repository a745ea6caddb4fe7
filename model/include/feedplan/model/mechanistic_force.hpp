#pragma once
// The mechanistic force kernel (Altintas, Manufacturing Automation, ch. 2; docs/method.md §6.1): the
// force of every tooth of a helical flat end mill on the exact engaged arcs of each section, the peak
// of the XY resultant over a revolution, the mean force, and the matrix that maps the six coefficients
// to the force for identification.
//
// Teeth. Teeth j = 0 … N−1 are numbered in the order they pass a point of the tool circle, so tooth j
// follows tooth j−1 (mod N). At spindle angle Ω (the tip immersion of tooth 0) the point of tooth j at
// height z above the tip has the immersion
//   φ_j(z) = Ω − j·2π/N − z·tan β / r        (the flute lags the tip by z·tan β / r).
//
// Chip. On a straight cut the centre advances f_z per tooth along +x, so tooth j's point at φ reaches
// k·f_z·sin φ beyond the circle cut k teeth earlier; with runout r_j the chip is the smallest of those
// reaches (Altintas, ch. 2, h_j = f_z sin φ + r_j − r_{j−1}, carried to the k-th previous tooth so that a
// tooth that cuts deep leaves less for the next ones — Kline & DeVor 1983):
//   h_j(φ) = min_{k = 1…N} ( k·f_z·sin φ + r_j − r_{j−k} ),      h_j(φ) = f_z·sin φ without runout.
// An element cuts, with its cutting and edge forces, where φ lies in an engaged arc and h > 0.
//
// Frame and sign. The force on the tool in the feed frame of engaged_section.hpp (x along the feed, y to
// its left, z up the tool axis):
//   dF_x = −dF_t cos φ − dF_r sin φ,   dF_y = dF_t sin φ − dF_r cos φ,   dF_z = dF_a.
//
// Integration along z. Along a flute dz = dφ / (tan β / r), so each tooth's force on a section is an
// integral over the immersions its flute spans there, intersected with the engaged arcs (straight
// flutes: the tip's immersion times the section height). Without size effect and runout, h = f_z sin φ
// and the integrals of sin φ cos φ, sin² φ, sin φ and cos φ are evaluated in closed form. Otherwise each
// tooth's integrals are tabulated once per call against the immersion over the arcs' range, on steps
// of 0.5°, each step integrated by the midpoint rule (a step where h changes sign only over its part
// with h > 0, the root found by linear interpolation), and read between steps by linear interpolation
// of the running integral. The integrand is smooth within a step, so the error is of order step²/8 of
// its slope, about 1e-5 of the force — far below the model's own uncertainty.

#include <array>
#include <span>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/model/engaged_section.hpp"
#include "feedplan/model/mechanistic_model.hpp"

namespace feedplan::model {

//! Largest immersion cell of the numerical integration of the mean force (size effect or runout), rad: 1°.
inline constexpr double kChipCellRad = 3.14159265358979323846 / 180.0;
//! Spindle angles sampled per tooth period for the peak, before the best candidates are refined.
inline constexpr int kPeakStepsPerToothPeriod = 64;
//! Spindle angles sampled per tooth period for the peak with runout, over the whole revolution: a
//! coarser scan, whose local maxima are refined more widely.
inline constexpr int kPeakStepsPerToothPeriodRunout = 16;
//! Local maxima of the sampled force refined by golden-section search for the peak.
inline constexpr int kPeakCandidates = 3;

//! Force on the tool in the feed frame, N.
struct MechanisticForce {
  double fx_n = 0.0;  //!< along the feed
  double fy_n = 0.0;  //!< normal to the feed, to its left
  double fz_n = 0.0;  //!< along the tool axis, up
};

//! Column of each coefficient in ForceRegressors::rows.
enum MechanisticCoefficient { kKtc = 0, kKrc = 1, kKac = 2, kKte = 3, kKre = 4, kKae = 5 };

//! The force is linear in the six coefficients for a given engagement, feed and size effect:
//! (F_x, F_y, F_z) = rows · (K_tc, K_rc, K_ac, K_te, K_re, K_ae). Rows 0 and 1 are the 2×6 map to the
//! XY force (their K_ac and K_ae columns are 0); row 2 maps to F_z. Units: mm² for the cutting
//! columns, mm for the edge columns.
struct ForceRegressors {
  std::array<std::array<double, 6>, 3> rows{};  //!< [F_x, F_y, F_z][MechanisticCoefficient]
};

//! The coefficients of `model` in MechanisticCoefficient order.
std::array<double, 6> coefficients(const MechanisticModel& model);

//! Problems with the model (validate(model)) and the cutter: radius finite and > 0, at least one
//! flute, helix in (−90, 90) deg, and either no runout or one value per flute
//! ("mechanistic.runout_mm has 3 values: must be empty or one per flute (4)").
std::vector<InputProblem> validate(const MechanisticModel& model, const CutterGeometry& cutter,
                                   const std::string& field_prefix = "mechanistic.");

//! The regressors at spindle angle `spindle_angle_rad` (Ω above) for feed per tooth `feed_per_tooth_mm`
//! on `sections`. Of `model` only the size effect and the runout are used (the force is linear in the
//! coefficients for those fixed). Needs a model and cutter that pass validate() and f_z > 0 (asserted;
//! validate once, not per call). Sections with top ≤ bottom or no arcs add nothing.
ForceRegressors regressors(const MechanisticModel& model, std::span<const EngagedSection> sections,
                           const CutterGeometry& cutter, double feed_per_tooth_mm, double spindle_angle_rad);

//! regressors() at each of `spindle_angles_rad`, on one engagement and feed: what every angle shares — the
//! teeth's chip rules and, with the size effect or runout, each tooth's integrals tabulated over the arcs —
//! is set up once, not per angle (with runout, the set-up costs more than a few hundred angles' sums).
//! The same values as regressors() angle by angle. Same requirements as regressors().
std::vector<ForceRegressors> regressors_at_angles(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                                  const CutterGeometry& cutter, double feed_per_tooth_mm,
                                                  std::span<const double> spindle_angles_rad);

//! The force at spindle angle `spindle_angle_rad`: regressors(…) times the model's coefficients.
//! Same requirements as regressors().
MechanisticForce predicted_force(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                 const CutterGeometry& cutter, double feed_per_tooth_mm, double spindle_angle_rad);

//! The largest |F_xy| = √(F_x² + F_y²) over one spindle revolution, N. Sampling: without runout the
//! force repeats every tooth period 2π/N, and Ω is sampled at kPeakStepsPerToothPeriod points of one
//! period; the kPeakCandidates largest local maxima of the samples (those within 2 % of the largest
//! sample) are then refined by golden-section search between their neighbours, to 1e-5 rad — as good for
//! a peak at a kink (a tooth entering) as for a smooth one, when the samples bracket it. With runout the
//! whole revolution is sampled, more coarsely, at kPeakStepsPerToothPeriodRunout points per tooth
//! period, and the max(kPeakCandidates, N) largest local maxima within 10 % of the largest sample are
//! refined the same way (within 1e-5 of a scan of 256 points per tooth period with every maximum refined,
//! on random engagements and runouts). The result is always a force the kernel reaches at some Ω.
//! Same requirements as regressors(); 0 with nothing engaged.
double predicted_peak_force_n(const MechanisticModel& model, std::span<const EngagedSection> sections,
                              const CutterGeometry& cutter, double feed_per_tooth_mm);

//! The peak of |F_xy| over a revolution and the spindle angle at which the kernel reaches it.
struct MechanisticPeak {
  double force_n = 0.0;            //!< largest |F_xy| over one spindle revolution, N (predicted_peak_force_n)
  double spindle_angle_rad = 0.0;  //!< Ω at which it is reached, rad, in [−2π/N, 2π) (0 with nothing engaged)
};

//! predicted_peak_force_n() with the spindle angle of the peak, found by the same scan and refinement
//! (predicted_peak_force_n returns its force). For propagating the coefficients' uncertainty to the peak:
//! at the peak's angle the regressors give the force's gradient in the coefficients. Same requirements.
MechanisticPeak predicted_peak(const MechanisticModel& model, std::span<const EngagedSection> sections,
                               const CutterGeometry& cutter, double feed_per_tooth_mm);

//! The mean force over one spindle revolution. Averaging over Ω turns each tooth's integral along its
//! flute into (section height / 2π) × the integral over the engaged arcs, independent of the helix;
//! that is evaluated in closed form without size effect and runout (Altintas' mean forces), on 1° cells
//! otherwise. Same requirements as regressors().
MechanisticForce predicted_mean_force(const MechanisticModel& model, std::span<const EngagedSection> sections,
                                      const CutterGeometry& cutter, double feed_per_tooth_mm);

}  // namespace feedplan::model
