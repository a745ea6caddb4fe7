#pragma once
// Series of the SVG plots (planner/plan_plot.hpp, planner/path_history_plot.hpp): long series reduced by
// min/max decimation per pixel column, and drawn as one <path> each. Header-only, standard library only.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/core/svg_axis.hpp"

namespace feedplan::svg {

// Min/max decimation per pixel column, with gaps. The points (x[i], y[i]) with finite values form runs
// separated by non-finite ones; in each run and pixel column the first, the lowest, the highest and the
// last point are kept (each once, in order), so the line looks as at full resolution and every extreme
// keeps its exact value. Returns the kept indices of each run.
inline std::vector<std::vector<std::size_t>> decimate(const std::vector<double>& x, const std::vector<double>& y,
                                               const PlotArea& panel) {
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
inline void append_series(std::string& svg, const PlotArea& panel, const std::vector<double>& x, const std::vector<double>& y,
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

// Grid, ticks, labels and frame of one panel of a stack of panels over a shared x axis; the x tick labels and title only when `x_labels`.
inline void append_panel_axes(std::string& svg, const PlotArea& panel, const std::string& y_label, bool x_labels,
                        const std::string& x_label) {
  svg::AxesStyle style;
  style.x_ticks.css_class = "x-tick";
  style.y_ticks.css_class = "y-tick";
  style.y_ticks.centred_on_tick = true;
  style.x_labels = x_labels;
  style.y_ticks_first = true;
  style.x_title = xml_text(x_label);
  style.x_title_y_px = panel.bottom_px + 40;
  style.y_title = xml_text(y_label);
  style.y_title_x_px = 24;
  style.titles_in_label_group = true;
  append_axes(svg, panel, style);
}

// Height of one legend row, px.
inline constexpr double kLegendRowPx = 16.0;

// A legend entry: a short line in the series' style (or a marker) and its label.
struct LegendEntry {
  std::string label;
  std::string style;   // stroke attributes of the line; empty: a marker in `marker_color`
  std::string marker_color = "#d62728";
};

// The legend in the panel's top right corner, on a white box so that lines under it do not hide it.
inline void append_legend(std::string& svg, const PlotArea& panel, const std::vector<LegendEntry>& entries) {
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
      svg += "<circle cx=\"" + px(left + 20) + "\" cy=\"" + px(y) + "\" r=\"3\" fill=\"" + entry.marker_color + "\"/>\n";
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

}  // namespace feedplan::svg
