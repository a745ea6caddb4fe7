#include "feedplan/trial/control_plot.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/svg_axis.hpp"
#include "feedplan/core/svg_series.hpp"

namespace feedplan::trial {

namespace {

constexpr double kMarginLeftPx = 90.0, kMarginRightPx = 30.0, kMarginTopPx = 56.0, kMarginBottomPx = 64.0;
constexpr double kPanelGapPx = 30.0;
constexpr const char* kTrueStyle = "stroke=\"#1f77b4\" stroke-width=\"1.2\"";
constexpr const char* kSensedStyle = "stroke=\"#ff7f0e\" stroke-width=\"1.2\"";
constexpr const char* kTargetStyle = "stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"";
constexpr const char* kCommandedStyle = "stroke=\"#d62728\" stroke-width=\"1.2\"";
constexpr const char* kAppliedStyle = "stroke=\"#333333\" stroke-width=\"1.2\"";

using svg::px;

// A series as (time, value) pairs.
struct Series {
  std::vector<double> t_s, values;
  void add(double t, double v) {
    t_s.push_back(t);
    values.push_back(v);
  }
  double largest(double start) const {
    for (const double v : values) start = std::max(start, v);
    return start;
  }
};

// Every series of the plot.
struct ControlSeries {
  Series true_peak, sensed, commanded, applied;
  double t_end_s = 0.0;
};

// A held value drawn as steps: the value from each time until the next.
void add_step(Series& series, double t_s, double value) {
  if (!series.values.empty()) series.add(t_s, series.values.back());
  series.add(t_s, value);
}

ControlSeries series_of(const ControlTrace& trace, const std::vector<force_log::RevolutionPeak>& revolutions) {
  ControlSeries out;
  for (const force_log::RevolutionPeak& rev : revolutions) {
    out.true_peak.add(0.5 * (rev.t_start_s + rev.t_end_s), rev.peak_xy_n);
    out.t_end_s = std::max(out.t_end_s, rev.t_end_s);
  }
  for (const SensedRevolution& rev : trace.revolutions) {
    out.sensed.add(rev.t_end_s, rev.force_n);
    out.t_end_s = std::max(out.t_end_s, rev.t_end_s);
  }
  for (const ControlStep& step : trace.steps) {
    add_step(out.commanded, step.t_s, 100.0 * step.commanded_ratio);
    out.applied.add(step.t_s, 100.0 * step.applied_ratio);
    out.t_end_s = std::max(out.t_end_s, step.t_s);
  }
  return out;
}

void append_force_panel(std::string& svg, const svg::PlotArea& area, const ControlSeries& s, double target_force_n,
                        const ControlPlotOptions& options) {
  svg += "<g id=\"panel-force\">\n";
  svg::append_panel_axes(svg, area, "force [N]", false, "");
  svg::append_series(svg, area, s.true_peak.t_s, s.true_peak.values, "true-peak", kTrueStyle);
  svg::append_series(svg, area, s.sensed.t_s, s.sensed.values, "sensed", kSensedStyle);
  const std::string y = px(area.to_y(target_force_n));
  svg += "<line class=\"target\" x1=\"" + px(area.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(area.right_px) +
         "\" y2=\"" + y + "\" " + kTargetStyle + "/>\n";
  std::string target_label = "target ";
  target_label += shortest_number_text(target_force_n);
  target_label += " N";
  svg::append_legend(svg, area, {{"true per-revolution peak |F_xy|", kTrueStyle}, {options.sensed_label, kSensedStyle},
                                 {target_label, kTargetStyle}});
  if (s.true_peak.values.empty() && s.sensed.values.empty()) svg::append_no_data(svg, area);
  svg += "</g>\n";
}

void append_override_panel(std::string& svg, const svg::PlotArea& area, const ControlSeries& s) {
  svg += "<g id=\"panel-override\">\n";
  svg::append_panel_axes(svg, area, "feed override [%]", true, "time t [s]");
  svg::append_series(svg, area, s.applied.t_s, s.applied.values, "applied", kAppliedStyle);
  svg::append_series(svg, area, s.commanded.t_s, s.commanded.values, "commanded", kCommandedStyle);
  svg::append_legend(svg, area, {{"commanded", kCommandedStyle}, {"applied by the machine", kAppliedStyle}});
  if (s.commanded.values.empty()) svg::append_no_data(svg, area);
  svg += "</g>\n";
}

}  // namespace

std::string control_plot_svg(const ControlTrace& trace, const std::vector<force_log::RevolutionPeak>& revolutions,
                             double target_force_n, const ControlPlotOptions& options) {
  assert(options.width_px >= 400.0 && options.height_px >= 400.0 && target_force_n > 0.0);
  const ControlSeries s = series_of(trace, revolutions);
  const double force_hi = s.sensed.largest(s.true_peak.largest(target_force_n));
  const double ratio_hi = s.applied.largest(s.commanded.largest(100.0));
  const double panel_px = (options.height_px - kMarginTopPx - kMarginBottomPx - kPanelGapPx) / 2.0;
  const double left = kMarginLeftPx, right = options.width_px - kMarginRightPx;
  const svg::Axis x = svg::nice_axis(0.0, s.t_end_s > 0.0 ? s.t_end_s : 1.0, 12, false);
  const svg::PlotArea force_area{left, right, kMarginTopPx, kMarginTopPx + panel_px, x,
                                 svg::nice_axis(0.0, 1.1 * force_hi, 8, true)};
  const svg::PlotArea override_area{left, right, kMarginTopPx + panel_px + kPanelGapPx,
                                    options.height_px - kMarginBottomPx, x, svg::nice_axis(0.0, 1.1 * ratio_hi, 8, true)};
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(options.width_px) + "\" height=\"" +
         px(options.height_px) + "\" viewBox=\"0 0 " + px(options.width_px) + " " + px(options.height_px) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + svg::xml_text(options.title) + "</title>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(0.5 * options.width_px) + "\" y=\"30\" text-anchor=\"middle\" font-size=\"16\">" +
         svg::xml_text(options.title) + "</text>\n";
  append_force_panel(svg, force_area, s, target_force_n, options);
  append_override_panel(svg, override_area, s);
  svg += "</svg>\n";
  return svg;
}

}  // namespace feedplan::trial
