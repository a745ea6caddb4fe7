#include "feedplan/planner/plan_plot.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string_view>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/number_text.hpp"

namespace feedplan::planner {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// Page layout, px: margins around the stack of panels and the gap between panels.
constexpr double kMarginLeftPx = 90.0;
constexpr double kMarginRightPx = 30.0;
constexpr double kMarginTopPx = 56.0;
constexpr double kMarginBottomPx = 64.0;
constexpr double kPanelGapPx = 30.0;
constexpr double kLegendRowPx = 16.0;

// Colours and strokes of the series.
constexpr const char* kEngagementStyle = "stroke=\"#1f77b4\" stroke-width=\"1\"";
constexpr const char* kBlockFeedStyle = "stroke=\"#1a237e\" stroke-width=\"1.5\"";
constexpr const char* kPredictedFeedStyle = "stroke=\"#ff7f0e\" stroke-width=\"1\"";
constexpr const char* kFeedLimitStyle = "stroke=\"#555555\" stroke-width=\"1\" stroke-dasharray=\"1 3\"";
constexpr const char* kForceStyle = "stroke=\"#1f77b4\" stroke-width=\"1\"";
constexpr const char* kTargetStyle = "stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"";
constexpr const char* kPeakColor = "#d62728";

// A pixel coordinate with one decimal (0.1 px is below what any screen shows).
std::string px(double value) {
  std::array<char, 32> buffer{};
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, 1).ptr;
  const std::string_view text(buffer.data(), static_cast<std::size_t>(end - buffer.data()));
  return text == "-0.0" ? "0.0" : std::string(text);
}

// Text content and attribute values in XML: the five characters with a meaning there, as entities.
std::string xml_text(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      out += "&lt;";
    } else if (c == '>') {
      out += "&gt;";
    } else if (c == '&') {
      out += "&amp;";
    } else if (c == '"') {
      out += "&quot;";
    } else if (c == '\'') {
      out += "&#39;";
    } else {
      out += c;
    }
  }
  return out;
}

// An axis: the range drawn and ticks at whole multiples of a 1-2-5 step (1, 2 or 5 × 10^k) inside it.
struct Axis {
  double lo = 0.0;
  double hi = 1.0;
  double step = 0.2;
  int decimals = 1;        // tick labels show the step exactly
  long long first = 0;     // ticks at n · step for n in [first, last]
  long long last = 5;
};

// The smallest 1-2-5 step that covers [lo, hi] in at most `max_intervals` whole steps. With `rounded`, the
// range widens to whole steps (value axes start and end at a tick); without, it stays [lo, hi] (the path
// axis: no empty space after the last sample).
Axis nice_axis(double lo, double hi, int max_intervals, bool rounded) {
  if (!(hi > lo)) hi = lo + (lo != 0.0 ? std::abs(lo) : 1.0);
  const int exponent = static_cast<int>(std::floor(std::log10((hi - lo) / max_intervals)));
  for (int k = exponent;; ++k) {
    for (const double mantissa : {1.0, 2.0, 5.0}) {
      const double step = mantissa * std::pow(10.0, k);
      const auto below = static_cast<long long>(std::floor(lo / step + 1e-9));
      const auto above = static_cast<long long>(std::ceil(hi / step - 1e-9));
      if (above - below > max_intervals) continue;
      Axis axis{lo, hi, step, std::max(0, -k), below, above};
      if (rounded) {
        axis.lo = static_cast<double>(below) * step;
        axis.hi = static_cast<double>(above) * step;
      } else {
        axis.first = static_cast<long long>(std::ceil(lo / step - 1e-9));
        axis.last = static_cast<long long>(std::floor(hi / step + 1e-9));
      }
      return axis;
    }
  }
}

std::string tick_label(const Axis& axis, double value) {
  std::array<char, 48> buffer{};
  const auto end =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, axis.decimals).ptr;
  std::string text(buffer.data(), end);
  if (text.front() == '-' && text.find_first_of("123456789") == std::string::npos) text.erase(0, 1);
  return text;
}

// One panel: its rectangle on the page and the data ranges mapped onto it.
struct Panel {
  double left_px, right_px, top_px, bottom_px;
  Axis x, y;

