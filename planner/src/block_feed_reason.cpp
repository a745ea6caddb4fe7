#include "feedplan/planner/block_feed_reason.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/planner/feed_limit.hpp"

namespace feedplan::planner {

namespace {

// The F the block split makes of a limit: rounded down onto the F levels (controller-friendly blocks) and to
// the feed resolution, at least the machine's minimum feed (block_split.cpp's round_down).
double rounded_down(double feed_mm_per_min, const PlanSettings& settings) {
  const PlanOptions& options = settings.options;
  const double top_mm_per_min = settings.machine.max_feed_mm_per_min;
  if (options.feed_step > 0.0 && feed_mm_per_min > 0.0 && feed_mm_per_min < top_mm_per_min) {
    const double log_ratio = std::log1p(options.feed_step);
    const double k = std::ceil(std::log(top_mm_per_min / feed_mm_per_min) / log_ratio - 1e-9);
    feed_mm_per_min = std::min(feed_mm_per_min, top_mm_per_min * std::exp(-k * log_ratio));
  }
  const double r = options.feed_resolution_mm_per_min;
  return std::max(std::floor(feed_mm_per_min / r + 1e-9) * r, settings.machine.min_feed_mm_per_min);
}

// The sample of `block` with the smallest feed limit; a limit carried over from a sample after the block
// (the force limit held over the last tooth's travel) is found there.
int deciding_sample(const PlanResult& result, const PlannedBlock& block) {
  const auto& samples = result.samples;
  int best = block.first_sample;
  for (int i = block.first_sample; i <= block.last_sample; ++i) {
    const PlannedSample& p = samples[static_cast<std::size_t>(i)];
    if (p.limit_reason == FeedLimitReason::kRapid) continue;
    const PlannedSample& b = samples[static_cast<std::size_t>(best)];
    if (b.limit_reason == FeedLimitReason::kRapid || p.feed_limit_mm_per_min < b.feed_limit_mm_per_min) best = i;
  }
  const double own_mm_per_min = samples[static_cast<std::size_t>(best)].feed_limit_mm_per_min;
  if (!(block.min_limit_mm_per_min < own_mm_per_min * (1.0 - 1e-9))) return best;
  for (std::size_t i = static_cast<std::size_t>(block.last_sample) + 1; i < samples.size(); ++i) {
    if (samples[i].limit_reason == FeedLimitReason::kRapid) break;
    if (std::abs(samples[i].feed_limit_mm_per_min - block.min_limit_mm_per_min) <= 1e-9 * own_mm_per_min) {
      return static_cast<int>(i);
    }
  }
  return best;
}

// The deciding sample's numbers for its reason.
void describe_limit(const PlanGeometry& geometry, const PlanSettings& settings, const PlanResult& result,
                    std::size_t block, BlockFeedReason& reason) {
  const PlannedSample& p = result.samples[static_cast<std::size_t>(reason.sample)];
  reason.limit = p.limit_reason;
  reason.limit_mm_per_min = p.feed_limit_mm_per_min;
  reason.target_force_n = settings.target_force_n;
  reason.engagement_deg = rad_to_deg(p.engagement_rad);
  const auto& engagement = geometry.engagement.samples;
  if (static_cast<std::size_t>(reason.sample) < engagement.size()) {
    reason.chip_thickness_mm = chip_thickness_mm(engagement[static_cast<std::size_t>(reason.sample)],
                                                 p.feed_limit_mm_per_min, geometry.tool.flutes, settings.spindle_rpm);
  }
  reason.plunge_feed_per_tooth_mm = geometry.tool.plunge_feed_per_tooth_mm();
  const auto& moves = result.program.path.moves;
  if (block < moves.size() && moves[block].kind == geometry::MoveKind::kArc) {
    reason.arc_radius_mm = geometry::arc_radius_mm(moves[block]);
  }
}

// `words` followed by `number` and `unit` ("plunge limit " "0.025" " mm/tooth"), built in place (GCC 12
// warns falsely, -Wrestrict, on "literal" + std::string).
std::string worded(const char* words, const std::string& number, const char* unit) {
  std::string text(words);
  text += number;
  text += unit;
  return text;
}

}  // namespace

BlockFeedReason block_feed_reason(const PlanGeometry& geometry, const PlanSettings& settings, const PlanResult& result,
                                  std::size_t block) {
  assert(block < result.blocks.size());
  const PlannedBlock& b = result.blocks[block];
  BlockFeedReason reason;
  assert(b.last_sample < static_cast<int>(result.samples.size()));
  if (!(b.feed_mm_per_min > 0.0)) {
    reason.rapid = true;
    return reason;
  }
  reason.sample = deciding_sample(result, b);
  describe_limit(geometry, settings, result, block, reason);
  const double limit_f = rounded_down(b.min_limit_mm_per_min, settings);
  reason.acceleration = std::isfinite(limit_f) && b.feed_mm_per_min < limit_f - 1e-6 * std::max(1.0, limit_f);
  return reason;
}

std::string to_text(const BlockFeedReason& reason) {
  if (reason.rapid) return "";
  if (reason.acceleration) return "acceleration";
  switch (reason.limit) {
    case FeedLimitReason::kForce: {
      std::string text = worded("force ", shortest_number_text(std::round(reason.target_force_n * 10.0) / 10.0), " N at ");
      text += fixed_number_text(reason.engagement_deg, 0);
      text += " deg engagement";
      return text;
    }
    case FeedLimitReason::kModelRange:
      return worded("model range, chip ", fixed_number_text(reason.chip_thickness_mm, 3), " mm");
    case FeedLimitReason::kPlunge:
      return worded("plunge limit ", shortest_number_text(std::round(reason.plunge_feed_per_tooth_mm * 1e4) / 1e4),
                    " mm/tooth");
    case FeedLimitReason::kMaxFeed: return "machine max feed";
    case FeedLimitReason::kMinFeed: return "machine min feed";
    case FeedLimitReason::kAirFeed: return "air";
    case FeedLimitReason::kCentripetal:
      return worded("arc R ", fixed_number_text(reason.arc_radius_mm, 3), " mm, acceleration");
    case FeedLimitReason::kRapid: return "";
  }
  return "";
}

std::vector<std::string> block_feed_reason_texts(const PlanGeometry& geometry, const PlanSettings& settings,
                                                 const PlanResult& result) {
  std::vector<std::string> texts;
  texts.reserve(result.blocks.size());
  for (std::size_t b = 0; b < result.blocks.size(); ++b) texts.push_back(to_text(block_feed_reason(geometry, settings, result, b)));
  return texts;
}

}  // namespace feedplan::planner
