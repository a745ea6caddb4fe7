#pragma once
// One force log from several runs of the virtual machine one after another (the tool runs of a program of
// several tools, each simulated from its own t = 0): the first run's header is the log's, later headers are
// dropped, and every row is moved to the program's clock by the start of its run. The rows stay in the
// documented format (force_log.hpp); between runs that record nothing (a drill, rapids only) the log has a gap.

#include <string>
#include <utility>
#include <vector>

#include "feedplan/force_log/force_log_sink.hpp"

namespace feedplan::cli {

//! Passes the runs' logs on to `sink` (which must outlive this one) as one log.
class JoinedForceLog final : public force_log::ForceLogSink {
 public:
  explicit JoinedForceLog(force_log::ForceLogSink& sink) : sink_(sink) {}

  //! The program time, s, at which the next run's t = 0 lies.
  void start_run_at(double t_s) { offset_s_ = t_s; }

  void begin(const force_log::ForceLog& header) override {
    if (begun_) return;
    begun_ = true;
    sink_.begin(header);
  }

  void add(const force_log::ForceLogRow& row) override {
    force_log::ForceLogRow shifted = row;
    shifted.t_s += offset_s_;
    sink_.add(shifted);
  }

  //! True once a run has given the header.
  bool begun() const { return begun_; }

 private:
  force_log::ForceLogSink& sink_;
  double offset_s_ = 0.0;
  bool begun_ = false;
};

}  // namespace feedplan::cli