  double to_x(double value) const { return left_px + (value - x.lo) / (x.hi - x.lo) * (right_px - left_px); }
  double to_y(double value) const { return bottom_px - (value - y.lo) / (y.hi - y.lo) * (bottom_px - top_px); }
  std::size_t columns() const { return static_cast<std::size_t>(std::max(1.0, std::floor(right_px - left_px))); }
};

// Min/max decimation per pixel column, with gaps. The points (x[i], y[i]) with finite values form runs
// separated by non-finite ones; in each run and pixel column the first, the lowest, the highest and the
// last point are kept (each once, in order), so the line looks as at full resolution and every extreme
// keeps its exact value. Returns the kept indices of each run.
std::vector<std::vector<std::size_t>> decimate(const std::vector<double>& x, const std::vector<double>& y,
                                               const Panel& panel) {
  const std::size_t columns = panel.columns();
  const double scale = static_cast<double>(columns) / (panel.x.hi - panel.x.lo);
  std::vector<std::vector<std::size_t>> runs;
  struct Column {
    std::size_t index = 0, first = 0, lowest = 0, highest = 0, last = 0;
  };
  std::optional<Column> open;
  const auto close_column = [&]() {
    if (!open) return;
    std::array<std::size_t, 4> picks{open->first, open->lowest, open->highest, open->last};
    std::sort(picks.begin(), picks.end());
    std::vector<std::size_t>& run = runs.back();
    for (const std::size_t i : picks) {
      if (run.empty() || run.back() != i) run.push_back(i);
    }
    open.reset();
  };
  bool in_run = false;
  for (std::size_t i = 0; i < y.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      close_column();
      in_run = false;
      continue;
    }
    if (!in_run) {
      runs.emplace_back();
      in_run = true;
    }
    const double position = std::clamp(std::floor((x[i] - panel.x.lo) * scale), 0.0, static_cast<double>(columns - 1));
    const auto column = static_cast<std::size_t>(position);
    if (open && open->index == column) {
      open->last = i;
      if (y[i] < y[open->lowest]) open->lowest = i;
      if (y[i] > y[open->highest]) open->highest = i;
      continue;
    }
    close_column();
    open = Column{column, i, i, i, i};
  }
  close_column();
  return runs;
}

// A series as one <path>: "M" starts each run, further points are implicit line-tos.
void append_series(std::string& svg, const Panel& panel, const std::vector<double>& x, const std::vector<double>& y,
                   const char* css_class, const char* style) {
  const std::vector<std::vector<std::size_t>> runs = decimate(x, y, panel);
  if (runs.empty()) return;
  svg += "<path class=\"";
  svg += css_class;
  svg += "\" fill=\"none\" stroke-linejoin=\"round\" stroke-linecap=\"round\" ";
  svg += style;
  svg += " d=\"";
  for (const std::vector<std::size_t>& run : runs) {
    for (std::size_t k = 0; k < run.size(); ++k) {
      svg += k == 0 ? (svg.back() == '"' ? "M" : " M") : " ";
      svg += px(panel.to_x(x[run[k]]));
      svg += ',';
      svg += px(panel.to_y(y[run[k]]));
    }
    if (run.size() == 1) svg += " l0,0";  // a lone point shows as a dot (round cap)
  }
  svg += "\"/>\n";
}

// A legend entry: a short line in the series' style (or a marker) and its label.
struct LegendEntry {
  std::string label;
  std::string style;   // stroke attributes of the line; empty: a marker in kPeakColor
};

