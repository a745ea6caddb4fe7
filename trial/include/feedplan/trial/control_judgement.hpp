#pragma once
// How well a run held its target, judged on the virtual machine's true per-revolution peaks of |F_xy|
// (sim::SimulationResult::revolutions: the cutting force itself, before any sensor) — a truth no
// controller sees, whichever sensor it was given.

#include <vector>

#include "feedplan/sim/milling_simulation.hpp"  // force_log::RevolutionPeak, the simulation's true peaks

namespace feedplan::trial {

//! A revolution is judged as in cut when its true peak is at least this share of the target: the first
//! and last slivers of a cut, where no feed could reach the target, are left out of the error figures.
inline constexpr double kJudgedInCutFraction = 0.2;

//! The figures `feedplan control` prints.
struct ControlJudgement {
  double target_force_n = 0.0;          //!< the target, N
  double max_peak_n = 0.0;              //!< largest true per-revolution peak, N
  double max_overshoot_percent = 0.0;   //!< (max_peak_n / target − 1) × 100, % (negative: never reached)
  int in_cut_revolutions = 0;           //!< revolutions with a true peak ≥ kJudgedInCutFraction × target
  double rms_error_n = 0.0;             //!< RMS of (peak − target) over those, N
  double rms_error_percent = 0.0;       //!< the same relative to the target, %
  double within_5_percent_share = 0.0;  //!< share of those with |peak − target| ≤ 5 % of the target, in [0, 1]
  double time_above_target_s = 0.0;     //!< summed length of the revolutions whose peak exceeds the target, s
  double cycle_time_s = 0.0;            //!< the run's cycle time, s
};

//! The figures for `revolutions` (true peaks, in order) against `target_force_n` (> 0, asserted) with the
//! run's `cycle_time_s`. In-cut figures are 0 when no revolution is in cut.
ControlJudgement judge_control(const std::vector<force_log::RevolutionPeak>& revolutions, double target_force_n,
                               double cycle_time_s);

}  // namespace feedplan::trial
