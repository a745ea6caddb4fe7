#include "feedplan/geometry/engagement_summary.hpp"

#include <algorithm>
#include <limits>

namespace feedplan::geometry {

EngagementSummary summarize(const ToolPath& path, const EngagementProfile& profile) {
  EngagementSummary summary;
  const std::size_t part_count = std::max<std::size_t>(path.part_names.size(), 1);
  std::vector<PartSummary> parts(part_count);
  std::vector<int> first_move(part_count, std::numeric_limits<int>::max());
  for (std::size_t p = 0; p < part_count; ++p) parts[p].name = p < path.part_names.size() ? path.part_names[p] : "path";
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    const Move& move = path.moves[i];
    const double length = length_mm(move);
    summary.length_mm += length;
    if (move.kind == MoveKind::kRapid) summary.rapid_length_mm += length;
    else if (move.cutting) summary.cutting_length_mm += length;
    else summary.air_length_mm += length;
    PartSummary& part = parts[move.part];
    part.length_mm += length;
    if (move.cutting && move.kind != MoveKind::kRapid) part.cutting_length_mm += length;
    first_move[move.part] = std::min(first_move[move.part], static_cast<int>(i));
  }
  std::vector<double> sums(part_count, 0.0);
  for (const auto& s : profile.samples) {
    ++summary.samples;
    if (!s.cutting) continue;
    PartSummary& part = parts[s.part];
    if (part.cutting_samples == 0) {
      part.engagement_min_rad = s.engagement_rad;
      part.engagement_max_rad = s.engagement_rad;
    }
    part.engagement_min_rad = std::min(part.engagement_min_rad, s.engagement_rad);
    part.engagement_max_rad = std::max(part.engagement_max_rad, s.engagement_rad);
    part.chip_factor_max = std::max(part.chip_factor_max, s.chip_factor);
    sums[s.part] += s.engagement_rad;
    ++part.cutting_samples;
    summary.engagement_max_rad = std::max(summary.engagement_max_rad, s.engagement_rad);
  }
  std::vector<std::size_t> order;
  for (std::size_t p = 0; p < part_count; ++p) {
    if (parts[p].cutting_samples > 0) parts[p].engagement_mean_rad = sums[p] / parts[p].cutting_samples;
    if (first_move[p] != std::numeric_limits<int>::max()) order.push_back(p);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return first_move[a] < first_move[b]; });
  for (const auto p : order) summary.parts.push_back(parts[p]);
  return summary;
}

}  // namespace feedplan::geometry