void append_panel_frame(std::string& svg, const Panel& panel, const std::string& y_label, bool x_labels,
                        const std::string& x_label) {
  svg += "<g stroke=\"#dddddd\" stroke-width=\"1\">\n";
  for (long long n = panel.x.first; n <= panel.x.last; ++n) {
    const std::string x = px(panel.to_x(static_cast<double>(n) * panel.x.step));
    svg += "<line x1=\"" + x + "\" y1=\"" + px(panel.top_px) + "\" x2=\"" + x + "\" y2=\"" + px(panel.bottom_px) +
           "\"/>\n";
  }
  for (long long n = panel.y.first; n <= panel.y.last; ++n) {
    const std::string y = px(panel.to_y(static_cast<double>(n) * panel.y.step));
    svg += "<line x1=\"" + px(panel.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(panel.right_px) + "\" y2=\"" + y +
           "\"/>\n";
  }
  svg += "</g>\n<g fill=\"#333333\">\n";
  for (long long n = panel.y.first; n <= panel.y.last; ++n) {
    const double value = static_cast<double>(n) * panel.y.step;
    svg += "<text class=\"y-tick\" x=\"" + px(panel.left_px - 6) + "\" y=\"" + px(panel.to_y(value)) +
           "\" text-anchor=\"end\" dominant-baseline=\"middle\">" + tick_label(panel.y, value) + "</text>\n";
  }
  if (x_labels) {
    for (long long n = panel.x.first; n <= panel.x.last; ++n) {
      const double value = static_cast<double>(n) * panel.x.step;
      svg += "<text class=\"x-tick\" x=\"" + px(panel.to_x(value)) + "\" y=\"" + px(panel.bottom_px + 16) +
             "\" text-anchor=\"middle\">" + tick_label(panel.x, value) + "</text>\n";
    }
    svg += "<text x=\"" + px(0.5 * (panel.left_px + panel.right_px)) + "\" y=\"" + px(panel.bottom_px + 40) +
           "\" text-anchor=\"middle\">" + xml_text(x_label) + "</text>\n";
  }
  const std::string middle_y = px(0.5 * (panel.top_px + panel.bottom_px));
  svg += "<text x=\"24\" y=\"" + middle_y + "\" text-anchor=\"middle\" transform=\"rotate(-90 24 " + middle_y +
         ")\">" + xml_text(y_label) + "</text>\n</g>\n";
  svg += "<rect x=\"" + px(panel.left_px) + "\" y=\"" + px(panel.top_px) + "\" width=\"" +
         px(panel.right_px - panel.left_px) + "\" height=\"" + px(panel.bottom_px - panel.top_px) +
         "\" fill=\"none\" stroke=\"#333333\"/>\n";
}

// The legend in the panel's top right corner, on a white box so that lines under it do not hide it.
void append_legend(std::string& svg, const Panel& panel, const std::vector<LegendEntry>& entries) {
  std::size_t longest = 0;
  for (const LegendEntry& entry : entries) longest = std::max(longest, entry.label.size());
  const double width = 48.0 + 6.5 * static_cast<double>(longest);
  const double left = panel.right_px - width - 6.0;
  const double top = panel.top_px + 6.0;
  svg += "<g class=\"legend\">\n<rect x=\"" + px(left) + "\" y=\"" + px(top) + "\" width=\"" + px(width) +
         "\" height=\"" + px(kLegendRowPx * static_cast<double>(entries.size()) + 6.0) +
         "\" fill=\"white\" fill-opacity=\"0.9\" stroke=\"#cccccc\"/>\n";
  double y = top + 3.0 + 0.5 * kLegendRowPx;
  for (const LegendEntry& entry : entries) {
    if (entry.style.empty()) {
      svg += "<circle cx=\"" + px(left + 20) + "\" cy=\"" + px(y) + "\" r=\"3\" fill=\"" + kPeakColor + "\"/>\n";
    } else {
      svg += "<line x1=\"" + px(left + 8) + "\" y1=\"" + px(y) + "\" x2=\"" + px(left + 32) + "\" y2=\"" + px(y) +
             "\" " + entry.style + "/>\n";
    }
    svg += "<text x=\"" + px(left + 40) + "\" y=\"" + px(y) + "\" dominant-baseline=\"middle\">" +
           xml_text(entry.label) + "</text>\n";
    y += kLegendRowPx;
  }
  svg += "</g>\n";
}

void append_no_data(std::string& svg, const Panel& panel) {
  svg += "<text x=\"" + px(0.5 * (panel.left_px + panel.right_px)) + "\" y=\"" +
         px(0.5 * (panel.top_px + panel.bottom_px)) + "\" text-anchor=\"middle\" fill=\"#888888\">no data</text>\n";
}

// Largest finite value of `values` (−∞ when there is none).
double largest(const std::vector<double>& values) {
  double high = -std::numeric_limits<double>::infinity();
  for (const double v : values) {
    if (std::isfinite(v)) high = std::max(high, v);
  }
  return high;
}

}  // namespace

