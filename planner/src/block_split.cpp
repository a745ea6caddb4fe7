#include "block_split.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace feedplan::planner::detail {
namespace {

// Time lost by slowing a block down that always justifies a new block, s (used when the block time is 0).
constexpr double kMinLossS = 1e-3;

double round_down(double feed_mm_per_min, const BlockSplitSettings& settings) {
  if (settings.level_step > 0.0 && feed_mm_per_min > 0.0 && feed_mm_per_min < settings.level_top_mm_per_min) {
    const double log_ratio = std::log1p(settings.level_step);
    const double k = std::ceil(std::log(settings.level_top_mm_per_min / feed_mm_per_min) / log_ratio - 1e-9);
    feed_mm_per_min = std::min(feed_mm_per_min, settings.level_top_mm_per_min * std::exp(-k * log_ratio));
  }
  const double r = settings.feed_resolution_mm_per_min;
  // A hair of slack so that a feed already on the grid (1200 − 1e-12) is not pushed one step down.
  const double floored = std::floor(feed_mm_per_min / r + 1e-9) * r;
  return std::max(floored, settings.min_feed_mm_per_min);
}

// F of the nodes [first, last] of the profile by the mode's rule, before rounding.
double block_feed(const std::vector<double>& s, const std::vector<double>& c, int first, int last,
                  const BlockSplitSettings& settings) {
  double lo = c[static_cast<std::size_t>(first)];
  for (int i = first + 1; i <= last; ++i) lo = std::min(lo, c[static_cast<std::size_t>(i)]);
  if (settings.mode == PlanMode::kSafe || last == first) return lo;
  double weighted = 0.0;
  double length = 0.0;
  for (int i = first; i < last; ++i) {
    const double ds = s[static_cast<std::size_t>(i) + 1] - s[static_cast<std::size_t>(i)];
    weighted += 0.5 * (c[static_cast<std::size_t>(i)] + c[static_cast<std::size_t>(i) + 1]) * ds;
    length += ds;
  }
  const double mean = length > 0.0 ? weighted / length : lo;
  return std::min(mean, lo * (1.0 + settings.merge_tolerance));
}

// Cuts the feed move spanning nodes [a, b] into blocks.
void split_move(int move_index, int a, int b, const std::vector<double>& s, const std::vector<double>& c,
                const BlockSplitSettings& settings, std::vector<PlannedBlock>& out, int& short_blocks) {
  const std::size_t first_of_move = out.size();
  int i = a;
  while (i < b) {
    double lo = c[static_cast<std::size_t>(i)];
    double hi = lo;
    int j = i;
    while (j < b) {
      const double next = c[static_cast<std::size_t>(j) + 1];
      const double new_lo = std::min(lo, next);
      const double new_hi = std::max(hi, next);
      const bool within = new_hi <= new_lo * (1.0 + settings.merge_tolerance);
      const double length_mm = s[static_cast<std::size_t>(j)] - s[static_cast<std::size_t>(i)];
      const double duration_s = j > i ? length_mm / (lo / 60.0) : 0.0;
      if (!within && duration_s >= settings.block_time_min_s) break;
      // A new minimum slows the whole block down; when that costs more time than one more block
      // lasts, start a new block here instead (a long plateau is not dragged down by the first
      // samples of a descent that follows it).
      if (next < lo && duration_s >= settings.block_time_min_s &&
          length_mm * (60.0 / next - 60.0 / lo) > std::max(settings.block_time_min_s, kMinLossS)) {
        break;
      }
      lo = new_lo;
      hi = new_hi;
      ++j;
    }
    PlannedBlock block;
    block.move_index = move_index;
    block.first_sample = i;
    block.last_sample = j;
    block.length_mm = s[static_cast<std::size_t>(j)] - s[static_cast<std::size_t>(i)];
    block.feed_mm_per_min = block_feed(s, c, i, j, settings);
    out.push_back(block);
    i = j;
  }
  // A last block shorter than the block time joins the one before it (same move).
  if (out.size() - first_of_move >= 2) {
    PlannedBlock& last = out.back();
    if (last.length_mm / (last.feed_mm_per_min / 60.0) < settings.block_time_min_s) {
      PlannedBlock& previous = out[out.size() - 2];
      previous.last_sample = last.last_sample;
      previous.length_mm += last.length_mm;
      previous.feed_mm_per_min = block_feed(s, c, previous.first_sample, previous.last_sample, settings);
      out.pop_back();
    }
  }
  for (std::size_t k = first_of_move; k < out.size(); ++k) {
    out[k].feed_mm_per_min = round_down(out[k].feed_mm_per_min, settings);
    if (out[k].length_mm / (out[k].feed_mm_per_min / 60.0) < settings.short_block_s) ++short_blocks;
  }
}

// Longest block the least-time cut considers, in samples (longer stretches become several blocks of the
// same F, joined afterwards).
constexpr int kLeastTimeWindow = 400;

// The least-time cut of the feed move spanning nodes [a, b] (the controller-friendly rule): blocks whose F
// is the profile's smallest value inside, each lasting at least the block time, with the least total time
// — dynamic programming over the block ends; ties go to fewer blocks. Neighbouring blocks of one F are
// joined.
void split_move_least_time(int move_index, int a, int b, const std::vector<double>& s, const std::vector<double>& c,
                           const BlockSplitSettings& settings, std::vector<PlannedBlock>& out, int& short_blocks) {
  const auto at = [](const std::vector<double>& v, int i) { return v[static_cast<std::size_t>(i)]; };
  const auto feed = [&](double v) { return round_down(v, settings); };
  const int n = b - a;
  constexpr double kBlockPenaltyS = 1e-9;  // prefers fewer blocks among cuts of equal time
  std::vector<double> best(static_cast<std::size_t>(n) + 1, std::numeric_limits<double>::infinity());
  std::vector<int> from(static_cast<std::size_t>(n) + 1, -1);
  best[0] = 0.0;
  for (int j = 1; j <= n; ++j) {
    double lo = at(c, a + j);
    for (int i = j - 1; i >= 0 && i >= j - kLeastTimeWindow; --i) {
      lo = std::min(lo, at(c, a + i));
      if (!std::isfinite(best[static_cast<std::size_t>(i)])) continue;
      const double duration_s = (at(s, a + j) - at(s, a + i)) / (feed(lo) / 60.0);
      const bool whole_move = i == 0 && j == n;
      if (duration_s < settings.block_time_min_s && !whole_move) continue;
      const double total = best[static_cast<std::size_t>(i)] + duration_s + kBlockPenaltyS;
      if (total < best[static_cast<std::size_t>(j)]) {
        best[static_cast<std::size_t>(j)] = total;
        from[static_cast<std::size_t>(j)] = i;
      }
    }
  }
  std::vector<int> ends;
  for (int j = n; j > 0; j = from[static_cast<std::size_t>(j)]) {
    if (from[static_cast<std::size_t>(j)] < 0) {  // no cut within the window: one block for the move
      ends = {n};
      break;
    }
    ends.push_back(j);
  }
  std::reverse(ends.begin(), ends.end());
  int first = 0;
  for (const int end : ends) {
    double lo = at(c, a + first);
    for (int i = first; i <= end; ++i) lo = std::min(lo, at(c, a + i));
    const double f = feed(lo);
    if (!out.empty() && out.back().move_index == move_index && out.back().feed_mm_per_min == f &&
        out.back().last_sample == a + first) {
      out.back().last_sample = a + end;
      out.back().length_mm = at(s, a + end) - at(s, out.back().first_sample);
    } else {
      PlannedBlock block;
      block.move_index = move_index;
      block.first_sample = a + first;
      block.last_sample = a + end;
      block.length_mm = at(s, a + end) - at(s, a + first);
      block.feed_mm_per_min = f;
      out.push_back(block);
    }
    first = end;
  }
  for (std::size_t k = out.size(); k-- > 0 && out[k].move_index == move_index;) {
    if (out[k].length_mm / (out[k].feed_mm_per_min / 60.0) < settings.short_block_s) ++short_blocks;
  }
}

// Lowers F so that every change between neighbouring feed blocks fits inside the faster block at the
// acceleration limit: v_{k+1}² ≤ v_k² + 2 a L_{k+1} (accelerating at the start of block k+1) and
// v_k² ≤ v_{k+1}² + 2 a L_k (decelerating at the end of block k). Rounding down after each change keeps
// the grid; repeated until nothing changes (only decreases, so it terminates).
void limit_steps(std::vector<PlannedBlock>& blocks, std::size_t begin, std::size_t end,
                 const BlockSplitSettings& settings) {
  if (end - begin < 2) return;
  const double two_a = 2.0 * settings.accel_mm_per_s2;
  auto speed = [](const PlannedBlock& b) { return b.feed_mm_per_min / 60.0; };
  for (int round = 0; round < 1000; ++round) {
    bool changed = false;
    for (std::size_t k = begin; k + 1 < end; ++k) {
      const double v = speed(blocks[k]);
      const double limit = std::sqrt(v * v + two_a * blocks[k + 1].length_mm) * 60.0;
      if (blocks[k + 1].feed_mm_per_min > limit) {
        blocks[k + 1].feed_mm_per_min = std::max(round_down(limit, settings), settings.min_feed_mm_per_min);
        changed = true;
      }
    }
    for (std::size_t k = end - 1; k-- > begin;) {
      const double v = speed(blocks[k + 1]);
      const double limit = std::sqrt(v * v + two_a * blocks[k].length_mm) * 60.0;
      if (blocks[k].feed_mm_per_min > limit) {
        blocks[k].feed_mm_per_min = std::max(round_down(limit, settings), settings.min_feed_mm_per_min);
        changed = true;
      }
    }
    if (!changed) return;
  }
}

}  // namespace

