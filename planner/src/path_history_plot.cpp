#include "feedplan/planner/path_history_plot.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/svg_axis.hpp"
#include "feedplan/core/svg_series.hpp"

namespace feedplan::planner {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMarginLeftPx = 90.0, kMarginRightPx = 30.0, kMarginTopPx = 56.0, kMarginBottomPx = 64.0;
constexpr double kPanelGapPx = 30.0;
constexpr const char* kTargetStyle = "stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"";
constexpr const char* kNextStyle = "stroke=\"#000000\" stroke-width=\"1.2\" stroke-dasharray=\"5 3\"";

using svg::px;

// Stroke of cycle k of `count`: from light blue (oldest) to dark blue (newest), the newest a little wider.
std::string cycle_style(std::size_t k, std::size_t count) {
  const double f = count <= 1 ? 1.0 : static_cast<double>(k) / static_cast<double>(count - 1);
  const auto channel = [f](int light, int dark) { return static_cast<int>(std::lround(light + f * (dark - light))); };
  char colour[8];
  std::snprintf(colour, sizeof colour, "#%02x%02x%02x", channel(0x9e, 0x08), channel(0xca, 0x30), channel(0xe1, 0x6b));
  return std::string("stroke=\"") + colour + "\" stroke-width=\"" + (k + 1 == count ? "1.6" : "1") + "\"";
}

// Zeros (not measured, not engaged) as gaps.
std::vector<double> gaps_for_zero(const std::vector<double>& values) {
  std::vector<double> out(values);
  for (double& v : out) {
    if (!(v > 0.0)) v = kNaN;
  }
  return out;
}

double largest(const std::vector<double>& values, double start) {
  for (const double v : values) {
    if (std::isfinite(v)) start = std::max(start, v);
  }
  return start;
}

struct Series {
  std::vector<std::vector<double>> force, feed;  // per cycle
  std::vector<double> next_force, next_feed;     // empty without a next plan
};

Series series_of(const std::vector<PathHistoryCycle>& history, const PlanResult* next, std::size_t n) {
  Series out;
  // Feeds in the cut only (where the plan predicted a force): air moves and rapids would set the scale.
  for (const PathHistoryCycle& c : history) {
    out.force.push_back(gaps_for_zero(c.measured_n));
    std::vector<double> feed = gaps_for_zero(c.feed_mm_per_min);
    for (std::size_t i = 0; i < feed.size() && i < c.predicted_n.size(); ++i) {
      if (!(c.predicted_n[i] > 0.0)) feed[i] = kNaN;
    }
    out.feed.push_back(std::move(feed));
  }
  if (next && next->samples.size() == n) {
    for (const PlannedSample& p : next->samples) {
      const bool cutting = p.engaged && p.predicted_force_n > 0.0;
      out.next_force.push_back(cutting ? p.predicted_force_n : kNaN);
      out.next_feed.push_back(cutting && p.feed_mm_per_min > 0.0 ? p.feed_mm_per_min : kNaN);
    }
  }
  return out;
}

// One line per cycle (class "<what> cycle-K"), older ones lighter; their legend entries, with the cycle's
// planned time when `with_time`.
std::vector<svg::LegendEntry> append_cycles(std::string& svg, const svg::PlotArea& area, const std::vector<double>& s_mm,
                                            const std::vector<PathHistoryCycle>& history,
                                            const std::vector<std::vector<double>>& per_cycle, const std::string& what,
                                            bool with_time) {
  std::vector<svg::LegendEntry> legend;
  for (std::size_t k = 0; k < history.size(); ++k) {
    const std::string style = cycle_style(k, history.size());
    const std::string css = what + " cycle-" + std::to_string(history[k].cycle);
    svg::append_series(svg, area, s_mm, per_cycle[k], css.c_str(), style.c_str());
    std::string label = "cycle " + std::to_string(history[k].cycle);
    if (with_time) label += ": " + fixed_number_text(history[k].cycle_time_s, 1) + " s planned";
    legend.push_back({label, style});
  }
  return legend;
}

void append_force_panel(std::string& svg, const svg::PlotArea& area, const std::vector<double>& s_mm,
                        const std::vector<PathHistoryCycle>& history, const Series& series, double target_force_n) {
  svg += "<g id=\"panel-force\">\n";
  svg::append_panel_axes(svg, area, "measured peak force F [N]", false, "");
  std::vector<svg::LegendEntry> legend = append_cycles(svg, area, s_mm, history, series.force, "measured", true);
  if (!series.next_force.empty()) {
    svg::append_series(svg, area, s_mm, series.next_force, "next-force", kNextStyle);
    legend.push_back({"next plan, predicted", kNextStyle});
  }
  const std::string target_label = "target " + shortest_number_text(target_force_n) + " N";
  const std::string y = px(area.to_y(target_force_n));
  svg += "<line class=\"target\" x1=\"" + px(area.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(area.right_px) +
         "\" y2=\"" + y + "\" " + kTargetStyle + "/>\n";
  legend.push_back({target_label, kTargetStyle});
  svg::append_legend(svg, area, legend);
  if (history.empty()) svg::append_no_data(svg, area);
  svg += "</g>\n";
}

void append_feed_panel(std::string& svg, const svg::PlotArea& area, const std::vector<double>& s_mm,
                       const std::vector<PathHistoryCycle>& history, const Series& series, const PlanResult* next) {
  svg += "<g id=\"panel-feed\">\n";
  svg::append_panel_axes(svg, area, "feed in the cut [mm/min]", true, "path length s [mm]");
  std::vector<svg::LegendEntry> legend = append_cycles(svg, area, s_mm, history, series.feed, "feed", false);
  if (!series.next_feed.empty()) {
    svg::append_series(svg, area, s_mm, series.next_feed, "next-feed", kNextStyle);
    legend.push_back({"next plan: " + fixed_number_text(next->summary.cycle_time_s, 1) + " s", kNextStyle});
  }
  if (!legend.empty()) svg::append_legend(svg, area, legend);
  if (history.empty()) svg::append_no_data(svg, area);
  svg += "</g>\n";
}

}  // namespace

std::string path_history_svg(const std::vector<double>& s_mm, const std::vector<PathHistoryCycle>& history,
                             double target_force_n, const PathHistoryPlotOptions& options) {
  assert(options.width_px >= 400.0 && options.height_px >= 400.0);
  for (const PathHistoryCycle& c : history) {
    assert(c.measured_n.size() == s_mm.size() && c.feed_mm_per_min.size() == s_mm.size());
    (void)c;
  }
  const Series series = series_of(history, options.next, s_mm.size());
  double force_hi = std::isfinite(target_force_n) ? target_force_n : 0.0;
  double feed_hi = 0.0;
  for (std::size_t k = 0; k < history.size(); ++k) {
    force_hi = largest(series.force[k], force_hi);
    feed_hi = largest(series.feed[k], feed_hi);
  }
  force_hi = largest(series.next_force, force_hi);
  feed_hi = largest(series.next_feed, feed_hi);
  const double s_lo = s_mm.empty() ? 0.0 : s_mm.front(), s_hi = s_mm.empty() ? 1.0 : s_mm.back();
  const double panel_px = (options.height_px - kMarginTopPx - kMarginBottomPx - kPanelGapPx) / 2.0;
  const double left = kMarginLeftPx, right = options.width_px - kMarginRightPx;
  const svg::Axis x = svg::nice_axis(s_lo, s_hi, 12, false);
  const svg::PlotArea force_area{left, right, kMarginTopPx, kMarginTopPx + panel_px, x,
                                 svg::nice_axis(0.0, 1.1 * force_hi, 8, true)};
  const svg::PlotArea feed_area{left, right, kMarginTopPx + panel_px + kPanelGapPx, options.height_px - kMarginBottomPx,
                                x, svg::nice_axis(0.0, 1.1 * feed_hi, 8, true)};

  const std::string title = options.title.empty() ? "Learning along the path" : options.title;
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(options.width_px) + "\" height=\"" +
         px(options.height_px) + "\" viewBox=\"0 0 " + px(options.width_px) + " " + px(options.height_px) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + svg::xml_text(title) + "</title>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(0.5 * options.width_px) + "\" y=\"30\" text-anchor=\"middle\" font-size=\"16\">" +
         svg::xml_text(title) + "</text>\n";
  append_force_panel(svg, force_area, s_mm, history, series, target_force_n);
  append_feed_panel(svg, feed_area, s_mm, history, series, options.next);
  svg += "</svg>\n";
  return svg;
}

}  // namespace feedplan::planner
