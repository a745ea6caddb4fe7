#pragma once
// Feed-drive servo currents as force sensors (seed 002, Kim & Kim 1996, Eqs. 12–14; docs/method.md §6.4):
// the static map I = a + b·|F| per axis, fitted from a log with both forces and currents, and applied to
// a log with currents only.
//
// What currents can tell: the current loop's bandwidth (≈ 62 Hz in seed 002) is far below the tooth
// frequency (187 Hz for 4 flutes at 2800 rpm), so the current follows the MEAN axis force, not the tooth
// peaks. The fit therefore compares means over windows (whole spindle revolutions, about 50 ms), the way
// seed 002's Fig. 4 relates steady-cutting currents and forces, not row by row (a row-by-row fit would
// regress the slow current on the force's tooth ripple and come out too flat). And forces made from
// currents are mean forces: their per-revolution "peaks" lie well below the true peaks the force model
// (seed 003 Eq. 1) describes, by a factor that depends on the engagement. Learning a peak model from them
// needs that factor (e.g. from a cutting test with a dynamometer); do not feed them to measured_revolutions
// as if they were dynamometer forces.

#include "feedplan/force_log/force_log.hpp"

namespace feedplan::learning {

//! I = a + b·|F| for one feed axis.
struct AxisCalibration {
  double a_a = 0.0;        //!< current with the axis moving and no cutting force, A
  double b_a_per_n = 0.0;  //!< current per newton of cutting force along the axis, A/N (> 0 when usable)
  double r_squared = 0.0;  //!< coefficient of determination of the fit over the windows, in [0, 1]
  int windows = 0;         //!< windows (whole revolutions, ≈ 50 ms) the fit used
};

//! The three axes.
struct CurrentCalibration {
  AxisCalibration x;  //!< x axis
  AxisCalibration y;  //!< y axis
  AxisCalibration z;  //!< z axis (windows = 0 and b = 0 when the log has no z force or current)
};

//! Window over which currents and forces are averaged before fitting, s (rounded to whole revolutions
//! when the log gives the spindle speed; far above the current loop's time constant ≈ 1/(2π·62 Hz)).
inline constexpr double kCalibrationWindowS = 0.05;

//! Fits I = a + b·|F| per axis by least squares over window means of the current and of the signed axis
//! force (|mean F|: the current loop filters the signed force, seed 002 Eq. 11), rows with a NaN left
//! out. Needs a log with forces (has_forces) and currents (has_currents). Throws InputError naming the
//! problem when either is missing, when the x or y axis has fewer than three windows, or when its force
//! does not vary (spread of the window means below 1 N: nothing to fit a slope on) or the fitted slope is
//! not positive. z is fitted when it has data and variation, else left at zero windows.
CurrentCalibration fit_current_calibration(const force_log::ForceLog& log_with_forces_and_currents);

//! The log with forces made from its currents: |F_axis| = (I − a)/b per row and axis (not clamped at 0,
//! so noise stays zero-mean; the sign is meaningless, currents give magnitudes). fz_n from iz_a when the
//! z calibration has b > 0, else NaN. has_forces becomes true, currents are kept, and a metadata line
//! says where the forces come from. These are mean forces, not tooth peaks (see the top of this file).
//! Throws InputError when the log has no currents or the x or y calibration has b ≤ 0.
force_log::ForceLog forces_from_currents(const force_log::ForceLog& current_log, const CurrentCalibration& calibration);

}  // namespace feedplan::learning
