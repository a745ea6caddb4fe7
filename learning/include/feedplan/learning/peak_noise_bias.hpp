#pragma once
// How far a sensor's noise raises the peaks read from it. A per-revolution or per-tooth peak is the largest
// of many rows; with noise on every row the largest reading sits above the largest true force — by more
// the more rows lie near the top and the larger the noise (on the family's machines 1–2 % of a 400 N
// peak at 2–10 N noise). Learning that holds the reading at the target holds the true force under it.
//
// The noise is measured in the log itself, where the tool is out of the material: per axis, the spread
// of the rows of the revolutions the plan has out of the cut (1.4826 × the median absolute deviation from
// each window's median, robust to a transient at an exit), and its lag-1 correlation from row to row (a
// sensor sampled faster than its noise is white is correlated). The excess is then found by simulation
// and extrapolation (SIMEX, Cook and Stefanski 1994): on up to kNoiseBiasWindows of the log's tooth
// periods, the mean peak reading as read and with more noise of the same kind added (a first-order
// autoregressive series per axis, a fixed seed) so that the noise variance is u σ² for u = 2, 3, 4 — the
// same unit draws scaled to each level (common random numbers: the differences between levels, which
// the extrapolation magnifies, carry the level's effect and not the draws' scatter);
// S = P + k u^p fitted through the four means, taken back to u = 0, is the mean peak without noise.
// On pulses of known excess the estimate's spread over seeds is about ±12 % with kNoiseBiasDraws = 48
// (±35 % with 16 independent draws per level).
// Adding the noise once more to the readings alone would miss half the excess: their tops already hold
// a draw of it.

#include <cstddef>
#include <string>
#include <vector>

#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::learning {

//! Tooth periods the excess is simulated on at most.
inline constexpr std::size_t kNoiseBiasWindows = 300;
//! Noise draws per period (each scaled to every noise level).
inline constexpr int kNoiseBiasDraws = 48;
//! Rows out of the cut below which the noise is not estimated.
inline constexpr std::size_t kMinNoiseRows = 200;

//! The noise of a log and the excess it puts on the peaks.
struct PeakNoise {
  std::size_t air_rows = 0;     //!< rows the noise was measured on
  double sigma_n = 0.0;         //!< RMS noise per axis (mean of x and y), N
  double lag1 = 0.0;            //!< correlation of the noise from one row to the next, in [0, 1)
  double peak_excess_n = 0.0;   //!< how far the noise raises a tooth period's peak reading, N (0: not estimated)
  std::string message;          //!< for people
};

//! The noise from the rows of `air` windows (revolutions out of the cut) and its excess on the peaks of
//! `periods` (tooth periods in the cut), of the log's rows `t_s`, `fx_n`, `fy_n` (equal lengths, times
//! increasing). Fewer than kMinNoiseRows rows out of the cut, or no period: nothing estimated (0), said so.
PeakNoise peak_noise(const std::vector<double>& t_s, const std::vector<double>& fx_n, const std::vector<double>& fy_n,
                     const std::vector<force_log::RevolutionPeak>& air,
                     const std::vector<force_log::RevolutionPeak>& periods);

}  // namespace feedplan::learning
