#include "feedplan/sim/layered_engagement.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace feedplan::sim {

namespace {

struct ZRange {
  double lo = 0.0;
  double hi = 0.0;
};

ZRange z_range_of(const geometry::Move& move) {
  return {std::min(move.start.z_mm, move.end.z_mm), std::max(move.start.z_mm, move.end.z_mm)};
}

// True when some move's tip z range meets (z_lo, z_hi]: the clipping of that move, or whether the
// tool reaches the layer, can differ between heights z_lo and z_hi.
bool any_move_between(const std::vector<ZRange>& ranges, double z_lo, double z_hi) {
  return std::any_of(ranges.begin(), ranges.end(), [&](const ZRange& r) { return r.hi > z_lo && r.lo <= z_hi; });
}

}  // namespace

LayeredEngagement::LayeredEngagement(const geometry::ToolPath& path, const geometry::Stock& stock,
                                     double tool_radius_mm, const LayerOptions& options)
    : thickness_mm_(options.layer_thickness_mm) {
  assert(options.layer_thickness_mm > 0.0 && options.ds_mm > 0.0 && tool_radius_mm > 0.0);
  // 1. The lowest tip of a feed move is where the first layer starts (so a 2.5D cut's layers line
  //    up with its depth); nothing below the stock bottom can be cut.
  double lowest = std::numeric_limits<double>::infinity();
  std::vector<ZRange> ranges;
  // A vertical move (no XY travel) removes the same disc from every layer between its ends: only its
  // two end heights can separate layers. A move with XY travel and a z change (helix, ramp) can make
  // every layer it spans different.
  auto add_range = [&ranges](const geometry::Move& move) {
    const ZRange range = z_range_of(move);
    if (geometry::xy_length_mm(move) <= 1e-9) {
      ranges.push_back({range.lo, range.lo});
      ranges.push_back({range.hi, range.hi});
    } else {
      ranges.push_back(range);
    }
  };
  for (const auto& move : path.moves) {
    add_range(move);
    if (move.kind != geometry::MoveKind::kRapid) lowest = std::min(lowest, z_range_of(move).lo);
  }
  for (const auto& swept : stock.removed) add_range(swept.move);
  if (!std::isfinite(lowest) || lowest >= stock.z_top_mm) return;  // no feed move reaches the stock
  z_base_mm_ = std::max(lowest, stock.z_bottom_mm);
  const int count = std::max(1, static_cast<int>(std::ceil((stock.z_top_mm - z_base_mm_) / thickness_mm_ - 1e-9)));

  // 2. Bands of equivalent layers; one engagement computation per band, on its first layer's middle.
  layer_band_.resize(count);
  double band_mid = 0.0;
  for (int k = 0; k < count; ++k) {
    const double mid = z_base_mm_ + (k + 0.5) * thickness_mm_;
    const bool new_band = k == 0 || any_move_between(ranges, band_mid, mid) || mid > stock.z_top_mm;
    if (new_band) {
      band_mid = mid;
      geometry::EngagementOptions engagement_options;
      engagement_options.ds_mm = options.ds_mm;
      engagement_options.evaluation_z_mm = mid;
      profiles_.push_back(geometry::compute_engagement(path, stock, tool_radius_mm, engagement_options));
      for (const auto& warning : profiles_.back().warnings) {
        if (std::find(warnings_.begin(), warnings_.end(), warning) == warnings_.end()) warnings_.push_back(warning);
      }
    }
    layer_band_[k] = static_cast<int>(profiles_.size()) - 1;
  }
}

std::span<const geometry::EngagedInterval> LayeredEngagement::intervals_at(int layer, double s_mm,
                                                                           Cursor& cursor) const {
  const auto& profile = profiles_[layer_band_[layer]];
  const auto& samples = profile.samples;
  if (samples.empty()) return {};
  std::size_t i = std::min(cursor.sample, samples.size() - 1);
  while (i + 1 < samples.size() && samples[i + 1].s_mm <= s_mm) ++i;
  while (i > 0 && samples[i].s_mm > s_mm) --i;
  if (i + 1 < samples.size() && samples[i + 1].s_mm - s_mm < s_mm - samples[i].s_mm) ++i;
  cursor.sample = i;
  const auto& sample = samples[i];
  return {profile.intervals.data() + sample.interval_begin, static_cast<std::size_t>(sample.interval_count)};
}

}  // namespace feedplan::sim
