#include "feedplan/trial/comparison_plot.hpp"

#include <algorithm>
#include <cassert>
#include <cstdio>

#include "feedplan/core/number_text.hpp"
#include "feedplan/core/svg_axis.hpp"
#include "feedplan/core/svg_series.hpp"

namespace feedplan::trial {

namespace {

constexpr double kMarginLeftPx = 90.0, kMarginRightPx = 30.0, kMarginTopPx = 50.0, kMarginBottomPx = 56.0;
constexpr double kPanelTitlePx = 24.0;  // the row's name above its panel
constexpr const char* kPeakStyle = "stroke=\"#1f77b4\" stroke-width=\"1.2\"";
constexpr const char* kTargetStyle = "stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"8 4\"";

using svg::px;

// The row's name and its figures, above its panel.
std::string panel_title(const StrategyRow& row) {
  const ControlJudgement& j = row.judgement;
  char figures[160];
  std::snprintf(figures, sizeof figures, " — largest peak %.0f N (%+.1f %%), RMS %.1f %%, %.0f %% within ±5 %%, %.2f s",
                j.max_peak_n, j.max_overshoot_percent, j.rms_error_percent, 100.0 * j.within_5_percent_share,
                j.cycle_time_s);
  std::string title = row.name;
  title += figures;
  return title;
}

void append_panel(std::string& svg, const svg::PlotArea& area, const StrategyRow& row, std::size_t index,
                  double target_force_n, bool last) {
  svg += "<g id=\"panel-" + std::to_string(index) + "\" class=\"row-" + std::string(to_string(row.kind)) + "\">\n";
  svg += "<text x=\"" + px(area.left_px) + "\" y=\"" + px(area.top_px - 7.0) + "\" font-size=\"13\">" +
         svg::xml_text(panel_title(row)) + "</text>\n";
  svg::append_panel_axes(svg, area, "force [N]", last, last ? "time t [s]" : "");
  std::vector<double> t_s, peak_n;
  t_s.reserve(row.revolutions.size());
  peak_n.reserve(row.revolutions.size());
  for (const force_log::RevolutionPeak& rev : row.revolutions) {
    t_s.push_back(0.5 * (rev.t_start_s + rev.t_end_s));
    peak_n.push_back(rev.peak_xy_n);
  }
  svg::append_series(svg, area, t_s, peak_n, "true-peak", kPeakStyle);
  const std::string y = px(area.to_y(target_force_n));
  svg += "<line class=\"target\" x1=\"" + px(area.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(area.right_px) +
         "\" y2=\"" + y + "\" " + kTargetStyle + "/>\n";
  if (index == 0) {
    std::string target_label = "target ";
    target_label += shortest_number_text(target_force_n);
    target_label += " N";
    svg::append_legend(svg, area, {{"true per-revolution peak |F_xy|", kPeakStyle}, {target_label, kTargetStyle}});
  }
  if (t_s.empty()) svg::append_no_data(svg, area);
  svg += "</g>\n";
}

}  // namespace

std::string comparison_plot_svg(const StrategyComparison& comparison, const ComparisonPlotOptions& options) {
  assert(options.width_px >= 400.0 && options.panel_height_px >= 60.0 && comparison.target_force_n > 0.0);
  double t_end_s = 0.0, force_hi_n = comparison.target_force_n;
  for (const StrategyRow& row : comparison.rows) {
    for (const force_log::RevolutionPeak& rev : row.revolutions) {
      t_end_s = std::max(t_end_s, rev.t_end_s);
      force_hi_n = std::max(force_hi_n, rev.peak_xy_n);
    }
  }
  const svg::Axis x = svg::nice_axis(0.0, t_end_s > 0.0 ? t_end_s : 1.0, 12, false);
  const svg::Axis y = svg::nice_axis(0.0, 1.1 * force_hi_n, 4, true);
  const double rows = static_cast<double>(comparison.rows.size());
  const double height_px = kMarginTopPx + rows * (kPanelTitlePx + options.panel_height_px) + kMarginBottomPx;
  const double left = kMarginLeftPx, right = options.width_px - kMarginRightPx;

  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(options.width_px) + "\" height=\"" + px(height_px) +
         "\" viewBox=\"0 0 " + px(options.width_px) + " " + px(height_px) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + svg::xml_text(options.title) + "</title>\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(0.5 * options.width_px) + "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" +
         svg::xml_text(options.title) + "</text>\n";
  double top = kMarginTopPx;
  for (std::size_t k = 0; k < comparison.rows.size(); ++k) {
    top += kPanelTitlePx;
    const svg::PlotArea area{left, right, top, top + options.panel_height_px, x, y};
    append_panel(svg, area, comparison.rows[k], k, comparison.target_force_n, k + 1 == comparison.rows.size());
    top += options.panel_height_px;
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace feedplan::trial
