#pragma once
// Axes of the SVG plots (sim/force_plot.hpp, planner/plan_plot.hpp, planner/target_sweep_plot.hpp), as
// text: an axis' range and its 1-2-5 ticks, the plot area that maps data onto pixels, the grid, tick labels,
// axis titles and frame drawn around it, and text made safe for XML. Header-only, standard library only.
//
// Coordinates are written with one decimal (0.1 px is below what any screen shows), tick labels with
// the decimals that show the step exactly, and a negative zero without its sign ("-0.0" is "0.0").
// The two plots differ in small details of their axes (tick-label classes, label baselines, where
// the titles go); AxesStyle holds those, so that each plot keeps its exact text.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>

namespace feedplan::svg {

//! `value` in fixed notation with `decimals` decimals ("12.5", "3"), locale-independent; a value
//! that rounds to zero is written without a minus sign.
inline std::string fixed_text(double value, int decimals) {
  std::array<char, 64> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, decimals);
  std::string text(buffer.data(), result.ptr);
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

//! A pixel coordinate: one decimal.
inline std::string px(double value) { return fixed_text(value, 1); }

//! Text content and attribute values in XML (titles, labels): the five characters with a meaning there, as
//! entities.
inline std::string xml_text(std::string_view text) {
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

//! An axis: the range drawn and ticks at whole multiples of a 1-2-5 step (1, 2 or 5 × 10^k) inside it.
struct Axis {
  double lo = 0.0;      //!< value at the start of the axis (left or bottom)
  double hi = 1.0;      //!< value at its end (right or top)
  double step = 0.2;    //!< distance between ticks
  int decimals = 1;     //!< decimals of the tick labels: they show the step exactly
  long long first = 0;  //!< ticks at n · step for n in [first, last]
  long long last = 5;

  //! The value of tick n.
  double tick(long long n) const { return static_cast<double>(n) * step; }
};

//! A 1-2-5 step giving about `count` intervals over `span`: the smallest one of at least span / count.
inline double tick_step(double span, int count) {
  const double raw = span / count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double residual = raw / magnitude;
  const double nice = residual <= 1.0 ? 1.0 : residual <= 2.0 ? 2.0 : residual <= 5.0 ? 5.0 : 10.0;
  return nice * magnitude;
}

//! Decimals that show a tick step exactly (0.05 → 2, 20 → 0).
inline int decimals_for(double step) { return std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9))); }

//! The axis [lo, hi] as it is, with ticks at the multiples of `step` that lie inside it.
inline Axis axis_within(double lo, double hi, double step, int decimals) {
  return {lo, hi, step, decimals, static_cast<long long>(std::ceil(lo / step - 1e-9)),
          static_cast<long long>(std::floor(hi / step + 1e-9))};
}

//! The smallest 1-2-5 step that covers [lo, hi] in at most `max_intervals` whole steps. With `rounded`, the
//! range widens to whole steps (value axes start and end at a tick); without, it stays [lo, hi] (a path
//! axis: no empty space after the last sample). An empty range is widened first.
inline Axis nice_axis(double lo, double hi, int max_intervals, bool rounded) {
  if (!(hi > lo)) hi = lo + (lo != 0.0 ? std::abs(lo) : 1.0);
  const int exponent = static_cast<int>(std::floor(std::log10((hi - lo) / max_intervals)));
  for (int k = exponent;; ++k) {
    for (const double mantissa : {1.0, 2.0, 5.0}) {
      const double step = mantissa * std::pow(10.0, k);
      const auto below = static_cast<long long>(std::floor(lo / step + 1e-9));
      const auto above = static_cast<long long>(std::ceil(hi / step - 1e-9));
      if (above - below > max_intervals) continue;
      if (!rounded) return axis_within(lo, hi, step, std::max(0, -k));
      return {static_cast<double>(below) * step, static_cast<double>(above) * step, step, std::max(0, -k), below,
              above};
    }
  }
}

//! A plot area: its rectangle on the page, px, and the axes mapped onto it.
struct PlotArea {
  double left_px, right_px, top_px, bottom_px;
  Axis x, y;

  double to_x(double value) const { return left_px + (value - x.lo) / (x.hi - x.lo) * (right_px - left_px); }
  double to_y(double value) const { return bottom_px - (value - y.lo) / (y.hi - y.lo) * (bottom_px - top_px); }
  //! Whole pixel columns across the area (at least 1), for decimation.
  std::size_t columns() const { return static_cast<std::size_t>(std::max(1.0, std::floor(right_px - left_px))); }
};

//! How the tick labels of one axis are written.
struct TickLabelStyle {
  std::string css_class;  //!< class attribute of every label; empty: none
  //! For y labels: placed at the tick's y with dominant-baseline="middle" (true), or with their
  //! baseline 4 px below it (false). No effect on x labels, which hang 16 px below the area.
  bool centred_on_tick = false;
};

//! What append_axes writes besides the grid and the frame, and the details in which plots differ.
struct AxesStyle {
  TickLabelStyle x_ticks;        //!< x tick labels
  TickLabelStyle y_ticks;        //!< y tick labels
  bool x_labels = true;          //!< write the x tick labels and the x title (false: a panel above another)
  bool y_ticks_first = false;    //!< y tick labels before the x tick labels
  std::string x_title;           //!< title under the x axis, XML text (escaped by the caller)
  double x_title_y_px = 0.0;     //!< baseline of the x title, px
  std::string y_title;           //!< title along the y axis, rotated by −90°, XML text
  double y_title_x_px = 22.0;    //!< centre of the y title, whole px
  //! The y title's centre of rotation as "22.0,y" (true) or "22 y" (false).
  bool y_title_centre_with_comma = false;
  //! The titles inside the labels' group, before the frame (true), or after the frame (false).
  bool titles_in_label_group = false;
};

