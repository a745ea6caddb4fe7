#include "feedplan/learning/log_alignment.hpp"

#include "feedplan/force_log/logged_spindle_speed.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <utility>

#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::learning {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMmPerInch = 25.4;
// A time step longer than this many median steps is a gap in the data.
constexpr double kGapFactor = 3.0;
// Share of the in-cut length below which a log counts as truncated (1 − this is what may be missing).
constexpr double kFullCoverage = 0.99;
// Two consecutive aligned rows further apart than this along the path leave the stretch between them
// uncovered (a gap in the log, off-path rows): nothing was measured there, mm.
constexpr double kCoverageBridgeMm = 2.0;
// Delay search: bins no finer than this, s (the estimate is interpolated between bins).
constexpr double kMinDelayBinS = 0.5e-3;
// Time-profile search: at most this many bins over log + plan (keeps the full search quadratic but small).
constexpr double kMaxTimeProfileBins = 8000.0;
constexpr double kMinTimeProfileBinS = 2e-3;
// Correlations this close to the maximum belong to its flat top (rounding in the sums).
constexpr double kFlatTop = 1e-9;
// The tool is in contact where the measured peak envelope exceeds this share of its (robust) maximum.
constexpr double kContactFraction = 0.1;

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string percent(double fraction) {
  return fixed(100.0 * fraction, fraction > 0.995 && fraction < 1.0 ? 1 : 0) + " %";
}

bool finite_xy(const force_log::ForceLogRow& row) { return std::isfinite(row.x_mm) && std::isfinite(row.y_mm); }
bool finite_force(const force_log::ForceLogRow& row) { return std::isfinite(row.fx_n) && std::isfinite(row.fy_n); }

// ---------------------------------------------------------------------------------------------------
// The planned path as a polyline through the plan's samples, with a uniform XY grid of its segments.

struct Projection {
  double distance_mm = 0.0;
  double s_mm = 0.0;
};

