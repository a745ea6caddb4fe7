#pragma once
// Internal to the virtual machine (milling_simulation.cpp): the force log on its own clock. The
// machine runs at its internal step; the log has a row every 1 / rate seconds from t = 0, each
// interpolated linearly between the internal steps around it (the spindle speed, a step function, is
// taken from the nearer step).

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/force_log_sink.hpp"

namespace feedplan::sim::detail {

//! Hands log rows to a sink as internal steps arrive.
class LogResampler {
 public:
  //! Rows go to `sink`, which must outlive the object, at `log_rate_hz` (> 0).
  LogResampler(force_log::ForceLogSink& sink, double log_rate_hz) : sink_(sink), log_dt_(1.0 / log_rate_hz) {}

  //! Takes the readings of the next internal step (times increasing) and writes every log row due up
  //! to its time.
  void add(const force_log::ForceLogRow& step_row);

  //! Rows written so far.
  long long rows() const { return next_log_; }

 private:
  force_log::ForceLogSink& sink_;
  double log_dt_;
  long long next_log_ = 0;
  force_log::ForceLogRow previous_row_;
  bool have_previous_row_ = false;
};

}  // namespace feedplan::sim::detail
