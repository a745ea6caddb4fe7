#include "feedplan/planner/plan_plot.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string_view>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/core/svg_axis.hpp"
#include "feedplan/core/svg_series.hpp"

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

// Colours and strokes of the series.
constexpr const char* kEngagementStyle = "stroke=\"#1f77b4\" stroke-width=\"1\"";
constexpr const char* kBlockFeedStyle = "stroke=\"#1a237e\" stroke-width=\"1.5\"";
constexpr const char* kPredictedFeedStyle = "stroke=\"#ff7f0e\" stroke-width=\"1\"";
constexpr const char* kFeedLimitStyle = "stroke=\"#555555\" stroke-width=\"1\" stroke-dasharray=\"1 3\"";
constexpr const char* kForceStyle = "stroke=\"#1f77b4\" stroke-width=\"1\"";
constexpr const char* kTargetStyle = "stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"";
constexpr const char* kPeakColor = "#d62728";

using svg::Axis;
using svg::nice_axis;
using svg::px;

using svg::xml_text;
using svg::append_series;
using svg::decimate;
using svg::LegendEntry;
using svg::append_legend;

// One panel: its rectangle on the page and the data ranges mapped onto it.
using Panel = svg::PlotArea;

// Largest finite value of `values` (−∞ when there is none).
double largest(const std::vector<double>& values) {
  double high = -std::numeric_limits<double>::infinity();
  for (const double v : values) {
    if (std::isfinite(v)) high = std::max(high, v);
  }
  return high;
}

// The plan's lines, with NaN on rapids (gaps), and the measured peaks to mark.
struct PlotSeries {
  std::vector<double> x;               // per sample: path length or time
  std::vector<double> engagement_deg;  // per sample
  std::vector<double> predicted_feed;  // per sample, mm/min
  std::vector<double> feed_limit;      // per sample, mm/min
  std::vector<double> force_n;         // per sample, N
  std::vector<double> step_x;          // the programmed F as a step line
  std::vector<double> step_feed;
  std::vector<double> peak_x;          // measured peaks inside the x range, in x order
  std::vector<double> peak_force;
  double force_low = 0.0;              // lowest force of samples and peaks, at most 0, N
};

PlotSeries sample_series(const std::vector<PlannedSample>& samples, bool x_is_time) {
  const std::size_t n = samples.size();
  PlotSeries series;
  series.x.resize(n);
  series.engagement_deg.resize(n);
  series.predicted_feed.resize(n);
  series.feed_limit.resize(n);
  series.force_n.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PlannedSample& p = samples[i];
    const bool rapid = p.limit_reason == FeedLimitReason::kRapid;
    series.x[i] = x_is_time ? p.time_s : p.s_mm;
    series.engagement_deg[i] = rapid ? kNaN : p.engagement_rad * kRadToDeg;
    series.predicted_feed[i] = rapid ? kNaN : p.feed_mm_per_min;
    series.feed_limit[i] = rapid ? kNaN : p.feed_limit_mm_per_min;
    series.force_n[i] = rapid ? kNaN : p.predicted_force_n;
    if (std::isfinite(series.force_n[i])) series.force_low = std::min(series.force_low, series.force_n[i]);
  }
  return series;
}

// The programmed F as a step line: each feed block from its first to its last sample at its F.
void add_programmed_feed(PlotSeries& series, const std::vector<PlannedBlock>& blocks) {
  const std::size_t n = series.x.size();
  series.step_x.reserve(2 * blocks.size() + 1);
  series.step_feed.reserve(2 * blocks.size() + 1);
  for (const PlannedBlock& block : blocks) {
    const auto first = static_cast<std::size_t>(block.first_sample);
    const auto last = static_cast<std::size_t>(block.last_sample);
    if (first >= n || last >= n) continue;
    if (block.feed_mm_per_min <= 0.0) {  // a rapid
      series.step_x.push_back(series.x[first]);
      series.step_feed.push_back(kNaN);
      continue;
    }
    series.step_x.insert(series.step_x.end(), {series.x[first], series.x[last]});
    series.step_feed.insert(series.step_feed.end(), {block.feed_mm_per_min, block.feed_mm_per_min});
  }
}