class PathIndex {
 public:
  PathIndex(const planner::PlanResult& plan, double reach_mm) : reach_mm_(reach_mm) {
    for (const auto& sample : plan.samples) {
      points_.push_back(sample.position);
      s_.push_back(sample.s_mm);
    }
    assert(!points_.empty());
    if (points_.size() == 1) {  // one point: one segment of length zero
      points_.push_back(points_.front());
      s_.push_back(s_.front());
    }
    double x_min = 1e300, x_max = -1e300, y_min = 1e300, y_max = -1e300;
    for (const auto& p : points_) {
      x_min = std::min(x_min, p.x_mm);
      x_max = std::max(x_max, p.x_mm);
      y_min = std::min(y_min, p.y_mm);
      y_max = std::max(y_max, p.y_mm);
    }
    x0_ = x_min - reach_mm_;
    y0_ = y_min - reach_mm_;
    const double width = x_max - x_min + 2.0 * reach_mm_;
    const double height = y_max - y_min + 2.0 * reach_mm_;
    // Cells about twice the reach, so a segment lands in a few cells; at most ~4 million cells.
    cell_mm_ = std::max({2.0 * reach_mm_, 0.25, std::sqrt(width * height / 4e6)});
    nx_ = static_cast<int>(width / cell_mm_) + 1;
    ny_ = static_cast<int>(height / cell_mm_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    for (int k = 0; k < segment_count(); ++k) {
      const auto& a = points_[static_cast<std::size_t>(k)];
      const auto& b = points_[static_cast<std::size_t>(k) + 1];
      const int i0 = cell_x(std::min(a.x_mm, b.x_mm) - reach_mm_);
      const int i1 = cell_x(std::max(a.x_mm, b.x_mm) + reach_mm_);
      const int j0 = cell_y(std::min(a.y_mm, b.y_mm) - reach_mm_);
      const int j1 = cell_y(std::max(a.y_mm, b.y_mm) + reach_mm_);
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) cells_[index(i, j)].push_back(k);  // in segment order
      }
    }
  }

  int segment_count() const { return static_cast<int>(points_.size()) - 1; }
  double s_of_segment_start(int k) const { return s_[static_cast<std::size_t>(k)]; }
  double length_mm() const { return s_.back() - s_.front(); }

  // Nearest point of segment k to q (z compared only when finite).
  Projection project(int k, double x, double y, double z) const {
    const auto& a = points_[static_cast<std::size_t>(k)];
    const auto& b = points_[static_cast<std::size_t>(k) + 1];
    const bool use_z = std::isfinite(z);
    const double dx = b.x_mm - a.x_mm, dy = b.y_mm - a.y_mm, dz = use_z ? b.z_mm - a.z_mm : 0.0;
    const double qx = x - a.x_mm, qy = y - a.y_mm, qz = use_z ? z - a.z_mm : 0.0;
    const double len2 = dx * dx + dy * dy + dz * dz;
    const double t = len2 > 0.0 ? std::clamp((qx * dx + qy * dy + qz * dz) / len2, 0.0, 1.0) : 0.0;
    const double ex = qx - t * dx, ey = qy - t * dy, ez = qz - t * dz;
    const double sa = s_[static_cast<std::size_t>(k)];
    const double sb = s_[static_cast<std::size_t>(k) + 1];
    return {std::sqrt(ex * ex + ey * ey + ez * ez), sa + t * (sb - sa)};
  }

  // Distance from q to the whole path (linear in its length; for messages only).
  double distance_to_path(double x, double y, double z) const {
    double best = 1e300;
    for (int k = 0; k < segment_count(); ++k) best = std::min(best, project(k, x, y, z).distance_mm);
    return best;
  }

  // Segment containing s (the last one starting at or before it).
  int segment_at(double s_mm) const {
    const auto it = std::upper_bound(s_.begin(), s_.end() - 1, s_mm);
    return std::max(0, static_cast<int>(it - s_.begin()) - 1);
  }

  // Every segment within reach of q is in this list (sorted by index), with others near it; empty
  // outside the grid.
  const std::vector<int>& candidates(double x, double y) const {
    static const std::vector<int> none;
    const double fx = (x - x0_) / cell_mm_, fy = (y - y0_) / cell_mm_;
    if (!(fx >= 0.0 && fy >= 0.0 && fx < nx_ && fy < ny_)) return none;
    return cells_[index(static_cast<int>(fx), static_cast<int>(fy))];
  }

 private:
  int cell_x(double x) const { return std::clamp(static_cast<int>((x - x0_) / cell_mm_), 0, nx_ - 1); }
  int cell_y(double y) const { return std::clamp(static_cast<int>((y - y0_) / cell_mm_), 0, ny_ - 1); }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i);
  }

  double reach_mm_;
  std::vector<geometry::Point3> points_;
  std::vector<double> s_;
  double x0_ = 0, y0_ = 0, cell_mm_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
};

// The row's place on the path at or after segment `k_min`: the local minima of the distance over the
// segments within reach, taken in path order; among those within a short stretch after the first one
// the nearest sets the bar, and the first minimum within `tie_mm` of it wins. So a crossing of the path
// far ahead (the next trochoid loop) never takes the match, and at a reversal (down and back up the same
// line) the leg the row is really on beats the one it only grazes.
std::optional<Projection> match_row(const PathIndex& path, double x, double y, double z, int k_min, double reach_mm,
                                    double window_mm, double tie_mm) {
  const std::vector<int>& cell = path.candidates(x, y);
  auto it = std::lower_bound(cell.begin(), cell.end(), k_min);
  std::vector<Projection> minima;
  double window_end = 1e300;
  int previous_k = -2;
  Projection previous{1e300, 0.0};
  bool previous_falling = true;  // the distance fell into the previous segment (or it starts a run)
  auto close_run_at_previous = [&]() {
    if (previous_k >= 0 && previous_falling) minima.push_back(previous);
  };
  for (; it != cell.end(); ++it) {
    const int k = *it;
    if (path.s_of_segment_start(k) > window_end) break;
    const Projection p = path.project(k, x, y, z);
    if (p.distance_mm > reach_mm) continue;
    if (k != previous_k + 1) {  // a new run of segments within reach
      close_run_at_previous();
      previous_falling = true;
    } else {
      if (p.distance_mm > previous.distance_mm) {
        if (previous_falling) minima.push_back(previous);
        previous_falling = false;
      } else {
        previous_falling = true;
      }
    }
    previous_k = k;
    previous = p;
    if (window_end > 1e299) window_end = path.s_of_segment_start(k) + window_mm;
  }
  close_run_at_previous();
  if (minima.empty()) return std::nullopt;
  double best = 1e300;
  for (const auto& m : minima) best = std::min(best, m.distance_mm);
  for (const auto& m : minima) {
    if (m.distance_mm <= best + tie_mm) return m;
  }
  return minima.front();
}

