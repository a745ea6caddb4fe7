#include "feedplan/sim/force_plot.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/svg_axis.hpp"

namespace feedplan::sim {

namespace {

// Layout of the plot area inside the SVG, px.
constexpr double kMarginLeft_px = 80.0;
constexpr double kMarginRight_px = 30.0;
constexpr double kMarginTop_px = 50.0;
constexpr double kMarginBottom_px = 60.0;
constexpr std::size_t kMaxPeakCircles = 500;

std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

using svg::fixed_text;
using svg::px;

// "x,y" of a data point, px.
std::string point(const svg::PlotArea& area, double t_s, double f_n) {
  return px(area.to_x(t_s)) + "," + px(area.to_y(f_n));
}

// The force range of the data: from 0 (or the smallest value) to the largest value, peak or target.
struct ForceRange {
  double min_n = 0.0;
  double max_n = 0.0;
};

ForceRange force_range(const ForcePlotData& data) {
  double f_min = 0.0, f_max = -std::numeric_limits<double>::infinity();
  for (const auto& s : data.series) {
    for (const double v : s.values_n) {
      if (!std::isfinite(v)) continue;
      f_min = std::min(f_min, v);
      f_max = std::max(f_max, v);
    }
  }
  for (const auto& p : data.peaks) f_max = std::max(f_max, p.peak_xy_n);
  if (data.target_force_n) f_max = std::max(f_max, *data.target_force_n);
  if (!std::isfinite(f_max) || f_max <= f_min) f_max = f_min + 1.0;
  return {f_min, f_max};
}

// The force axis: about 6 intervals, whole steps from below the range to above it with headroom.
svg::Axis force_axis(const ForceRange& range) {
  const double headroom_n = 0.05 * (range.max_n - range.min_n);  // keeps the highest peak off the frame
  const double y_step = svg::tick_step(range.max_n + headroom_n - range.min_n, 6);
  const double f0 = std::floor(range.min_n / y_step) * y_step;
  const double f1 = std::ceil((range.max_n + headroom_n) / y_step) * y_step;
  const double top = f1 > f0 ? f1 : f0 + y_step;
  return {f0, top, y_step, svg::decimals_for(y_step), std::llround(f0 / y_step), std::llround(top / y_step)};
}

// The time axis: the samples' span (0 to 1 s without samples), about 8 intervals.
svg::Axis time_axis(const std::vector<double>& t_s) {
  double t0 = 0.0, t1 = 1.0;
  if (!t_s.empty()) {
    t0 = t_s.front();
    t1 = t_s.back() > t0 ? t_s.back() : t0 + 1.0;
  }
  const double x_step = svg::tick_step(t1 - t0, 8);
  return svg::axis_within(t0, t1, x_step, svg::decimals_for(x_step));
}

// The plot area inside the margins, with time along x and force along y.
svg::PlotArea plot_area(const ForcePlotData& data) {
  return {kMarginLeft_px, data.width_px - kMarginRight_px, kMarginTop_px, data.height_px - kMarginBottom_px,
          time_axis(data.t_s), force_axis(force_range(data))};
}

// The XML declaration, the <svg> element, the title and a white background.
void append_page(std::string& svg, const ForcePlotData& data) {
  const std::string width = fixed_text(data.width_px, 0);
  const std::string height = fixed_text(data.height_px, 0);
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + width + "\" height=\"" + height +
         "\" viewBox=\"0 0 " + width + " " + height + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + escape(data.title) + "</title>\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + width + "\" height=\"" + height + "\" fill=\"white\"/>\n";
  svg += "<text x=\"" + px(data.width_px / 2) + "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" +
         escape(data.title) + "</text>\n";
}

// Grid, ticks, tick labels, the frame and the axis titles.
void append_axes(std::string& svg, const svg::PlotArea& area, double height_px) {
  svg::AxesStyle style;
  style.x_title = "time t [s]";
  style.x_title_y_px = height_px - 16;
  style.y_title = "force F [N]";
  style.y_title_x_px = 22;
  style.y_title_centre_with_comma = true;
  svg::append_axes(svg, area, style);
}

// The points `kept` of `t` and `f`, closing a polyline's points attribute.
void append_points(std::string& svg, const svg::PlotArea& area, const std::vector<double>& t,
                     const std::vector<double>& f, const std::vector<std::size_t>& kept) {
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (k > 0) svg += ' ';
    svg += point(area, t[kept[k]], f[kept[k]]);
  }
  svg += "\"/>\n";
}

// One polyline per series with points. Returns whether any series had one.
bool append_series(std::string& svg, const ForcePlotData& data, const svg::PlotArea& area, std::size_t columns) {
  bool any_point = false;
  for (const auto& s : data.series) {
    const std::vector<std::size_t> kept = min_max_decimation(data.t_s, s.values_n, columns);
    if (kept.empty()) continue;
    any_point = true;
    svg += "<polyline fill=\"none\" stroke=\"" + escape(s.color) + "\" stroke-width=\"1\" points=\"";
    append_points(svg, area, data.t_s, s.values_n, kept);
  }
  return any_point;
}

// Per-revolution peaks: circles, or a decimated line when there are too many.
void append_peaks(std::string& svg, const std::vector<force_log::RevolutionPeak>& peaks, const svg::PlotArea& area,
                  std::size_t columns) {
  if (peaks.empty()) return;
  const std::string color = "#d62728";
  if (peaks.size() <= kMaxPeakCircles) {
    svg += "<g fill=\"" + color + "\">\n";
    for (const auto& p : peaks) {
      svg += "<circle cx=\"" + px(area.to_x(p.t_peak_s)) + "\" cy=\"" + px(area.to_y(p.peak_xy_n)) + "\" r=\"3\"/>\n";
    }
    svg += "</g>\n";
    return;
  }
  std::vector<double> t, f;
  for (const auto& p : peaks) {
    t.push_back(p.t_peak_s);
    f.push_back(p.peak_xy_n);
  }
  svg += "<polyline fill=\"none\" stroke=\"" + color + "\" stroke-width=\"1.5\" points=\"";
  append_points(svg, area, t, f, min_max_decimation(t, f, columns));
}

// The target: a dashed line with its value.
void append_target(std::string& svg, const svg::PlotArea& area, double target_force_n) {
  const double y = area.to_y(target_force_n);
  svg += "<line x1=\"" + px(area.left_px) + "\" y1=\"" + px(y) + "\" x2=\"" + px(area.right_px) + "\" y2=\"" + px(y) +
         "\" stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/>\n";
  svg += "<text x=\"" + px(area.right_px - 4) + "\" y=\"" + px(y - 5) +
         "\" text-anchor=\"end\" fill=\"#2ca02c\">target " + escape(fixed_text(target_force_n, 0)) + " N</text>\n";
}

// Legend, on a white box so that lines under it do not hide it.
void append_legend(std::string& svg, const ForcePlotData& data, const svg::PlotArea& area) {
  std::size_t legend_width_chars = 0;
  for (const auto& s : data.series) legend_width_chars = std::max(legend_width_chars, s.label.size());
  if (!data.peaks.empty()) legend_width_chars = std::max<std::size_t>(legend_width_chars, 19);
  const std::size_t entries = data.series.size() + (data.peaks.empty() ? 0 : 1);
  if (entries > 0) {
    svg += "<rect x=\"" + px(area.left_px + 4) + "\" y=\"" + px(area.top_px + 4) + "\" width=\"" +
           px(44.0 + 7.0 * static_cast<double>(legend_width_chars)) + "\" height=\"" +
           px(16.0 * static_cast<double>(entries) + 6.0) +
           "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#cccccc\"/>\n";
  }
  double legend_y = area.top_px + 20;
  auto legend_entry = [&](const std::string& color, const std::string& label) {
    svg += "<line x1=\"" + px(area.left_px + 10) + "\" y1=\"" + px(legend_y - 4) + "\" x2=\"" +
           px(area.left_px + 34) + "\" y2=\"" + px(legend_y - 4) + "\" stroke=\"" + escape(color) +
           "\" stroke-width=\"2\"/>\n";
    svg += "<text x=\"" + px(area.left_px + 40) + "\" y=\"" + px(legend_y) + "\">" + escape(label) + "</text>\n";
    legend_y += 16;
  };
  for (const auto& s : data.series) legend_entry(s.color, s.label);
  if (!data.peaks.empty()) legend_entry("#d62728", "peak per revolution");
}

}  // namespace

