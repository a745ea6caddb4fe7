#include "coverage.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "fixed_text.hpp"

namespace feedplan::learning::detail {

namespace {

// Share of the in-cut length below which a log counts as truncated (1 − this is what may be missing).
constexpr double kFullCoverage = 0.99;
// Two consecutive aligned rows further apart than this along the path leave the stretch between them
// uncovered (a gap in the log, off-path rows): nothing was measured there, mm.
constexpr double kCoverageBridgeMm = 2.0;

// The in-cut part of the path: lengths of the plan's segments with an engaged end.
struct InCut {
  std::vector<double> start_mm, end_mm;  // segments, in path order
  double length_mm = 0.0;
  double first_mm = 0.0, last_mm = 0.0;
};

InCut in_cut_of(const planner::PlanResult& plan) {
  InCut cut;
  const auto& samples = plan.samples;
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    if (!samples[k].engaged && !samples[k + 1].engaged) continue;
    const double a = samples[k].s_mm, b = samples[k + 1].s_mm;
    if (b <= a) continue;
    if (cut.start_mm.empty()) cut.first_mm = a;
    cut.last_mm = b;
    cut.start_mm.push_back(a);
    cut.end_mm.push_back(b);
    cut.length_mm += b - a;
  }
  return cut;
}

// Share of the in-cut length inside the union of `intervals` (each [lo, hi]).
double covered_fraction(const InCut& cut, std::vector<std::pair<double, double>> intervals) {
  if (cut.length_mm <= 0.0 || intervals.empty()) return 0.0;
  std::sort(intervals.begin(), intervals.end());
  std::vector<std::pair<double, double>> merged;
  for (const auto& iv : intervals) {
    if (!merged.empty() && iv.first <= merged.back().second) {
      merged.back().second = std::max(merged.back().second, iv.second);
    } else {
      merged.push_back(iv);
    }
  }
  double covered = 0.0;
  std::size_t m = 0;
  for (std::size_t k = 0; k < cut.start_mm.size(); ++k) {
    const double a = cut.start_mm[k], b = cut.end_mm[k];
    while (m < merged.size() && merged[m].second <= a) ++m;
    for (std::size_t j = m; j < merged.size() && merged[j].first < b; ++j) {
      covered += std::max(0.0, std::min(b, merged[j].second) - std::max(a, merged[j].first));
    }
  }
  return std::clamp(covered / cut.length_mm, 0.0, 1.0);
}

}  // namespace

// Coverage, status and the coverage part of the message, once s_mm is known.
void finish_coverage(const planner::PlanResult& plan, const force_log::ForceLog& log, Alignment& out,
                     const std::string& method_text) {
  const InCut cut = in_cut_of(plan);
  std::vector<std::pair<double, double>> intervals;
  double s_min = 1e300, s_max = -1e300;
  std::size_t previous = log.rows.size();
  out.rows_aligned = 0;
  for (std::size_t i = 0; i < out.s_mm.size(); ++i) {
    const double s = out.s_mm[i];
    if (!std::isfinite(s)) continue;
    ++out.rows_aligned;
    s_min = std::min(s_min, s);
    s_max = std::max(s_max, s);
    if (previous < log.rows.size()) {
      const double s_prev = out.s_mm[previous];
      if (std::abs(s - s_prev) <= kCoverageBridgeMm) intervals.emplace_back(std::min(s, s_prev), std::max(s, s_prev));
    }
    previous = i;
  }
  out.covered_fraction = covered_fraction(cut, intervals);
  std::string text = method_text;
  if (out.rows_aligned > 0) {
    text += "; the aligned rows span s = " + fixed(s_min, 1) + " to " + fixed(s_max, 1) + " mm";
  }
  if (cut.length_mm <= 0.0) {
    out.status = AlignmentStatus::kNoCut;
    text += "; the plan has no in-cut section: nothing to learn from";
  } else if (out.covered_fraction <= 0.0) {
    out.status = AlignmentStatus::kNoCut;
    text += "; no aligned row lies in the cut (s = " + fixed(cut.first_mm, 1) + " to " + fixed(cut.last_mm, 1) +
            " mm): nothing to learn from";
  } else if (out.covered_fraction < kFullCoverage) {
    out.status = AlignmentStatus::kTruncated;
    text += "; truncated: the log covers " + percent(out.covered_fraction) +
            " of the in-cut path (s = " + fixed(cut.first_mm, 1) + " to " + fixed(cut.last_mm, 1) + " mm)";
    if (s_max < cut.last_mm - kCoverageBridgeMm) text += ", it ends before the cut does";
    if (s_min > cut.first_mm + kCoverageBridgeMm) text += ", it starts after the cut has begun";
    text += "; usable for the part covered";
  } else {
    out.status = AlignmentStatus::kOk;
    text += "; covers " + percent(out.covered_fraction) + " of the in-cut path";
  }
  if (out.rows_with_nan > 0) text += "; " + std::to_string(out.rows_with_nan) + " rows with NaN values skipped";
  if (out.gaps > 0) text += "; " + std::to_string(out.gaps) + " gaps (time steps over 3 x the median)";
  out.message = text;
}

}  // namespace feedplan::learning::detail
