// The bounded plot collector (force_plot_collector.hpp) against the plot of the whole log
// (force_plot_data, the truth): the same largest and smallest |F_xy| at the same times, the same time
// span, and never more than 4 samples per bucket however long the log.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/sim/force_plot.hpp"
#include "feedplan/sim/force_plot_collector.hpp"

namespace feedplan::sim {
namespace {

// 10 kHz, 200 s: 2 million rows of a tooth-passing force with a seeded spike and a gap in contact.
force_log::ForceLog long_log() {
  force_log::ForceLog log;
  std::uint64_t state = 12345;
  for (int i = 0; i < 2'000'000; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double noise = static_cast<double>(state >> 11) / 9007199254740992.0;
    force_log::ForceLogRow row;
    row.t_s = i * 1e-4;
    const bool in_cut = i < 700'000 || i > 900'000;
    row.fx_n = in_cut ? 300.0 * std::abs(std::sin(i * 0.0147)) + 5.0 * noise : 0.0;
    row.fy_n = in_cut ? 120.0 * std::cos(i * 0.0147) : 0.0;
    if (i == 1'234'567) row.fx_n = 900.0;
    log.rows.push_back(row);
  }
  return log;
}

TEST(ForcePlotCollector, KeepsTheExtremesOfTheWholeLogInBoundedMemory) {
  const force_log::ForceLog log = long_log();
  ForcePlotCollector collector;
  collector.begin(log);
  for (const auto& row : log.rows) collector.add(row);
  const ForcePlotData kept = collector.data("t");
  const ForcePlotData whole = force_plot_data(log, "t");
  const auto& k = kept.series.front().values_n;
  const auto& w = whole.series.front().values_n;
  ASSERT_LE(k.size(), 4 * ForcePlotCollector::kMaxBuckets);
  ASSERT_GT(k.size(), ForcePlotCollector::kMaxBuckets);
  const auto k_max = std::max_element(k.begin(), k.end());
  const auto w_max = std::max_element(w.begin(), w.end());
  EXPECT_EQ(*k_max, *w_max);
  EXPECT_EQ(kept.t_s[k_max - k.begin()], whole.t_s[w_max - w.begin()]);
  EXPECT_EQ(*std::min_element(k.begin(), k.end()), *std::min_element(w.begin(), w.end()));
  EXPECT_EQ(kept.t_s.front(), whole.t_s.front());
  EXPECT_EQ(kept.t_s.back(), whole.t_s.back());
  EXPECT_TRUE(std::is_sorted(kept.t_s.begin(), kept.t_s.end()));
}

}  // namespace
}  // namespace feedplan::sim