std::vector<PlannedBlock> split_blocks(const geometry::ToolPath& path, const std::vector<double>& s_mm,
                                       const std::vector<double>& command_mm_per_min,
                                       const std::vector<int>& move_first_sample, const BlockSplitSettings& settings,
                                       int& short_blocks) {
  assert(move_first_sample.size() == path.moves.size() + 1);
  std::vector<PlannedBlock> blocks;
  short_blocks = 0;
  std::size_t run_begin = 0;
  for (std::size_t m = 0; m < path.moves.size(); ++m) {
    const int a = move_first_sample[m];
    const int b = move_first_sample[m + 1];
    if (b <= a) continue;
    if (path.moves[m].kind == geometry::MoveKind::kRapid) {
      limit_steps(blocks, run_begin, blocks.size(), settings);
      PlannedBlock rapid;
      rapid.move_index = static_cast<int>(m);
      rapid.first_sample = a;
      rapid.last_sample = b;
      rapid.length_mm = s_mm[static_cast<std::size_t>(b)] - s_mm[static_cast<std::size_t>(a)];
      blocks.push_back(rapid);
      run_begin = blocks.size();
      continue;
    }
    if (settings.least_time) {
      split_move_least_time(static_cast<int>(m), a, b, s_mm, command_mm_per_min, settings, blocks, short_blocks);
    } else {
      split_move(static_cast<int>(m), a, b, s_mm, command_mm_per_min, settings, blocks, short_blocks);
    }
  }
  limit_steps(blocks, run_begin, blocks.size(), settings);
  return blocks;
}

}  // namespace feedplan::planner::detail
