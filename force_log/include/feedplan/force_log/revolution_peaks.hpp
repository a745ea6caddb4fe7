#pragma once
// The peak of the XY resultant force in each spindle revolution: the quantity seed 003's model
// (Eq. 1) predicts and seed 002's controller regulates (docs/method.md §5.3). Used on simulated logs and
// on measured ones (e.g. Kistler exports).
//
// Revolutions are counted from the first sample: revolution k covers the spindle angle
// [k, k + 1) turns after it, i.e. with a constant speed the time window [t0 + k T, t0 + (k + 1) T),
// T = 60 / rpm. A sample belongs to the window its time falls in; to keep samples that sit exactly on
// a boundary (t0 + k T up to rounding) in the later window, the angle is rounded up by 1e-6 turn first.
// With a per-sample speed the angle is integrated by the trapezoidal rule. Only complete revolutions
// are returned: the last window is dropped unless the samples reach its end (the last sample is less
// than one mean sample spacing before it). A window without samples (a gap in the data) is skipped,
// so revolution numbers may jump.

#include <cstddef>
#include <string>
#include <vector>

namespace feedplan::force_log {

//! The force in one spindle revolution.
struct RevolutionPeak {
  long revolution = 0;         //!< 0 for the revolution starting at the first sample
  double t_start_s = 0.0;      //!< time the revolution starts, s
  double t_end_s = 0.0;        //!< time it ends (the next one starts), s
  double peak_xy_n = 0.0;      //!< largest |F_xy| = sqrt(Fx² + Fy²) over its samples, N
  double t_peak_s = 0.0;       //!< time of that sample, s
  double mean_xy_n = 0.0;      //!< mean |F_xy| over its samples, N
  std::size_t samples = 0;     //!< samples in the window
};

//! Per-revolution peaks at a constant spindle speed. `t_s`, `fx_n`, `fy_n` are samples of equal
//! length with strictly increasing times. Throws feedplan::InputError when the spindle speed is not
//! finite and > 0, the times do not increase (field "t_s[i]") or a force is not finite ("fx_n[i]");
//! lengths that differ are a programmer error (assert). Returns one entry per complete revolution, in order; none for fewer than two samples.
std::vector<RevolutionPeak> revolution_peaks(const std::vector<double>& t_s, const std::vector<double>& fx_n,
                                             const std::vector<double>& fy_n, double spindle_rpm);

//! The same with the spindle speed of every sample (`spindle_rpm` as long as `t_s`, each finite and > 0;
//! a bad one is an InputError naming "spindle_rpm[i]").
std::vector<RevolutionPeak> revolution_peaks(const std::vector<double>& t_s, const std::vector<double>& fx_n,
                                             const std::vector<double>& fy_n, const std::vector<double>& spindle_rpm);

//! The peaks as CSV: header `revolution,t_start_s,t_end_s,t_peak_s,peak_xy_n,mean_xy_n`, one row per
//! revolution; times to 1 µs, forces to 1 mN, '.' as the decimal point whatever the locale.
std::string format_revolution_peaks(const std::vector<RevolutionPeak>& peaks);

//! Writes format_revolution_peaks(peaks) to `path` atomically. Returns "" on success, otherwise a
//! message naming the path and the reason; the target is then left as it was.
std::string write_revolution_peaks(const std::string& path, const std::vector<RevolutionPeak>& peaks);

}  // namespace feedplan::force_log
