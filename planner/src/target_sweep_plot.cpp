#include "feedplan/planner/target_sweep_plot.hpp"

#include <algorithm>
#include <cassert>

#include "feedplan/core/svg_axis.hpp"

namespace feedplan::planner {
namespace {

constexpr double kWidthPx = 900.0;
constexpr double kHeightPx = 700.0;
constexpr double kLeftPx = 80.0, kRightPx = 30.0, kTopPx = 60.0, kBottomPx = 60.0, kGapPx = 50.0;

using svg::px;

//! The smallest target met everywhere that the not-met plans report, or 0.
double floor_target_n(const std::vector<TargetSweepRow>& rows) {
  double floor = 0.0;
  for (const TargetSweepRow& r : rows) {
    if (r.status == PlanStatus::kTargetNotMet) floor = std::max(floor, r.target_needed_n);
  }
  return floor;
}

//! One panel: the series `value` over the targets, titled `y_title`; with `diagonal`, the line value = target.
void append_panel(std::string& svg, const std::vector<TargetSweepRow>& rows, double (*value)(const TargetSweepRow&),
                  const std::string& id, const std::string& series_class, const std::string& y_title, double top_px,
                  double bottom_px, bool x_labels, bool diagonal) {
  double x_lo = rows.front().target_n, x_hi = rows.back().target_n;
  const double floor_n = floor_target_n(rows);
  if (floor_n > 0.0) x_hi = std::max(x_hi, floor_n);
  double y_lo = 0.0, y_hi = 0.0;
  for (const TargetSweepRow& r : rows) y_hi = std::max(y_hi, value(r));
  if (diagonal) y_hi = std::max(y_hi, x_hi);
  svg::PlotArea area{kLeftPx, kWidthPx - kRightPx, top_px, bottom_px, svg::nice_axis(x_lo, x_hi, 10, true),
                     svg::nice_axis(y_lo, y_hi, 6, true)};
  svg += "<g id=\"" + id + "\">\n";
  svg::AxesStyle style;
  style.x_labels = x_labels;
  style.x_title = "target force [N]";
  style.x_title_y_px = bottom_px + 44;
  style.y_title = y_title;
  style.y_title_x_px = 22;
  style.y_title_centre_with_comma = true;
  svg::append_axes(svg, area, style);
  if (diagonal) {
    svg += "<line class=\"target\" x1=\"" + px(area.to_x(area.x.lo)) + "\" y1=\"" + px(area.to_y(area.x.lo)) + "\" x2=\"" +
           px(area.to_x(std::min(area.x.hi, area.y.hi))) + "\" y2=\"" + px(area.to_y(std::min(area.x.hi, area.y.hi))) +
           "\" stroke=\"#888\" stroke-dasharray=\"6,4\"/>\n";
  }
  if (floor_n > 0.0) {
    svg += "<line class=\"floor\" x1=\"" + px(area.to_x(floor_n)) + "\" y1=\"" + px(top_px) + "\" x2=\"" +
           px(area.to_x(floor_n)) + "\" y2=\"" + px(bottom_px) + "\" stroke=\"#c62828\" stroke-dasharray=\"4,4\"/>\n";
  }
  svg += "<polyline class=\"" + series_class + "\" fill=\"none\" stroke=\"#1565c0\" stroke-width=\"1.5\" points=\"";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i > 0) svg += ' ';
    svg += px(area.to_x(rows[i].target_n));
    svg += ',';
    svg += px(area.to_y(value(rows[i])));
  }
  svg += "\"/>\n";
  for (const TargetSweepRow& r : rows) {
    const bool met = r.status != PlanStatus::kTargetNotMet;
    svg += "<circle class=\"" + std::string(met ? "planned" : "not-met") + "\" cx=\"" + px(area.to_x(r.target_n)) +
           "\" cy=\"" + px(area.to_y(value(r))) + "\" r=\"3.5\" " +
           (met ? "fill=\"#1565c0\"" : "fill=\"white\" stroke=\"#c62828\" stroke-width=\"1.5\"") + "/>\n";
  }
  svg += "</g>\n";
}

}  // namespace

std::string target_sweep_svg(const std::vector<TargetSweepRow>& rows, const std::string& title) {
  assert(!rows.empty());
  std::string svg;
  const std::string width = svg::fixed_text(kWidthPx, 0), height = svg::fixed_text(kHeightPx, 0);
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + width + "\" height=\"" + height + "\" viewBox=\"0 0 " +
         width + " " + height + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + svg::xml_text(title) + "</title>\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + width + "\" height=\"" + height + "\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(kWidthPx / 2) + "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" + svg::xml_text(title) +
         "</text>\n";
  const double panel_px = (kHeightPx - kTopPx - kBottomPx - kGapPx) / 2;
  append_panel(svg, rows, [](const TargetSweepRow& r) { return r.cycle_time_s; }, "panel-time", "cycle-time",
               "cycle time [s]", kTopPx, kTopPx + panel_px, false, false);
  append_panel(svg, rows, [](const TargetSweepRow& r) { return r.max_predicted_force_n; }, "panel-peak", "max-peak",
               "largest predicted peak [N]", kTopPx + panel_px + kGapPx, kHeightPx - kBottomPx, true, true);
  svg += "</svg>\n";
  return svg;
}

}  // namespace feedplan::planner
