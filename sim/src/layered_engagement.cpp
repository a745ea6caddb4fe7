#include "feedplan/sim/layered_engagement.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>

#include "track_cover.hpp"

namespace feedplan::sim {

namespace {

// True when the move's tip z range meets (z_lo, z_hi]: the clipping of that move, or whether the tool
// reaches the layer, can differ between heights z_lo and z_hi. A vertical move (no XY travel) removes
// the same disc from every layer between its ends: only its two end heights can separate layers. A
// move with XY travel and a z change (helix, ramp) can make every layer it spans different.
bool move_between(const geometry::Move& move, double z_lo, double z_hi) {
  const double a = move.start.z_mm;
  const double b = move.end.z_mm;
  if (geometry::xy_length_mm(move) <= 1e-9) return (a > z_lo && a <= z_hi) || (b > z_lo && b <= z_hi);
  return std::max(a, b) > z_lo && std::min(a, b) <= z_hi;
}

bool any_move_between(const geometry::ToolPath& path, const geometry::Stock& stock, double z_lo, double z_hi) {
  auto between = [&](const geometry::Move& move) { return move_between(move, z_lo, z_hi); };
  return std::any_of(path.moves.begin(), path.moves.end(), between) ||
         std::any_of(stock.removed.begin(), stock.removed.end(),
                     [&](const geometry::SweptMove& swept) { return between(swept.move); });
}

// The layers and their bands, before any engagement is computed.
struct LayerPlan {
  double z_base_mm = 0.0;
  std::vector<int> layer_band;
  std::vector<double> band_z_mm;  // evaluation height of each band: the middle of its first layer
};

// 1. The lowest tip of a feed move is where the first layer starts (so a 2.5D cut's layers line up
//    with its depth); nothing below the stock bottom can be cut. 2. Bands of equivalent layers.
LayerPlan plan_layers(const geometry::ToolPath& path, const geometry::Stock& stock, double thickness_mm) {
  LayerPlan plan;
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto& move : path.moves) {
    if (move.kind != geometry::MoveKind::kRapid) lowest = std::min({lowest, move.start.z_mm, move.end.z_mm});
  }
  if (!std::isfinite(lowest) || lowest >= stock.z_top_mm) return plan;  // no feed move reaches the stock
  plan.z_base_mm = std::max(lowest, stock.z_bottom_mm);
  const int count = std::max(1, static_cast<int>(std::ceil((stock.z_top_mm - plan.z_base_mm) / thickness_mm - 1e-9)));
  plan.layer_band.resize(count);
  for (int k = 0; k < count; ++k) {
    const double mid = plan.z_base_mm + (k + 0.5) * thickness_mm;
    const bool new_band = k == 0 || any_move_between(path, stock, plan.band_z_mm.back(), mid) || mid > stock.z_top_mm;
    if (new_band) plan.band_z_mm.push_back(mid);
    plan.layer_band[k] = static_cast<int>(plan.band_z_mm.size()) - 1;
  }
  return plan;
}

// The first move from which the layer at `z_hi` sees the material the layer at `z_lo` sees (both
// under the stock top, no earlier cut of the stock between them): after the last move between the two
// heights and after every such move's track has been re-cut below both (`cover`, for z_lo; `covered`
// caches its answers per move). nullopt when that never happens before the last move.
std::optional<std::size_t> first_shared_move(const geometry::ToolPath& path, const geometry::Stock& stock, double z_lo,
                                             double z_hi, const detail::TrackCover& cover,
                                             std::vector<std::optional<std::optional<std::size_t>>>& covered) {
  if (z_hi > stock.z_top_mm) return std::nullopt;
  for (const auto& swept : stock.removed) {
    if (move_between(swept.move, z_lo, z_hi)) return std::nullopt;
  }
  std::size_t first = 0;
  for (std::size_t k = 0; k < path.moves.size(); ++k) {
    if (!move_between(path.moves[k], z_lo, z_hi)) continue;
    if (!covered[k]) covered[k] = cover.covered_after(k);
    if (!*covered[k]) return std::nullopt;
    first = std::max({first, k + 1, **covered[k]});
  }
  if (first == 0 || first >= path.moves.size()) return std::nullopt;
  return first;
}

// The path up to (not including) move `end`.
geometry::ToolPath path_before(const geometry::ToolPath& path, std::size_t end) {
  geometry::ToolPath prefix;
  prefix.part_names = path.part_names;
  prefix.moves.assign(path.moves.begin(), path.moves.begin() + static_cast<std::ptrdiff_t>(end));
  return prefix;
}

// Path length up to the start of every move, and the total at the end, mm.
std::vector<double> move_starts_mm(const geometry::ToolPath& path) {
  std::vector<double> starts(path.moves.size() + 1, 0.0);
  for (std::size_t i = 0; i < path.moves.size(); ++i) starts[i + 1] = starts[i] + geometry::length_mm(path.moves[i]);
  return starts;
}

}  // namespace