// Measured peaks inside the x range, in x order.
void add_measured_peaks(PlotSeries& series, const std::vector<std::pair<double, double>>& measured,
                        const Axis& x_axis) {
  std::vector<std::pair<double, double>> peaks;
  for (const auto& [px_value, f_value] : measured) {
    if (std::isfinite(px_value) && std::isfinite(f_value) && px_value >= x_axis.lo && px_value <= x_axis.hi) {
      peaks.emplace_back(px_value, f_value);
    }
  }
  std::sort(peaks.begin(), peaks.end());
  for (const auto& [px_value, f_value] : peaks) {
    series.peak_x.push_back(px_value);
    series.peak_force.push_back(f_value);
    series.force_low = std::min(series.force_low, f_value);
  }
}

// The three panels stacked over the shared x axis, each y axis covering its lines.
struct Panels {
  Panel engagement;
  Panel feed;
  Panel force;
};

Panels stacked_panels(const PlotSeries& series, const Axis& x_axis, double target_force_n,
                      const PlanPlotOptions& options) {
  const double panel_height = (options.height_px - kMarginTopPx - kMarginBottomPx - 2.0 * kPanelGapPx) / 3.0;
  const auto panel_at = [&](int row, const Axis& y_axis) {
    const double top = kMarginTopPx + row * (panel_height + kPanelGapPx);
    return Panel{kMarginLeftPx, options.width_px - kMarginRightPx, top, top + panel_height, x_axis, y_axis};
  };
  const double engagement_high = std::max(largest(series.engagement_deg), 1.0);
  const double feed_high = std::max({largest(series.step_feed), largest(series.predicted_feed), 1.0});
  double force_high = std::max({largest(series.force_n), largest(series.peak_force), target_force_n, 1.0});
  force_high += 0.06 * (force_high - series.force_low);  // headroom: the highest peak stays off the frame
  return {panel_at(0, nice_axis(0.0, engagement_high * 1.05, 6, true)),
          panel_at(1, nice_axis(0.0, feed_high * 1.05, 6, true)),
          panel_at(2, nice_axis(series.force_low, force_high, 6, true))};
}

// The XML declaration, the <svg> element, the title and a white background.
void append_page(std::string& svg, const PlanPlotOptions& options) {
  const std::string title = options.title.empty() ? "Feed plan" : options.title;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(options.width_px) + "\" height=\"" +
         px(options.height_px) + "\" viewBox=\"0 0 " + px(options.width_px) + " " + px(options.height_px) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + xml_text(title) + "</title>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(0.5 * options.width_px) + "\" y=\"30\" text-anchor=\"middle\" font-size=\"16\">" +
         xml_text(title) + "</text>\n";
}

// Panel 1: the engagement angle.
void append_engagement_panel(std::string& svg, const Panel& panel, const PlotSeries& series,
                             const std::string& x_label, bool has_data) {
  svg += "<g id=\"panel-engagement\">\n";
  svg::append_panel_axes(svg, panel, "engagement α_en [deg]", false, x_label);
  append_series(svg, panel, series.x, series.engagement_deg, "engagement", kEngagementStyle);
  append_legend(svg, panel, {{"engagement angle", kEngagementStyle}});
  if (!has_data) svg::append_no_data(svg, panel);
  svg += "</g>\n";
}

// Panel 2: the feed — limit, programmed F and predicted feed.
void append_feed_panel(std::string& svg, const Panel& panel, const PlotSeries& series, const std::string& x_label,
                       bool has_data) {
  svg += "<g id=\"panel-feed\">\n";
  svg::append_panel_axes(svg, panel, "feed [mm/min]", false, x_label);
  append_series(svg, panel, series.x, series.feed_limit, "feed-limit", kFeedLimitStyle);
  append_series(svg, panel, series.step_x, series.step_feed, "block-feed", kBlockFeedStyle);
  append_series(svg, panel, series.x, series.predicted_feed, "predicted-feed", kPredictedFeedStyle);
  append_legend(svg, panel,
                {{"programmed F (blocks)", kBlockFeedStyle},
                 {"predicted feed", kPredictedFeedStyle},
                 {"feed limit", kFeedLimitStyle}});
  if (!has_data) svg::append_no_data(svg, panel);
  svg += "</g>\n";
}

