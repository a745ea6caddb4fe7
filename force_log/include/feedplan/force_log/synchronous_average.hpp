#pragma once
// The force over one spindle revolution, averaged over many (the revolution-synchronous average): at
// each spindle angle, the mean Fx and Fy of the revolutions given. Noise and the revolution-to-revolution
// scatter average out; what repeats every turn — the teeth's force pulses, each tooth's own chip under
// runout — stays. It is what identifying cutting coefficients and runout from a cutting test needs
// (seeds 002 and 003 regulate the peak; the shape of the pulses says which coefficient is which).
//
// Angles come from time: within revolution [t_start, t_end) a sample at t lies at the fraction
// (t − t_start) / (t_end − t_start) of the turn, and falls in bin ⌊fraction · bins⌋. The angle origin is
// each revolution's start (force_log::revolution_peaks counts them from the first sample), so the
// average is meaningful when the spindle speed is steady over the revolutions, as in a cutting test's
// steady part; the phase of the teeth against that origin is unknown (there is no encoder) and is for
// the identification to find.

#include <cstddef>
#include <vector>

#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::force_log {

//! Bins per revolution by default: 2° each.
inline constexpr int kSynchronousBins = 180;

//! The average force at `bins` equal spindle-angle bins over one revolution.
struct SynchronousAverage {
  std::vector<double> fx_n;      //!< mean Fx per bin, N (bins entries)
  std::vector<double> fy_n;      //!< mean Fy per bin, N
  int revolutions = 0;           //!< revolutions averaged
};

//! The synchronous average of the samples (`t_s`, `fx_n`, `fy_n`, equal lengths, times increasing) over
//! `revolutions` (windows from revolution_peaks on the same samples). The number of bins is `bins`,
//! lowered to half the fewest samples any of the revolutions has (two samples per bin on average); with
//! fewer than 4 bins, or a bin no sample falls in, or no revolutions, the result is empty.
SynchronousAverage synchronous_average(const std::vector<double>& t_s, const std::vector<double>& fx_n,
                                       const std::vector<double>& fy_n,
                                       const std::vector<RevolutionPeak>& revolutions, int bins = kSynchronousBins);

}  // namespace feedplan::force_log
