#include "feedplan/sim/force_plot_collector.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace feedplan::sim {

void ForcePlotCollector::begin(const force_log::ForceLog& header) {
  has_forces_ = header.has_forces;
  started_ = false;
  width_s_ = 0.0;
  buckets_.clear();
  used_.clear();
}

void ForcePlotCollector::add(const force_log::ForceLogRow& row) {
  const Sample sample{row.t_s, has_forces_ ? std::hypot(row.fx_n, row.fy_n) : std::numeric_limits<double>::quiet_NaN()};
  if (!started_) {
    started_ = true;
    t0_s_ = row.t_s;
  } else if (width_s_ == 0.0) {
    width_s_ = row.t_s - t0_s_;  // one row per bucket until there are too many
  }
  const std::size_t index =
      width_s_ > 0.0 ? static_cast<std::size_t>(std::floor((row.t_s - t0_s_) / width_s_ + 1e-9)) : 0;
  if (index >= kMaxBuckets) {
    widen();
    add(row);
    return;
  }
  if (index >= buckets_.size()) {
    buckets_.resize(index + 1);
    used_.resize(index + 1, false);
  }
  Bucket& bucket = buckets_[index];
  if (!used_[index]) {
    bucket = {sample, sample, sample, sample};
    used_[index] = true;
    return;
  }
  if (sample.value_n < bucket.low.value_n) bucket.low = sample;
  if (sample.value_n > bucket.high.value_n) bucket.high = sample;
  bucket.last = sample;
}

// Twice as wide: bucket i takes buckets 2i and 2i + 1.
void ForcePlotCollector::widen() {
  std::vector<Bucket> merged((buckets_.size() + 1) / 2);
  std::vector<bool> used(merged.size(), false);
  for (std::size_t i = 0; i < buckets_.size(); ++i) {
    if (!used_[i]) continue;
    Bucket& into = merged[i / 2];
    if (!used[i / 2]) {
      into = buckets_[i];
      used[i / 2] = true;
      continue;
    }
    if (buckets_[i].low.value_n < into.low.value_n) into.low = buckets_[i].low;
    if (buckets_[i].high.value_n > into.high.value_n) into.high = buckets_[i].high;
    into.last = buckets_[i].last;
  }
  buckets_ = std::move(merged);
  used_ = std::move(used);
  width_s_ *= 2.0;
}

ForcePlotData ForcePlotCollector::data(const std::string& title, std::vector<force_log::RevolutionPeak> peaks,
                                       std::optional<double> target_force_n) const {
  ForcePlotData plot;
  plot.title = title;
  plot.peaks = std::move(peaks);
  plot.target_force_n = target_force_n;
  ForcePlotSeries resultant;
  resultant.label = "|F_xy|";
  for (std::size_t i = 0; i < buckets_.size(); ++i) {
    if (!used_[i]) continue;
    const Bucket& b = buckets_[i];
    Sample kept[4] = {b.first, b.low, b.high, b.last};
    std::sort(std::begin(kept), std::end(kept), [](const Sample& x, const Sample& y) { return x.t_s < y.t_s; });
    for (int k = 0; k < 4; ++k) {
      if (k > 0 && kept[k].t_s == kept[k - 1].t_s) continue;  // each sample once
      plot.t_s.push_back(kept[k].t_s);
      resultant.values_n.push_back(kept[k].value_n);
    }
  }
  plot.series.push_back(std::move(resultant));
  return plot;
}

}  // namespace feedplan::sim
