#pragma once
// Internal to the virtual machine (milling_simulation.cpp): per-revolution peak and mean of the true
// force |F_xy| at every internal step, revolutions counted by the simulated spindle angle (so they
// follow the spindle speed of each block, not a fixed period).

#include <vector>

#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::sim::detail {

//! Collects one RevolutionPeak per spindle revolution.
class RevolutionStatistics {
 public:
  //! Takes the force `fxy_n` of the step at time `t_s` with the spindle at `spindle_angle_rad`; a
  //! revolution ends where the angle passes a whole turn.
  void add(double t_s, double spindle_angle_rad, double fxy_n);

  //! Ends the last revolution at `t_end_s` and returns every revolution in order.
  std::vector<force_log::RevolutionPeak> finish(double t_end_s);

 private:
  void close_revolution(double t_end_s);

  std::vector<force_log::RevolutionPeak> revolutions_;
  int revolution_ = 0;
  force_log::RevolutionPeak current_;
  double sum_n_ = 0.0;
  long long steps_ = 0;
};

}  // namespace feedplan::sim::detail