std::string plan_plot_svg(const PlanResult& result, double target_force_n, const PlanPlotOptions& options) {
  assert(options.width_px >= 400.0 && options.height_px >= 400.0);
  assert(std::isfinite(target_force_n));
  const std::vector<PlannedSample>& samples = result.samples;
  const std::size_t n = samples.size();

  // The series, with NaN on rapids (gaps).
  std::vector<double> x(n), engagement_deg(n), predicted_feed(n), feed_limit(n), force_n(n);
  double force_low = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const PlannedSample& p = samples[i];
    const bool rapid = p.limit_reason == FeedLimitReason::kRapid;
    x[i] = options.x_is_time ? p.time_s : p.s_mm;
    engagement_deg[i] = rapid ? kNaN : p.engagement_rad * kRadToDeg;
    predicted_feed[i] = rapid ? kNaN : p.feed_mm_per_min;
    feed_limit[i] = rapid ? kNaN : p.feed_limit_mm_per_min;
    force_n[i] = rapid ? kNaN : p.predicted_force_n;
    if (std::isfinite(force_n[i])) force_low = std::min(force_low, force_n[i]);
  }
  // The programmed F as a step line: each feed block from its first to its last sample at its F.
  std::vector<double> step_x, step_feed;
  step_x.reserve(2 * result.blocks.size() + 1);
  step_feed.reserve(2 * result.blocks.size() + 1);
  for (const PlannedBlock& block : result.blocks) {
    const auto first = static_cast<std::size_t>(block.first_sample);
    const auto last = static_cast<std::size_t>(block.last_sample);
    if (first >= n || last >= n) continue;
    if (block.feed_mm_per_min <= 0.0) {  // a rapid
      step_x.push_back(x[first]);
      step_feed.push_back(kNaN);
      continue;
    }
    step_x.insert(step_x.end(), {x[first], x[last]});
    step_feed.insert(step_feed.end(), {block.feed_mm_per_min, block.feed_mm_per_min});
  }

  // Shared x axis and the page.
  const bool has_data = n > 0;
  const double x_first = has_data ? x.front() : 0.0;
  const double x_last = has_data ? x.back() : 1.0;
  const Axis x_axis = nice_axis(x_first, x_last, 10, false);
  const double panel_height = (options.height_px - kMarginTopPx - kMarginBottomPx - 2.0 * kPanelGapPx) / 3.0;
  const auto panel_at = [&](int row, const Axis& y_axis) {
    const double top = kMarginTopPx + row * (panel_height + kPanelGapPx);
    return Panel{kMarginLeftPx, options.width_px - kMarginRightPx, top, top + panel_height, x_axis, y_axis};
  };

  // Measured peaks inside the x range, in x order.
  std::vector<double> peak_x, peak_force;
  if (options.measured_peaks) {
    std::vector<std::pair<double, double>> peaks;
    for (const auto& [px_value, f_value] : *options.measured_peaks) {
      if (std::isfinite(px_value) && std::isfinite(f_value) && px_value >= x_axis.lo && px_value <= x_axis.hi) {
        peaks.emplace_back(px_value, f_value);
      }
    }
    std::sort(peaks.begin(), peaks.end());
    for (const auto& [px_value, f_value] : peaks) {
      peak_x.push_back(px_value);
      peak_force.push_back(f_value);
      force_low = std::min(force_low, f_value);
    }
  }

  const double engagement_high = std::max(largest(engagement_deg), 1.0);
  const double feed_high = std::max({largest(step_feed), largest(predicted_feed), 1.0});
  double force_high = std::max({largest(force_n), largest(peak_force), target_force_n, 1.0});
  force_high += 0.06 * (force_high - force_low);  // headroom: the highest peak stays off the frame
  const Panel engagement_panel = panel_at(0, nice_axis(0.0, engagement_high * 1.05, 6, true));
  const Panel feed_panel = panel_at(1, nice_axis(0.0, feed_high * 1.05, 6, true));
  const Panel force_panel = panel_at(2, nice_axis(force_low, force_high, 6, true));
  for (double& limit : feed_limit) limit = std::min(limit, feed_panel.y.hi);  // NaN stays NaN

  const std::string title = options.title.empty() ? "Feed plan" : options.title;
  const std::string x_label = options.x_is_time ? "time t [s]" : "path length s [mm]";
  const std::string target_label = "target " + shortest_number_text(target_force_n) + " N";

  std::string svg;
  svg.reserve(256 * 1024);
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(options.width_px) + "\" height=\"" +
         px(options.height_px) + "\" viewBox=\"0 0 " + px(options.width_px) + " " + px(options.height_px) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + xml_text(title) + "</title>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(0.5 * options.width_px) + "\" y=\"30\" text-anchor=\"middle\" font-size=\"16\">" +
         xml_text(title) + "</text>\n";

  // 1. Engagement.
  svg += "<g id=\"panel-engagement\">\n";
  append_panel_frame(svg, engagement_panel, "engagement α_en [deg]", false, x_label);
  append_series(svg, engagement_panel, x, engagement_deg, "engagement", kEngagementStyle);
  append_legend(svg, engagement_panel, {{"engagement angle", kEngagementStyle}});
  if (!has_data) append_no_data(svg, engagement_panel);
  svg += "</g>\n";

  // 2. Feed.
  svg += "<g id=\"panel-feed\">\n";
  append_panel_frame(svg, feed_panel, "feed [mm/min]", false, x_label);
  append_series(svg, feed_panel, x, feed_limit, "feed-limit", kFeedLimitStyle);
  append_series(svg, feed_panel, step_x, step_feed, "block-feed", kBlockFeedStyle);
  append_series(svg, feed_panel, x, predicted_feed, "predicted-feed", kPredictedFeedStyle);
  append_legend(svg, feed_panel,
                {{"programmed F (blocks)", kBlockFeedStyle},
                 {"predicted feed", kPredictedFeedStyle},
                 {"feed limit", kFeedLimitStyle}});
  if (!has_data) append_no_data(svg, feed_panel);
  svg += "</g>\n";

  // 3. Force.
  svg += "<g id=\"panel-force\">\n";
  append_panel_frame(svg, force_panel, "force F [N]", true, x_label);
  append_series(svg, force_panel, x, force_n, "predicted-force", kForceStyle);
  const std::string target_y = px(force_panel.to_y(target_force_n));
  svg += "<line class=\"target\" x1=\"" + px(force_panel.left_px) + "\" y1=\"" + target_y + "\" x2=\"" +
         px(force_panel.right_px) + "\" y2=\"" + target_y + "\" " + kTargetStyle + "/>\n";
  svg += "<text x=\"" + px(force_panel.left_px + 6) + "\" y=\"" + px(force_panel.to_y(target_force_n) - 5) +
         "\" fill=\"#2ca02c\">" + xml_text(target_label) + "</text>\n";
  std::vector<LegendEntry> force_legend{{"predicted force", kForceStyle}, {target_label, kTargetStyle}};
  if (options.measured_peaks) {
    // Markers at the decimated peaks: every highest and lowest one per pixel column is drawn.
    svg += "<g class=\"measured-peaks\" fill=\"";
    svg += kPeakColor;
    svg += "\">\n";
    for (const std::vector<std::size_t>& run : decimate(peak_x, peak_force, force_panel)) {
      for (const std::size_t k : run) {
        svg += "<circle cx=\"" + px(force_panel.to_x(peak_x[k])) + "\" cy=\"" +
               px(force_panel.to_y(peak_force[k])) + "\" r=\"2.5\"/>\n";
      }
    }
    svg += "</g>\n";
    force_legend.push_back({"measured peaks", ""});
  }
  append_legend(svg, force_panel, force_legend);
  if (!has_data) append_no_data(svg, force_panel);
  svg += "</g>\n</svg>\n";
  return svg;
}

std::string write_plan_plot(const std::filesystem::path& path, const PlanResult& result, double target_force_n,
                            const PlanPlotOptions& options) {
  return write_file_atomically(path, plan_plot_svg(result, target_force_n, options));
}

}  // namespace feedplan::planner