LayeredEngagement::LayeredEngagement(const geometry::ToolPath& path, const geometry::Stock& stock,
                                     double tool_radius_mm, const LayerOptions& options)
    : thickness_mm_(options.layer_thickness_mm) {
  assert(options.layer_thickness_mm > 0.0 && options.ds_mm > 0.0 && tool_radius_mm > 0.0);
  const LayerPlan plan = plan_layers(path, stock, thickness_mm_);
  z_base_mm_ = plan.z_base_mm;
  layer_band_ = plan.layer_band;
  if (plan.band_z_mm.empty()) return;

  // Where every band starts sharing the lowest band's engagement (path.moves.size(): never).
  const std::size_t bands = plan.band_z_mm.size();
  const detail::TrackCover cover(path, plan.band_z_mm.front(), options.recut_tolerance_mm);
  std::vector<std::optional<std::optional<std::size_t>>> covered(path.moves.size());
  std::vector<std::size_t> own_moves(bands, path.moves.size());
  for (std::size_t b = 1; b < bands && options.share_recut_layers; ++b) {
    own_moves[b] = first_shared_move(path, stock, plan.band_z_mm.front(), plan.band_z_mm[b], cover, covered)
                       .value_or(path.moves.size());
  }
  const std::vector<double> starts = move_starts_mm(path);
  double work_total = 0.0, work_done = 0.0;
  for (const std::size_t end : own_moves) work_total += starts[end];

  std::vector<std::size_t> first_sample_of_move;  // in the lowest band
  for (std::size_t b = 0; b < bands; ++b) {
    const bool shares = own_moves[b] < path.moves.size();
    geometry::EngagementOptions engagement_options;
    engagement_options.ds_mm = options.ds_mm;
    engagement_options.evaluation_z_mm = plan.band_z_mm[b];
    const geometry::EngagementProfile profile =
        compute_engagement(shares ? path_before(path, own_moves[b]) : path, stock, tool_radius_mm, engagement_options);
    for (const auto& warning : profile.warnings) {
      if (std::find(warnings_.begin(), warnings_.end(), warning) == warnings_.end()) warnings_.push_back(warning);
    }
    if (b == 0) {
      first_sample_of_move.assign(path.moves.size() + 1, profile.samples.size());
      for (std::size_t i = profile.samples.size(); i-- > 0;) first_sample_of_move[profile.samples[i].move_index] = i;
    }
    // A prefix's last sample is its last move's end: the lowest band's first sample of the next move
    // stands there, with that move's feed direction.
    if (b == 0) {
      s_mm_.reserve(profile.samples.size());
      for (const auto& sample : profile.samples) s_mm_.push_back(sample.s_mm);
    }
    add_band(profile, shares ? first_sample_of_move[own_moves[b]] : profile.samples.size());
    samples_computed_ += profile.samples.size();
    work_done += starts[own_moves[b]];
    if (options.progress) options.progress(work_done, work_total);
  }
}

// The band's arcs at its first `sample_count` samples; arcs equal to the previous band's at a sample
// are kept once.
void LayeredEngagement::add_band(const geometry::EngagementProfile& profile, std::size_t sample_count) {
  assert(sample_count <= s_mm_.size() && sample_count <= profile.samples.size());
  const Band* previous = bands_.empty() ? nullptr : &bands_.back();
  Band band;
  band.interval_begin.reserve(sample_count);
  band.interval_count.reserve(sample_count);
  for (std::size_t i = 0; i < sample_count; ++i) {
    const geometry::EngagementSample& sample = profile.samples[i];
    assert(sample.s_mm == s_mm_[i] && sample.interval_count < 65536);
    const std::span<const geometry::EngagedInterval> arcs(profile.intervals.data() + sample.interval_begin,
                                                          static_cast<std::size_t>(sample.interval_count));
    if (previous && i < previous->size()) {
      const auto before = sample_intervals(*previous, i);
      const bool same = std::equal(arcs.begin(), arcs.end(), before.begin(), before.end(), [](const auto& a, const auto& b) {
        return a.entry_rad == b.entry_rad && a.exit_rad == b.exit_rad;
      });
      if (same) {
        band.interval_begin.push_back(previous->interval_begin[i]);
        band.interval_count.push_back(previous->interval_count[i]);
        continue;
      }
    }
    band.interval_begin.push_back(static_cast<std::uint32_t>(intervals_.size()));
    band.interval_count.push_back(static_cast<std::uint16_t>(arcs.size()));
    intervals_.insert(intervals_.end(), arcs.begin(), arcs.end());
  }
  bands_.push_back(std::move(band));
}

std::span<const geometry::EngagedInterval> LayeredEngagement::sample_intervals(const Band& band, std::size_t i) const {
  const Band& owner = i < band.size() ? band : bands_.front();
  return {intervals_.data() + owner.interval_begin[i], owner.interval_count[i]};
}

std::size_t LayeredEngagement::sample_at(double s_mm, Cursor& cursor) const {
  const std::size_t count = s_mm_.size();
  if (count == 0) return 0;
  std::size_t i = std::min(cursor.sample, count - 1);
  while (i + 1 < count && s_mm_[i + 1] <= s_mm) ++i;
  while (i > 0 && s_mm_[i] > s_mm) --i;
  if (i + 1 < count && s_mm_[i + 1] - s_mm < s_mm - s_mm_[i]) ++i;
  cursor.sample = i;
  return i;
}

std::span<const geometry::EngagedInterval> LayeredEngagement::band_intervals(int band, std::size_t sample) const {
  if (s_mm_.empty()) return {};
  return sample_intervals(bands_[band], sample);
}

std::span<const geometry::EngagedInterval> LayeredEngagement::intervals_at(int layer, double s_mm,
                                                                           Cursor& cursor) const {
  const std::size_t sample = sample_at(s_mm, cursor);
  return band_intervals(layer_band_[layer], sample);
}

}  // namespace feedplan::sim
