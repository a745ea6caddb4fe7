#pragma once
// The force plot of a log that is never held whole: the rows pass through (a force_log::ForceLogSink)
// and only min/max buckets of |F_xy| are kept — at most kMaxBuckets of them, each keeping its first,
// smallest, largest and last sample, twice as wide whenever there would be more. Every peak and
// trough stays, as force_plot_svg's own min/max decimation (force_plot.hpp) would keep them from the
// whole log; the plot is drawn from these few samples.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/force_log/force_log_sink.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/sim/force_plot.hpp"

namespace feedplan::sim {

//! Collects the |F_xy| series of a force log for a plot, in bounded memory.
class ForcePlotCollector final : public force_log::ForceLogSink {
 public:
  //! Buckets kept at most; the series has at most 4 samples per bucket.
  static constexpr std::size_t kMaxBuckets = 8192;

  void begin(const force_log::ForceLog& header) override;
  void add(const force_log::ForceLogRow& row) override;

  //! The plot of what was collected, as force_plot_data would make it from the whole log.
  ForcePlotData data(const std::string& title, std::vector<force_log::RevolutionPeak> peaks = {},
                     std::optional<double> target_force_n = std::nullopt) const;

 private:
  struct Sample {
    double t_s = 0.0;
    double value_n = 0.0;
  };
  struct Bucket {
    Sample first, low, high, last;
  };
  void widen();

  bool has_forces_ = true;
  bool started_ = false;
  double t0_s_ = 0.0;
  double width_s_ = 0.0;  // bucket width; 0 until the second row sets it to the row spacing
  std::vector<Bucket> buckets_;
  std::vector<bool> used_;
};

}  // namespace feedplan::sim
