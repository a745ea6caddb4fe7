#pragma once
// The figure seeds 000/001/002/004 report for a controller on a depth-step cut: per depth, the steady error
// — the largest |true per-revolution peak − target| over the revolutions that end in the depth's steady
// window (depth_step_slot.hpp) — judged on the virtual machine's true peaks, which no controller sees. A
// revolution is placed by the tool centre's x at its end, read from the force log's positions
// (PositionTrack, a log sink that keeps only time and x).

#include <vector>

#include "feedplan/force_log/force_log_sink.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/trial/depth_step_slot.hpp"

namespace feedplan::trial {

//! Keeps the time and the tool centre's x of every log row (hand it to the run as, or beside, its sink).
class PositionTrack final : public force_log::ForceLogSink {
 public:
  void begin(const force_log::ForceLog& header) override;
  void add(const force_log::ForceLogRow& row) override;
  //! The tool centre's x at the last row at or before `t_s`, mm (NaN before the first row).
  double x_at(double t_s) const;

 private:
  std::vector<double> t_s_;
  std::vector<double> x_mm_;
};

//! One depth's steady error.
struct DepthSteadyError {
  double depth_mm = 0.0;          //!< the depth, mm
  double from_x_mm = 0.0;         //!< the steady window along x, mm
  double to_x_mm = 0.0;
  int revolutions = 0;            //!< revolutions ending in the window
  double max_abs_error_n = 0.0;   //!< largest |peak − target| among them, N (0 when none)
  double mean_error_n = 0.0;      //!< their mean peak − target, N (0 when none)
};

//! The steady error of every segment of `slot`, in order, from the true `revolutions` placed by `track`
//! against `target_force_n`.
std::vector<DepthSteadyError> depth_steady_errors(const DepthStepSlot& slot,
                                                  const std::vector<force_log::RevolutionPeak>& revolutions,
                                                  const PositionTrack& track, double target_force_n);

}  // namespace feedplan::trial