std::vector<std::size_t> min_max_decimation(const std::vector<double>& t_s, const std::vector<double>& values,
                                            std::size_t columns) {
  assert(t_s.size() == values.size());
  assert(columns >= 1);
  std::vector<std::size_t> kept;
  const std::size_t finite = static_cast<std::size_t>(
      std::count_if(values.begin(), values.end(), [](double v) { return std::isfinite(v); }));
  if (finite <= 4 * columns) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (std::isfinite(values[i])) kept.push_back(i);
    }
    return kept;
  }
  const double t0 = t_s.front();
  const double span = t_s.back() - t_s.front();
  auto column_of = [&](std::size_t i) {
    if (!(span > 0.0)) return std::size_t{0};
    const double c = std::floor((t_s[i] - t0) / span * static_cast<double>(columns));
    return std::min(columns - 1, static_cast<std::size_t>(std::max(0.0, c)));
  };
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::size_t current = kNone, first = 0, last = 0, low = 0, high = 0;
  auto flush = [&]() {
    if (current == kNone) return;
    std::array<std::size_t, 4> picks = {first, low, high, last};
    std::sort(picks.begin(), picks.end());
    for (std::size_t k = 0; k < picks.size(); ++k) {
      if (k == 0 || picks[k] != picks[k - 1]) kept.push_back(picks[k]);
    }
  };
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) continue;
    const std::size_t c = column_of(i);
    if (c != current) {
      flush();
      current = c;
      first = last = low = high = i;
      continue;
    }
    last = i;
    if (values[i] < values[low]) low = i;
    if (values[i] > values[high]) high = i;
  }
  flush();
  return kept;
}