// ---------------------------------------------------------------------------------------------------
// Signals on a uniform time grid.

// Value at `x` of the piecewise-linear function through (xs, ys), xs non-decreasing; `outside` beyond.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x, double outside) {
  if (xs.empty() || !(x >= xs.front()) || !(x <= xs.back())) return outside;
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  if (it == xs.end()) return ys.back();
  const std::size_t j = static_cast<std::size_t>(it - xs.begin());
  if (j == 0) return ys.front();
  const double x0 = xs[j - 1], x1 = xs[j];
  const double w = x1 > x0 ? (x - x0) / (x1 - x0) : 1.0;
  return ys[j - 1] + w * (ys[j] - ys[j - 1]);
}

// Mean per bin of (time, value) pairs; NaN for bins without a value.
std::vector<double> bin_means(const std::vector<double>& t_s, const std::vector<double>& value, double t0_s,
                              double bin_s, std::size_t bins) {
  std::vector<double> sum(bins, 0.0);
  std::vector<int> count(bins, 0);
  for (std::size_t i = 0; i < t_s.size(); ++i) {
    if (!std::isfinite(value[i])) continue;
    const double f = (t_s[i] - t0_s) / bin_s;
    if (!(f >= 0.0)) continue;
    const std::size_t b = static_cast<std::size_t>(f);
    if (b >= bins) continue;
    sum[b] += value[i];
    ++count[b];
  }
  std::vector<double> mean(bins, kNaN);
  for (std::size_t b = 0; b < bins; ++b) {
    if (count[b] > 0) mean[b] = sum[b] / count[b];
  }
  return mean;
}

// Centred running maximum over `width` bins (odd), of the finite values only: the peak envelope.
std::vector<double> moving_max(const std::vector<double>& x, int width) {
  if (width <= 1) return x;
  const std::size_t half = static_cast<std::size_t>(width / 2);
  const std::size_t n = x.size();
  std::vector<double> out(n, kNaN);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) continue;
    double most = x[i];
    for (std::size_t j = i >= half ? i - half : 0; j < std::min(n, i + half + 1); ++j) {
      if (std::isfinite(x[j])) most = std::max(most, x[j]);
    }
    out[i] = most;
  }
  return out;
}

// 1 where the measured peak envelope (running maximum over `width` bins) exceeds kContactFraction of
// its maximum (the 99.9th percentile, so single spikes do not set it), 0 elsewhere, NaN without data.
std::vector<double> in_contact(const std::vector<double>& force_bins, int width) {
  std::vector<double> envelope = moving_max(force_bins, width);
  std::vector<double> finite;
  for (double v : envelope) {
    if (std::isfinite(v)) finite.push_back(v);
  }
  if (finite.empty()) return envelope;
  const std::size_t k = static_cast<std::size_t>(0.999 * static_cast<double>(finite.size() - 1));
  std::nth_element(finite.begin(), finite.begin() + static_cast<long>(k), finite.end());
  const double threshold = kContactFraction * finite[k];
  for (double& v : envelope) {
    if (std::isfinite(v)) v = v > threshold ? 1.0 : 0.0;
  }
  return envelope;
}

struct CorrelationPeak {
  double lag_bins = 0.0;     // interpolated lag of the maximum
  double correlation = 0.0;  // Pearson coefficient there
  bool at_edge = false;      // the maximum lies on the edge of the searched range
  bool found = false;
};

