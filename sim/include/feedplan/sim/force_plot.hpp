#pragma once
// Force-versus-time plots as self-contained SVG (no external tools, no scripts, no fonts to fetch):
// one polyline per series, optional per-revolution peak markers and a target line, axes with units,
// ticks and a title. Long series are reduced by min/max decimation per pixel column, so every peak
// that would be visible at full resolution stays in the plot.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::sim {

//! One line of the plot: a value per sample time of ForcePlotData::t_s.
struct ForcePlotSeries {
  std::string label;              //!< legend text, e.g. "|F_xy|"
  std::vector<double> values_n;   //!< force per sample, N (NaN: not drawn)
  std::string color = "#1f77b4";  //!< SVG colour of the line
};

//! What to draw.
struct ForcePlotData {
  std::string title = "Cutting force";     //!< text above the plot
  std::vector<double> t_s;                 //!< sample times, s, increasing
  std::vector<ForcePlotSeries> series;     //!< lines, each as long as t_s
  std::vector<force_log::RevolutionPeak> peaks;       //!< per-revolution peaks to mark (t_peak_s, peak_xy_n); may be empty
  std::optional<double> target_force_n;    //!< draw a dashed horizontal line at this force, N
  double width_px = 1200.0;                //!< SVG width, px (≥ 200)
  double height_px = 600.0;                //!< SVG height, px (≥ 150)
  std::size_t max_points_per_series = 4000;  //!< decimation limit per polyline (≥ 4)
};

//! Indices of the samples of `values` that min/max decimation keeps: the time span of `t_s` is cut
//! into `columns` equal columns and, in each, the first sample, the smallest and the largest value and
//! the last sample are kept (in time order, each once), so the global maximum and minimum are always
//! kept exactly. NaN values are never kept. Returns every finite sample's index when there are no more
//! than 4 × `columns` of them. `t_s` must increase and be as long as `values`.
std::vector<std::size_t> min_max_decimation(const std::vector<double>& t_s, const std::vector<double>& values,
                                            std::size_t columns);

//! The plot as SVG text. The x axis spans t_s (seconds), the y axis 0 (or the smallest value, if
//! negative) to the largest value, peak or target plus a margin, with 1-2-5 ticks; each series is a
//! polyline of at most max_points_per_series points (min_max_decimation with max_points / 4 columns);
//! peaks are small circles (a polyline when there are more than 500); the target is a dashed line with
//! its value. Title and labels are XML-escaped. Sizes and lengths must be valid (assert); an empty plot
//! (no samples) still gives axes and a "no data" note.
std::string force_plot_svg(const ForcePlotData& data);

//! Writes force_plot_svg(data) to `path` atomically. Returns "" on success, otherwise a message naming
//! the path and the reason; the target is then left as it was.
std::string write_force_plot(const std::string& path, const ForcePlotData& data);

//! Plot data for a force log: the XY resultant |F_xy| = sqrt(fx² + fy²) against time, titled `title`,
//! with `peaks` marked (pass revolution_peaks(...) or nothing) and an optional target. A log without
//! forces (has_forces false) gives an empty series.
ForcePlotData force_plot_data(const force_log::ForceLog& log, const std::string& title, std::vector<force_log::RevolutionPeak> peaks = {},
                              std::optional<double> target_force_n = std::nullopt);

}  // namespace feedplan::sim