// The target as a dashed line across the force panel, labelled at its left end.
void append_target(std::string& svg, const Panel& panel, double target_force_n, const std::string& target_label) {
  const std::string target_y = px(panel.to_y(target_force_n));
  svg += "<line class=\"target\" x1=\"" + px(panel.left_px) + "\" y1=\"" + target_y + "\" x2=\"" +
         px(panel.right_px) + "\" y2=\"" + target_y + "\" " + kTargetStyle + "/>\n";
  svg += "<text x=\"" + px(panel.left_px + 6) + "\" y=\"" + px(panel.to_y(target_force_n) - 5) +
         "\" fill=\"#2ca02c\">" + xml_text(target_label) + "</text>\n";
}

// Markers at the decimated peaks: every highest and lowest one per pixel column is drawn.
void append_measured_peaks(std::string& svg, const Panel& panel, const PlotSeries& series) {
  svg += "<g class=\"measured-peaks\" fill=\"";
  svg += kPeakColor;
  svg += "\">\n";
  for (const std::vector<std::size_t>& run : decimate(series.peak_x, series.peak_force, panel)) {
    for (const std::size_t k : run) {
      svg += "<circle cx=\"" + px(panel.to_x(series.peak_x[k])) + "\" cy=\"" + px(panel.to_y(series.peak_force[k])) +
             "\" r=\"2.5\"/>\n";
    }
  }
  svg += "</g>\n";
}

// Panel 3: the predicted force, the target and, when given, the measured peaks.
void append_force_panel(std::string& svg, const Panel& panel, const PlotSeries& series, double target_force_n,
                        const PlanPlotOptions& options, const std::string& x_label, bool has_data) {
  const std::string target_label = "target " + shortest_number_text(target_force_n) + " N";
  svg += "<g id=\"panel-force\">\n";
  svg::append_panel_axes(svg, panel, "force F [N]", true, x_label);
  append_series(svg, panel, series.x, series.force_n, "predicted-force", kForceStyle);
  append_target(svg, panel, target_force_n, target_label);
  std::vector<LegendEntry> force_legend{{"predicted force", kForceStyle}, {target_label, kTargetStyle}};
  if (options.measured_peaks) {
    append_measured_peaks(svg, panel, series);
    force_legend.push_back({"measured peaks", ""});
  }
  append_legend(svg, panel, force_legend);
  if (!has_data) svg::append_no_data(svg, panel);
  svg += "</g>\n";
}

}  // namespace

std::string plan_plot_svg(const PlanResult& result, double target_force_n, const PlanPlotOptions& options) {
  assert(options.width_px >= 400.0 && options.height_px >= 400.0);
  assert(std::isfinite(target_force_n));
  PlotSeries series = sample_series(result.samples, options.x_is_time);
  add_programmed_feed(series, result.blocks);
  const bool has_data = !result.samples.empty();
  const Axis x_axis = nice_axis(has_data ? series.x.front() : 0.0, has_data ? series.x.back() : 1.0, 10, false);
  if (options.measured_peaks) add_measured_peaks(series, *options.measured_peaks, x_axis);
  const Panels panels = stacked_panels(series, x_axis, target_force_n, options);
  for (double& limit : series.feed_limit) limit = std::min(limit, panels.feed.y.hi);  // NaN stays NaN
  const std::string x_label = options.x_is_time ? "time t [s]" : "path length s [mm]";

  std::string svg;
  svg.reserve(256 * 1024);
  append_page(svg, options);
  append_engagement_panel(svg, panels.engagement, series, x_label, has_data);
  append_feed_panel(svg, panels.feed, series, x_label, has_data);
  append_force_panel(svg, panels.force, series, target_force_n, options, x_label, has_data);
  svg += "</svg>\n";
  return svg;
}

std::string write_plan_plot(const std::filesystem::path& path, const PlanResult& result, double target_force_n,
                            const PlanPlotOptions& options) {
  return write_file_atomically(path, plan_plot_svg(result, target_force_n, options));
}

}  // namespace feedplan::planner