// Pearson correlation of x[i] with y[i − lag] for lag in [lag_min, lag_max]; y outside its range takes
// `y_outside` (NaN: the pair is left out). Pairs with a NaN are left out. The maximum is refined by a
// parabola through its neighbours.
CorrelationPeak correlate(const std::vector<double>& x, const std::vector<double>& y, long lag_min, long lag_max,
                          double y_outside) {
  CorrelationPeak peak;
  std::vector<double> r(static_cast<std::size_t>(lag_max - lag_min + 1), kNaN);
  const long nx = static_cast<long>(x.size()), ny = static_cast<long>(y.size());
  for (long lag = lag_min; lag <= lag_max; ++lag) {
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    long n = 0;
    for (long i = 0; i < nx; ++i) {
      const double xi = x[static_cast<std::size_t>(i)];
      if (!std::isfinite(xi)) continue;
      const long j = i - lag;
      const double yj = (j >= 0 && j < ny) ? y[static_cast<std::size_t>(j)] : y_outside;
      if (!std::isfinite(yj)) continue;
      sx += xi;
      sy += yj;
      sxx += xi * xi;
      syy += yj * yj;
      sxy += xi * yj;
      ++n;
    }
    if (n < 3) continue;
    const double cov = sxy - sx * sy / n;
    const double vx = sxx - sx * sx / n;
    const double vy = syy - sy * sy / n;
    if (vx <= 0.0 || vy <= 0.0) continue;
    r[static_cast<std::size_t>(lag - lag_min)] = cov / std::sqrt(vx * vy);
  }
  std::size_t best = r.size();
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (std::isfinite(r[k]) && (best == r.size() || r[k] > r[best])) best = k;
  }
  if (best == r.size()) return peak;
  peak.found = true;
  peak.correlation = r[best];
  // A flat top (contact signals of different length): its middle.
  std::size_t lo = best, hi = best;
  while (lo > 0 && r[lo - 1] >= r[best] - kFlatTop) --lo;
  while (hi + 1 < r.size() && r[hi + 1] >= r[best] - kFlatTop) ++hi;
  peak.lag_bins = static_cast<double>(lag_min) + 0.5 * static_cast<double>(lo + hi);
  peak.at_edge = lo == 0 || hi + 1 == r.size();
  if (lo == hi && !peak.at_edge && std::isfinite(r[best - 1]) && std::isfinite(r[best + 1])) {
    const double a = r[best - 1], b = r[best], c = r[best + 1];
    const double denominator = a - 2.0 * b + c;
    if (denominator < 0.0) peak.lag_bins += std::clamp(0.5 * (a - c) / denominator, -0.5, 0.5);
  }
  return peak;
}

// Spindle speed for smoothing over one revolution: the log's column, its metadata, else the program's.
double spindle_rpm_for(const force_log::ForceLog& log, const planner::PlanResult& plan) {
  if (const double logged = logged_spindle_rpm(log); logged > 0.0) return logged;
  double most = 0.0;
  for (const auto& block : plan.program.blocks) most = std::max(most, block.spindle_rpm);
  return most;
}

std::vector<double> force_xy(const force_log::ForceLog& log) {
  std::vector<double> f(log.rows.size(), kNaN);
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    if (finite_force(log.rows[i])) f[i] = std::hypot(log.rows[i].fx_n, log.rows[i].fy_n);
  }
  return f;
}

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

// Median time step of the rows, s.
double median_step_s(const force_log::ForceLog& log) {
  std::vector<double> dt;
  for (std::size_t i = 1; i < log.rows.size(); ++i) dt.push_back(log.rows[i].t_s - log.rows[i - 1].t_s);
  if (dt.empty()) return 1e-3;
  std::nth_element(dt.begin(), dt.begin() + static_cast<long>(dt.size() / 2), dt.end());
  return dt[dt.size() / 2];
}

// Rows, NaN rows and gaps (shared by both methods).
void count_rows(const force_log::ForceLog& log, Alignment& out) {
  out.rows = static_cast<int>(log.rows.size());
  std::vector<double> dt;
  dt.reserve(log.rows.size());
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    const auto& row = log.rows[i];
    if ((log.has_positions && !finite_xy(row)) || (log.has_forces && !finite_force(row))) ++out.rows_with_nan;
    if (i > 0) dt.push_back(row.t_s - log.rows[i - 1].t_s);
  }
  if (dt.empty()) return;
  const double median = median_step_s(log);
  for (double step : dt) {
    if (step > kGapFactor * median) ++out.gaps;
  }
}

