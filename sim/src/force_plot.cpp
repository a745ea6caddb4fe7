#include "feedplan/sim/force_plot.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <charconv>
#include <cmath>
#include <limits>

#include "feedplan/core/atomic_file.hpp"

namespace feedplan::sim {

namespace {

// Layout of the plot area inside the SVG, px.
constexpr double kMarginLeft_px = 80.0;
constexpr double kMarginRight_px = 30.0;
constexpr double kMarginTop_px = 50.0;
constexpr double kMarginBottom_px = 60.0;
constexpr std::size_t kMaxPeakCircles = 500;

std::string fixed(double value, int decimals) {
  std::array<char, 64> buffer{};
  const auto result =
      std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, std::chars_format::fixed, decimals);
  std::string text(buffer.data(), result.ptr);
  if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos) text.erase(0, 1);
  return text;
}

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

// A "nice" tick step (1, 2 or 5 × 10^n) giving about `count` intervals over `span`.
double tick_step(double span, int count) {
  const double raw = span / count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double residual = raw / magnitude;
  const double nice = residual <= 1.0 ? 1.0 : residual <= 2.0 ? 2.0 : residual <= 5.0 ? 5.0 : 10.0;
  return nice * magnitude;
}

// Decimals that show a tick step exactly (0.05 → 2, 20 → 0).
int decimals_for(double step) { return std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9))); }

// Maps data to pixels.
struct Frame {
  double t0_s, t1_s, f0_n, f1_n;
  double left_px, right_px, top_px, bottom_px;
  double x(double t_s) const { return left_px + (t_s - t0_s) / (t1_s - t0_s) * (right_px - left_px); }
  double y(double f_n) const { return bottom_px - (f_n - f0_n) / (f1_n - f0_n) * (bottom_px - top_px); }
};

