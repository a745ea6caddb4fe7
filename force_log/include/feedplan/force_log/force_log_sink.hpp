#pragma once
// Where a force log goes while it is being recorded, row by row: a file (force_log_file_writer.hpp),
// memory, a plot, or several of them — so a long recording need not be held whole. A data-acquisition
// run (the virtual machine's) gives the header once, then the rows in time order.

#include <utility>
#include <vector>

#include "feedplan/force_log/force_log.hpp"

namespace feedplan::force_log {

//! A consumer of a force log as it is recorded.
class ForceLogSink {
 public:
  virtual ~ForceLogSink() = default;
  //! The log's metadata and flags (its rows are not read), once, before any row.
  virtual void begin(const ForceLog& header) = 0;
  //! The next row (times increasing).
  virtual void add(const ForceLogRow& row) = 0;
};

//! Keeps the log in memory: the header and every row, in `log` (which must outlive the sink).
class ForceLogInMemory final : public ForceLogSink {
 public:
  explicit ForceLogInMemory(ForceLog& log) : log_(log) {}
  void begin(const ForceLog& header) override {
    log_.metadata = header.metadata;
    log_.has_positions = header.has_positions;
    log_.has_forces = header.has_forces;
    log_.has_currents = header.has_currents;
    log_.rows.clear();
  }
  void add(const ForceLogRow& row) override { log_.rows.push_back(row); }

 private:
  ForceLog& log_;
};

//! Passes the log on to several sinks (each must outlive this one), in the order given.
class ForceLogFanOut final : public ForceLogSink {
 public:
  explicit ForceLogFanOut(std::vector<ForceLogSink*> sinks) : sinks_(std::move(sinks)) {}
  void begin(const ForceLog& header) override {
    for (ForceLogSink* sink : sinks_) sink->begin(header);
  }
  void add(const ForceLogRow& row) override {
    for (ForceLogSink* sink : sinks_) sink->add(row);
  }

 private:
  std::vector<ForceLogSink*> sinks_;
};

}  // namespace feedplan::force_log