std::string row_text(const force_log::ForceLog& log, std::size_t i) {
  return "row " + std::to_string(i + 1) + " (t = " + fixed(log.rows[i].t_s, 4) + " s)";
}

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

// ---------------------------------------------------------------------------------------------------
// Method 1: positions.

struct PositionMatch {
  std::vector<double> s_mm;
  std::size_t first = 0, last = 0;  // first and last matched rows (first > last: none)
  int off_path = 0;                 // unmatched rows among those
  std::size_t first_off_path = 0;
  int leading = 0, trailing = 0;  // rows before the program (first match at the path's start) / after it
  int span_rows = 0;              // rows with positions that should follow the path
};

// The part of the path where the tool is in material: from the first to the last engaged plan sample
// (the whole path when none is engaged).
struct CutSpan {
  double first_mm = 0.0;
  double last_mm = 0.0;
};

CutSpan cut_span(const planner::PlanResult& plan) {
  CutSpan span{plan.samples.empty() ? 0.0 : plan.samples.front().s_mm, plan.samples.empty() ? 0.0 : plan.samples.back().s_mm};
  const auto first = std::find_if(plan.samples.begin(), plan.samples.end(), [](const auto& p) { return p.engaged; });
  if (first == plan.samples.end()) return span;
  const auto last = std::find_if(plan.samples.rbegin(), plan.samples.rend(), [](const auto& p) { return p.engaged; });
  return {first->s_mm, last->s_mm};
}

PositionMatch match_positions(const force_log::ForceLog& log, const PathIndex& path, double scale, double reach_mm,
                              const CutSpan& cut) {
  PositionMatch m;
  const std::size_t n = log.rows.size();
  m.s_mm.assign(n, kNaN);
  m.first = n;
  // Backward tolerance for position noise; the stretch after the first candidate searched for a nearer one.
  const double back_mm = std::min(0.1, reach_mm);
  const double window_mm = 2.0 + 4.0 * reach_mm;
  const double tie_mm = 0.1 * reach_mm;
  double anchor_mm = -1e300;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& row = log.rows[i];
    if (!finite_xy(row)) continue;
    const int k_min = anchor_mm > -1e299 ? path.segment_at(anchor_mm - back_mm) : 0;
    const auto match =
        match_row(path, scale * row.x_mm, scale * row.y_mm, scale * row.z_mm, k_min, reach_mm, window_mm, tie_mm);
    if (!match) continue;
    m.s_mm[i] = match->s_mm;
    anchor_mm = std::max(anchor_mm, match->s_mm);
    if (m.first == n) m.first = i;
    m.last = i;
  }
  if (m.first == n) {
    for (std::size_t i = 0; i < n; ++i) m.leading += finite_xy(log.rows[i]) ? 1 : 0;
    return m;
  }
  // Rows before the machine reaches the part of the path in material are the machine arriving — from
  // its home, through the program's own approach moves, which a forward match cannot follow back up a
  // plunge — and are neither matched nor off the path, when that first arrival lies before the cut
  // starts; the same for rows after the cut when the last match lies after it. Otherwise rows before
  // the first match or after the last one left the path.
  const double near_mm = 2.0 * reach_mm + 1.0;
  std::size_t cut_first = m.first;
  while (cut_first <= m.last && !(std::isfinite(m.s_mm[cut_first]) && m.s_mm[cut_first] >= cut.first_mm - near_mm)) {
    ++cut_first;
  }
  std::size_t cut_last = m.last;
  while (cut_last > cut_first && !(std::isfinite(m.s_mm[cut_last]) && m.s_mm[cut_last] <= cut.last_mm + near_mm)) {
    --cut_last;
  }
  const bool arrives_before_cut = m.s_mm[m.first] <= cut.first_mm + near_mm;
  const bool leaves_after_cut = m.s_mm[m.last] >= cut.last_mm - near_mm;
  m.span_rows = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite_xy(log.rows[i])) continue;
    const bool before = i < (arrives_before_cut ? cut_first : m.first);
    const bool after = i > (leaves_after_cut ? cut_last : m.last);
    if ((before && arrives_before_cut) || (after && leaves_after_cut)) {
      if (!std::isfinite(m.s_mm[i])) ++(before ? m.leading : m.trailing);  // off the path, not on its approach
      continue;
    }
    ++m.span_rows;
    if (std::isfinite(m.s_mm[i])) continue;
    if (m.off_path == 0) m.first_off_path = i;
    ++m.off_path;
  }
  return m;
}