//! The grid lines at every tick, light grey, as one group.
inline void append_grid(std::string& svg, const PlotArea& area) {
  svg += "<g stroke=\"#dddddd\" stroke-width=\"1\">\n";
  for (long long n = area.x.first; n <= area.x.last; ++n) {
    const std::string x = px(area.to_x(area.x.tick(n)));
    svg += "<line x1=\"" + x + "\" y1=\"" + px(area.top_px) + "\" x2=\"" + x + "\" y2=\"" + px(area.bottom_px) +
           "\"/>\n";
  }
  for (long long n = area.y.first; n <= area.y.last; ++n) {
    const std::string y = px(area.to_y(area.y.tick(n)));
    svg += "<line x1=\"" + px(area.left_px) + "\" y1=\"" + y + "\" x2=\"" + px(area.right_px) + "\" y2=\"" + y +
           "\"/>\n";
  }
  svg += "</g>\n";
}

//! ` class="…"`, or nothing for an empty class.
inline std::string class_attribute(const std::string& css_class) {
  return css_class.empty() ? std::string() : " class=\"" + css_class + "\"";
}

//! The x tick labels, centred under their ticks.
inline void append_x_tick_labels(std::string& svg, const PlotArea& area, const TickLabelStyle& style) {
  for (long long n = area.x.first; n <= area.x.last; ++n) {
    const double value = area.x.tick(n);
    svg += "<text" + class_attribute(style.css_class) + " x=\"" + px(area.to_x(value)) + "\" y=\"" +
           px(area.bottom_px + 16) + "\" text-anchor=\"middle\">" + fixed_text(value, area.x.decimals) + "</text>\n";
  }
}

//! The y tick labels, right-aligned left of the area.
inline void append_y_tick_labels(std::string& svg, const PlotArea& area, const TickLabelStyle& style) {
  for (long long n = area.y.first; n <= area.y.last; ++n) {
    const double value = area.y.tick(n);
    const double y = area.to_y(value);
    svg += "<text" + class_attribute(style.css_class) + " x=\"" + px(area.left_px - 6) + "\" y=\"" +
           px(style.centred_on_tick ? y : y + 4) + "\" text-anchor=\"end\"" +
           (style.centred_on_tick ? " dominant-baseline=\"middle\"" : "") + ">" +
           fixed_text(value, area.y.decimals) + "</text>\n";
  }
}

//! The x title (when x labels are on) and the y title.
inline void append_axis_titles(std::string& svg, const PlotArea& area, const AxesStyle& style) {
  if (style.x_labels) {
    svg += "<text x=\"" + px(0.5 * (area.left_px + area.right_px)) + "\" y=\"" + px(style.x_title_y_px) +
           "\" text-anchor=\"middle\">" + style.x_title + "</text>\n";
  }
  const std::string middle_y = px(0.5 * (area.top_px + area.bottom_px));
  const std::string centre = style.y_title_centre_with_comma ? px(style.y_title_x_px) + "," + middle_y
                                                             : fixed_text(style.y_title_x_px, 0) + " " + middle_y;
  svg += "<text x=\"" + fixed_text(style.y_title_x_px, 0) + "\" y=\"" + middle_y +
         "\" text-anchor=\"middle\" transform=\"rotate(-90 " + centre + ")\">" + style.y_title + "</text>\n";
}

//! The frame around the area.
inline void append_frame(std::string& svg, const PlotArea& area) {
  svg += "<rect x=\"" + px(area.left_px) + "\" y=\"" + px(area.top_px) + "\" width=\"" +
         px(area.right_px - area.left_px) + "\" height=\"" + px(area.bottom_px - area.top_px) +
         "\" fill=\"none\" stroke=\"#333333\"/>\n";
}

//! The axes of `area`: grid, tick labels and titles (in one dark grey group) and the frame.
inline void append_axes(std::string& svg, const PlotArea& area, const AxesStyle& style) {
  append_grid(svg, area);
  svg += "<g fill=\"#333333\">\n";
  if (style.y_ticks_first) append_y_tick_labels(svg, area, style.y_ticks);
  if (style.x_labels) append_x_tick_labels(svg, area, style.x_ticks);
  if (!style.y_ticks_first) append_y_tick_labels(svg, area, style.y_ticks);
  if (style.titles_in_label_group) append_axis_titles(svg, area, style);
  svg += "</g>\n";
  append_frame(svg, area);
  if (!style.titles_in_label_group) append_axis_titles(svg, area, style);
}

//! "no data", grey, in the middle of the area.
inline void append_no_data(std::string& svg, const PlotArea& area) {
  svg += "<text x=\"" + px(0.5 * (area.left_px + area.right_px)) + "\" y=\"" +
         px(0.5 * (area.top_px + area.bottom_px)) + "\" text-anchor=\"middle\" fill=\"#888888\">no data</text>\n";
}

}  // namespace feedplan::svg
