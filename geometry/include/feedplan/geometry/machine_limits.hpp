#pragma once
// What a machine's feed drives and control can do: one type for the spec's `machine:` section, the
// planner (which keeps every commanded feed and acceleration inside it) and the virtual machine (whose
// motion runs under it). Each user reads the fields that concern it: the planner the feed range,
// acceleration, rapid rate and block time; the virtual machine the acceleration, rapid rate, largest
// feed, junction deviation and centripetal limit.

#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::geometry {

struct MachineLimits {
  double max_feed_mm_per_min = 10000.0;    //!< highest programmable feed; larger F run at it, mm/min
  double min_feed_mm_per_min = 10.0;       //!< lowest feed the planner may command, mm/min
  //! Path acceleration limit (tangential, both signs) and the centripetal limit on arcs, mm/s²
  //! (0.67 G on seed 003's VM4-II).
  double max_accel_mm_per_s2 = 6500.0;
  double rapid_feed_mm_per_min = 30000.0;  //!< rapid traverse rate (G0), mm/min
  double block_time_min_s = 0.002;         //!< shortest time the control can execute one block in, s
  //! δ of the junction-deviation rule of the look-ahead (grbl's $11); 0 stops at every corner that is
  //! not tangent-continuous, mm.
  double junction_deviation_mm = 0.01;
  bool limit_centripetal = true;  //!< cap arc speeds by v² ≤ max_accel_mm_per_s2 · arc radius
};

//! Every problem with the limits, fields named "machine.<field>", in field order: acceleration, rapid
//! rate and largest feed finite and > 0; smallest feed finite, > 0 and below the largest; block time in
//! [0, 1] s; junction deviation finite and ≥ 0. Empty when the limits are usable.
std::vector<InputProblem> validate(const MachineLimits& limits);

}  // namespace feedplan::geometry