// Why the rows do not follow the path, or "" when they do.
std::string not_this_program(const force_log::ForceLog& log, const PathIndex& path, const PositionMatch& m,
                             const AlignmentOptions& options, double scale) {
  const std::size_t n = log.rows.size();
  auto distance_of = [&](std::size_t i) {
    const auto& row = log.rows[i];
    return path.distance_to_path(scale * row.x_mm, scale * row.y_mm, scale * row.z_mm);
  };
  const std::string reach = fixed(options.max_distance_mm, 2) + " mm";
  if (m.first == n) {
    std::size_t i = 0;
    while (i < n && !finite_xy(log.rows[i])) ++i;
    if (i == n) return "no row has a position";
    return "no logged position comes within " + reach + " of the planned path; " + row_text(log, i) + " is " +
           fixed(distance_of(i), 2) + " mm from it";
  }
  const double span_rows = static_cast<double>(m.span_rows);
  if (m.off_path > options.max_off_path_fraction * span_rows) {
    return std::to_string(m.off_path) + " of " + std::to_string(m.span_rows) + " rows (" +
           percent(m.off_path / span_rows) + ", allowed " + percent(options.max_off_path_fraction) +
           ") are more than " + reach + " from the planned path; the first, " + row_text(log, m.first_off_path) +
           ", is " + fixed(distance_of(m.first_off_path), 2) + " mm from it";
  }
  return "";
}

// Force delay: cross-correlation of when the tool is in contact by the measured force with when the plan
// has it engaged, at each row's place (see the file comment).
void estimate_delay(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options,
                    Alignment& out, std::string& text) {
  if (!log.has_forces) {
    text += "; force delay not estimated (the log has no forces)";
    return;
  }
  std::vector<double> plan_s, plan_engaged;
  for (const auto& sample : plan.samples) {
    plan_s.push_back(sample.s_mm);
    plan_engaged.push_back(sample.engaged ? 1.0 : 0.0);
  }
  const std::size_t n = log.rows.size();
  std::vector<double> t(n), predicted(n, kNaN);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = log.rows[i].t_s;
    if (std::isfinite(out.s_mm[i])) {
      predicted[i] = interpolate(plan_s, plan_engaged, out.s_mm[i], 0.0);
    } else if (finite_xy(log.rows[i])) {
      predicted[i] = 0.0;  // before or after the program, or off the path: not cutting the planned stock
    }
  }
  const std::vector<double> measured_rows = force_xy(log);
  const double span_s = t.back() - t.front();
  double bin_s = std::max(median_step_s(log), kMinDelayBinS);
  bin_s = std::max(bin_s, span_s / 2e4);  // keeps the search small on long logs
  const std::size_t bins = static_cast<std::size_t>(span_s / bin_s) + 1;
  const double rpm = spindle_rpm_for(log, plan);
  const int width = rpm > 0.0 ? 2 * static_cast<int>(0.5 * (60.0 / rpm) / bin_s) + 1 : 1;
  const std::vector<double> measured = in_contact(bin_means(t, measured_rows, t.front(), bin_s, bins), width);
  const std::vector<double> expected = moving_max(bin_means(t, predicted, t.front(), bin_s, bins), width);
  const long max_lag = static_cast<long>(std::ceil(options.max_delay_s / bin_s));
  const CorrelationPeak peak = correlate(measured, expected, -max_lag, max_lag, 0.0);
  if (!peak.found) {
    text += "; force delay not estimated (no contact, or contact throughout, in the measured or planned force)";
    return;
  }
  out.delay_s = std::clamp(peak.lag_bins * bin_s, -options.max_delay_s, options.max_delay_s);
  out.delay_correlation = peak.correlation;
  text += "; force delay " + fixed(1e3 * out.delay_s, 1) + " ms (correlation " + fixed(peak.correlation, 2) + ")";
  if (peak.at_edge) {
    text += " at the edge of the searched range +-" + fixed(1e3 * options.max_delay_s, 0) +
            " ms: the true delay may be larger";
  }
  if (peak.correlation < 0.5) text += ", weak: check that the log belongs to this plan";
}