std::string point(const Frame& frame, double t_s, double f_n) {
  return fixed(frame.x(t_s), 1) + "," + fixed(frame.y(f_n), 1);
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

  // Data ranges.
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
  const double headroom_n = 0.05 * (f_max - f_min);  // keeps the highest peak off the frame
  const double y_step = tick_step(f_max + headroom_n - f_min, 6);
  const double f0 = std::floor(f_min / y_step) * y_step;
  const double f1 = std::ceil((f_max + headroom_n) / y_step) * y_step;
  double t0 = 0.0, t1 = 1.0;
  if (!data.t_s.empty()) {
    t0 = data.t_s.front();
    t1 = data.t_s.back() > t0 ? data.t_s.back() : t0 + 1.0;
  }
  const Frame frame{t0,
                    t1,
                    f0,
                    f1 > f0 ? f1 : f0 + y_step,
                    kMarginLeft_px,
                    data.width_px - kMarginRight_px,
                    kMarginTop_px,
                    data.height_px - kMarginBottom_px};

  std::string svg;
  svg += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + fixed(data.width_px, 0) + "\" height=\"" +
         fixed(data.height_px, 0) + "\" viewBox=\"0 0 " + fixed(data.width_px, 0) + " " + fixed(data.height_px, 0) +
         "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<title>" + escape(data.title) + "</title>\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + fixed(data.width_px, 0) + "\" height=\"" + fixed(data.height_px, 0) +
         "\" fill=\"white\"/>\n";
  svg += "<text x=\"" + fixed(data.width_px / 2, 1) + "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" +
         escape(data.title) + "</text>\n";

  // Grid, ticks and tick labels.
  svg += "<g stroke=\"#dddddd\" stroke-width=\"1\">\n";
  const double x_step = tick_step(t1 - t0, 8);
  std::string labels;
  // Ticks at whole multiples of the step, counted in integers so that no error accumulates.
  const auto first_x_tick = static_cast<long long>(std::ceil(t0 / x_step - 1e-9));
  const auto last_x_tick = static_cast<long long>(std::floor(t1 / x_step + 1e-9));
  for (long long n = first_x_tick; n <= last_x_tick; ++n) {
    const double t = static_cast<double>(n) * x_step;
    const double x = frame.x(t);
    svg += "<line x1=\"" + fixed(x, 1) + "\" y1=\"" + fixed(frame.top_px, 1) + "\" x2=\"" + fixed(x, 1) + "\" y2=\"" +
           fixed(frame.bottom_px, 1) + "\"/>\n";
    labels += "<text x=\"" + fixed(x, 1) + "\" y=\"" + fixed(frame.bottom_px + 16, 1) + "\" text-anchor=\"middle\">" +
              fixed(t, decimals_for(x_step)) + "</text>\n";
  }
  const auto first_y_tick = static_cast<long long>(std::llround(frame.f0_n / y_step));
  const auto last_y_tick = static_cast<long long>(std::llround(frame.f1_n / y_step));
  for (long long n = first_y_tick; n <= last_y_tick; ++n) {
    const double f = static_cast<double>(n) * y_step;
    const double y = frame.y(f);
    svg += "<line x1=\"" + fixed(frame.left_px, 1) + "\" y1=\"" + fixed(y, 1) + "\" x2=\"" + fixed(frame.right_px, 1) +
           "\" y2=\"" + fixed(y, 1) + "\"/>\n";
    labels += "<text x=\"" + fixed(frame.left_px - 6, 1) + "\" y=\"" + fixed(y + 4, 1) + "\" text-anchor=\"end\">" +
              fixed(f, decimals_for(y_step)) + "</text>\n";
  }
  svg += "</g>\n<g fill=\"#333333\">\n" + labels + "</g>\n";

  // Axes and their labels.
  svg += "<rect x=\"" + fixed(frame.left_px, 1) + "\" y=\"" + fixed(frame.top_px, 1) + "\" width=\"" +
         fixed(frame.right_px - frame.left_px, 1) + "\" height=\"" + fixed(frame.bottom_px - frame.top_px, 1) +
         "\" fill=\"none\" stroke=\"#333333\"/>\n";
  svg += "<text x=\"" + fixed((frame.left_px + frame.right_px) / 2, 1) + "\" y=\"" + fixed(data.height_px - 16, 1) +
         "\" text-anchor=\"middle\">time t [s]</text>\n";
  const std::string y_label_at = fixed(22, 1) + "," + fixed((frame.top_px + frame.bottom_px) / 2, 1);
  svg += "<text x=\"22\" y=\"" + fixed((frame.top_px + frame.bottom_px) / 2, 1) +
         "\" text-anchor=\"middle\" transform=\"rotate(-90 " + y_label_at + ")\">force F [N]</text>\n";

  // Series.
  const std::size_t plot_columns = static_cast<std::size_t>(std::max(1.0, std::floor(frame.right_px - frame.left_px)));
  const std::size_t columns = std::max<std::size_t>(1, std::min(data.max_points_per_series / 4, plot_columns));
  bool any_point = false;
  for (const auto& s : data.series) {
    const std::vector<std::size_t> kept = min_max_decimation(data.t_s, s.values_n, columns);
    if (kept.empty()) continue;
    any_point = true;
    svg += "<polyline fill=\"none\" stroke=\"" + escape(s.color) + "\" stroke-width=\"1\" points=\"";
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (k > 0) svg += ' ';
      svg += point(frame, data.t_s[kept[k]], s.values_n[kept[k]]);
    }
    svg += "\"/>\n";
  }

  // Per-revolution peaks.
  if (!data.peaks.empty()) {
    const std::string color = "#d62728";
    if (data.peaks.size() <= kMaxPeakCircles) {
      svg += "<g fill=\"" + color + "\">\n";
      for (const auto& p : data.peaks) {
        svg += "<circle cx=\"" + fixed(frame.x(p.t_peak_s), 1) + "\" cy=\"" + fixed(frame.y(p.peak_xy_n), 1) +
               "\" r=\"3\"/>\n";
      }
      svg += "</g>\n";
    } else {
      std::vector<double> t, f;
      for (const auto& p : data.peaks) {
        t.push_back(p.t_peak_s);
        f.push_back(p.peak_xy_n);
      }
      svg += "<polyline fill=\"none\" stroke=\"" + color + "\" stroke-width=\"1.5\" points=\"";
      const std::vector<std::size_t> kept = min_max_decimation(t, f, columns);
      for (std::size_t k = 0; k < kept.size(); ++k) {
        if (k > 0) svg += ' ';
        svg += point(frame, t[kept[k]], f[kept[k]]);
      }
      svg += "\"/>\n";
    }
  }

  // Target.
  if (data.target_force_n) {
    const double y = frame.y(*data.target_force_n);
    svg += "<line x1=\"" + fixed(frame.left_px, 1) + "\" y1=\"" + fixed(y, 1) + "\" x2=\"" + fixed(frame.right_px, 1) +
           "\" y2=\"" + fixed(y, 1) + "\" stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"6 4\"/>\n";
    svg += "<text x=\"" + fixed(frame.right_px - 4, 1) + "\" y=\"" + fixed(y - 5, 1) +
           "\" text-anchor=\"end\" fill=\"#2ca02c\">target " + escape(fixed(*data.target_force_n, 0)) + " N</text>\n";
  }

  // Legend, on a white box so that lines under it do not hide it.
  std::size_t legend_width_chars = 0;
  for (const auto& s : data.series) legend_width_chars = std::max(legend_width_chars, s.label.size());
  if (!data.peaks.empty()) legend_width_chars = std::max<std::size_t>(legend_width_chars, 19);
  const std::size_t entries = data.series.size() + (data.peaks.empty() ? 0 : 1);
  if (entries > 0) {
    svg += "<rect x=\"" + fixed(frame.left_px + 4, 1) + "\" y=\"" + fixed(frame.top_px + 4, 1) + "\" width=\"" +
           fixed(44.0 + 7.0 * static_cast<double>(legend_width_chars), 1) + "\" height=\"" +
           fixed(16.0 * static_cast<double>(entries) + 6.0, 1) +
           "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#cccccc\"/>\n";
  }
  double legend_y = frame.top_px + 20;
  auto legend_entry = [&](const std::string& color, const std::string& label) {
    svg += "<line x1=\"" + fixed(frame.left_px + 10, 1) + "\" y1=\"" + fixed(legend_y - 4, 1) + "\" x2=\"" +
           fixed(frame.left_px + 34, 1) + "\" y2=\"" + fixed(legend_y - 4, 1) + "\" stroke=\"" + escape(color) +
           "\" stroke-width=\"2\"/>\n";
    svg += "<text x=\"" + fixed(frame.left_px + 40, 1) + "\" y=\"" + fixed(legend_y, 1) + "\">" + escape(label) +
           "</text>\n";
    legend_y += 16;
  };
  for (const auto& s : data.series) legend_entry(s.color, s.label);
  if (!data.peaks.empty()) legend_entry("#d62728", "peak per revolution");

  if (!any_point && data.peaks.empty()) {
    svg += "<text x=\"" + fixed((frame.left_px + frame.right_px) / 2, 1) + "\" y=\"" +
           fixed((frame.top_px + frame.bottom_px) / 2, 1) + "\" text-anchor=\"middle\" fill=\"#888888\">no data</text>\n";
  }
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