std::string force_plot_svg(const ForcePlotData& data) {
  assert(data.width_px >= 200.0 && data.height_px >= 150.0);
  assert(data.max_points_per_series >= 4);
  assert(std::all_of(data.series.begin(), data.series.end(),
                     [&](const ForcePlotSeries& s) { return s.values_n.size() == data.t_s.size(); }));
  const svg::PlotArea area = plot_area(data);
  const std::size_t columns = std::max<std::size_t>(1, std::min(data.max_points_per_series / 4, area.columns()));

  std::string svg;
  append_page(svg, data);
  append_axes(svg, area, data.height_px);
  const bool any_point = append_series(svg, data, area, columns);
  append_peaks(svg, data.peaks, area, columns);
  if (data.target_force_n) append_target(svg, area, *data.target_force_n);
  append_legend(svg, data, area);
  if (!any_point && data.peaks.empty()) svg::append_no_data(svg, area);
  svg += "</svg>\n";
  return svg;
}

std::string write_force_plot(const std::string& path, const ForcePlotData& data) {
  return write_file_atomically(path, force_plot_svg(data));
}

ForcePlotData force_plot_data(const force_log::ForceLog& log, const std::string& title, std::vector<force_log::RevolutionPeak> peaks,
                              std::optional<double> target_force_n) {
  ForcePlotData data;
  data.title = title;
  data.peaks = std::move(peaks);
  data.target_force_n = target_force_n;
  ForcePlotSeries resultant;
  resultant.label = "|F_xy|";
  for (const auto& row : log.rows) {
    data.t_s.push_back(row.t_s);
    resultant.values_n.push_back(log.has_forces ? std::hypot(row.fx_n, row.fy_n)
                                                : std::numeric_limits<double>::quiet_NaN());
  }
  data.series.push_back(std::move(resultant));
  return data;
}

}  // namespace feedplan::sim