Alignment align_by_positions(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options,
                             bool check_units) {
  Alignment out;
  out.method = AlignmentMethod::kPositions;
  count_rows(log, out);
  const PathIndex path(plan, options.max_distance_mm);
  const CutSpan cut = cut_span(plan);
  const PositionMatch m = match_positions(log, path, 1.0, options.max_distance_mm, cut);
  const std::string problem = not_this_program(log, path, m, options, 1.0);
  if (!problem.empty()) {
    out.s_mm.assign(log.rows.size(), kNaN);
    if (check_units) {
      for (const double scale : {kMmPerInch, 1.0 / kMmPerInch}) {
        const PositionMatch scaled = match_positions(log, path, scale, options.max_distance_mm, cut);
        if (scaled.first < log.rows.size() && not_this_program(log, path, scaled, options, scale).empty()) {
          out.status = AlignmentStatus::kUnitsLookWrong;
          out.message = scale > 1.0
                            ? "the logged positions fit the planned path after x 25.4: the log looks like inches; "
                              "convert it to mm"
                            : "the logged positions fit the planned path after / 25.4: the log is scaled by "
                              "25.4 (mm read as inches?); convert it to mm";
          return out;
        }
      }
    }
    out.status = AlignmentStatus::kNotThisProgram;
    out.message = "the log does not follow the planned path: " + problem;
    return out;
  }
  out.s_mm = m.s_mm;
  out.rows_off_path = m.off_path;
  std::string text = "aligned by positions";
  if (m.leading > 0) text += "; " + std::to_string(m.leading) + " rows before the path starts";
  if (m.trailing > 0) text += "; " + std::to_string(m.trailing) + " rows after it ends";
  if (m.off_path > 0) {
    text += "; " + std::to_string(m.off_path) + " rows off the path (first: " + row_text(log, m.first_off_path) + ")";
  }
  finish_coverage(plan, log, out, text);
  if (options.estimate_delay && usable(out.status)) estimate_delay(log, plan, options, out, out.message);
  return out;
}

// ---------------------------------------------------------------------------------------------------
// Method 2: the plan's time profile.

Alignment align_by_time_profile(const force_log::ForceLog& log, const planner::PlanResult& plan) {
  Alignment out;
  out.method = AlignmentMethod::kTimeProfile;
  count_rows(log, out);
  out.s_mm.assign(log.rows.size(), kNaN);
  const std::string method = "aligned by the plan's predicted time profile (the log has no positions)";
  std::vector<double> plan_t, plan_s, plan_engaged;
  for (const auto& sample : plan.samples) {
    plan_t.push_back(sample.time_s);
    plan_s.push_back(sample.s_mm);
    plan_engaged.push_back(sample.engaged ? 1.0 : 0.0);
  }
  const std::size_t n = log.rows.size();
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = log.rows[i].t_s;
  const double log_span_s = t.back() - t.front();
  const double plan_span_s = plan_t.back() - plan_t.front();
  const double bin_s = std::max(kMinTimeProfileBinS, (log_span_s + plan_span_s) / kMaxTimeProfileBins);
  const std::size_t log_bins = static_cast<std::size_t>(log_span_s / bin_s) + 1;
  const std::size_t plan_bins = static_cast<std::size_t>(plan_span_s / bin_s) + 1;
  const double rpm = spindle_rpm_for(log, plan);
  const int width = rpm > 0.0 ? 2 * static_cast<int>(0.5 * (60.0 / rpm) / bin_s) + 1 : 1;
  const std::vector<double> measured = in_contact(bin_means(t, force_xy(log), t.front(), bin_s, log_bins), width);
  std::vector<double> expected(plan_bins);
  for (std::size_t j = 0; j < plan_bins; ++j) {
    expected[j] = interpolate(plan_t, plan_engaged, plan_t.front() + (static_cast<double>(j) + 0.5) * bin_s, 0.0);
  }
  expected = moving_max(expected, width);
  // measured[i] (log time t0 + i h) pairs with expected[i − lag] (plan time (i − lag) h): the program
  // started at log time t0 + lag h. Outside the plan the machine does not cut: 0.
  const CorrelationPeak peak =
      correlate(measured, expected, -static_cast<long>(plan_bins), static_cast<long>(log_bins), 0.0);
  if (!peak.found) {
    out.status = AlignmentStatus::kNoCut;
    out.message = method +
                  "; the measured force never changes between air and contact (no cut, or in the cut throughout): "
                  "nothing to align the plan's time profile by";
    return out;
  }
  const double start_s = t.front() + peak.lag_bins * bin_s - plan_t.front();
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = t[i] - start_s;
    if (tau >= plan_t.front() && tau <= plan_t.back()) out.s_mm[i] = interpolate(plan_t, plan_s, tau, kNaN);
  }
  std::string text = method + ": the program starts at t = " + fixed(start_s, 3) +
                     " s on the log's clock (correlation " + fixed(peak.correlation, 2) +
                     "); s follows the predicted speeds, good to a few mm";
  if (peak.correlation < 0.5) text += "; weak correlation: check that the log belongs to this plan";
  finish_coverage(plan, log, out, text);
  return out;
}

}  // namespace

std::string to_string(AlignmentMethod method) {
  switch (method) {
    case AlignmentMethod::kPositions:
      return "positions";
    case AlignmentMethod::kTimeProfile:
      return "time profile";
  }
  return "?";
}

std::string to_string(AlignmentStatus status) {
  switch (status) {
    case AlignmentStatus::kOk:
      return "ok";
    case AlignmentStatus::kNotThisProgram:
      return "not this program";
    case AlignmentStatus::kNoCut:
      return "no cut";
    case AlignmentStatus::kTruncated:
      return "truncated";
    case AlignmentStatus::kUnitsLookWrong:
      return "units look wrong";
  }
  return "?";
}

bool usable(AlignmentStatus status) { return status == AlignmentStatus::kOk || status == AlignmentStatus::kTruncated; }

Alignment align_log(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options) {
  std::vector<InputProblem> problems;
  if (!(std::isfinite(options.max_distance_mm) && options.max_distance_mm > 0.0)) {
    problems.push_back(
        {"alignment.max_distance_mm", "= " + shortest_number_text(options.max_distance_mm) + ": must be > 0"});
  }
  if (!(options.max_off_path_fraction >= 0.0 && options.max_off_path_fraction <= 1.0)) {
    problems.push_back({"alignment.max_off_path_fraction",
                        "= " + shortest_number_text(options.max_off_path_fraction) + ": must be in [0, 1]"});
  }
  if (!(std::isfinite(options.max_delay_s) && options.max_delay_s >= 0.0)) {
    problems.push_back({"alignment.max_delay_s", "= " + shortest_number_text(options.max_delay_s) + ": must be >= 0"});
  }
  if (!log.has_positions && !log.has_forces) {
    problems.push_back({"log",
                        "has neither positions nor forces: nothing to align by (turn currents into forces "
                        "first, forces_from_currents)"});
  }
  if (log.rows.empty()) problems.push_back({"log", "has no rows"});
  for (std::size_t i = 1; i < log.rows.size(); ++i) {
    if (!(log.rows[i].t_s > log.rows[i - 1].t_s)) {
      problems.push_back({"log row " + std::to_string(i + 1) + " t_s",
                          "= " + shortest_number_text(log.rows[i].t_s) + ": must be greater than the previous row's " +
                              shortest_number_text(log.rows[i - 1].t_s)});
      break;
    }
  }
  if (!problems.empty()) throw InputError(std::move(problems));
  if (plan.samples.empty()) {
    Alignment out;
    count_rows(log, out);
    out.method = log.has_positions ? AlignmentMethod::kPositions : AlignmentMethod::kTimeProfile;
    out.status = AlignmentStatus::kNoCut;
    out.s_mm.assign(log.rows.size(), kNaN);
    out.message = "the plan has no samples: nothing to align with";
    return out;
  }
  return log.has_positions ? align_by_positions(log, plan, options, true) : align_by_time_profile(log, plan);
}

}  // namespace feedplan::learning
