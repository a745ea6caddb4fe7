// Force plots: well-formed SVG with title, axis labels, target and peak markers; min/max decimation
// keeps every extreme (checked against maxima computed here) and stays within the point limit.

#include "feedplan/sim/force_plot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::sim {
namespace {

const std::string kKistlerDir = std::string(FEEDPLAN_TEST_DATA_DIR) + "/kistler/";

// Checks that every element is closed in order and that text holds no bare '<' or '&'. Returns ""
// when the document is well formed, otherwise what is wrong.
std::string well_formed(const std::string& svg) {
  std::vector<std::string> open;
  std::size_t i = 0;
  while (i < svg.size()) {
    if (svg[i] == '&') {
      const std::size_t semicolon = svg.find(';', i);
      if (semicolon == std::string::npos) return "bare '&'";
      const std::string entity = svg.substr(i, semicolon - i + 1);
      if (entity != "&amp;" && entity != "&lt;" && entity != "&gt;" && entity != "&quot;" && entity != "&apos;") {
        return "bad entity " + entity;
      }
      i = semicolon + 1;
      continue;
    }
    if (svg[i] != '<') {
      ++i;
      continue;
    }
    const std::size_t close = svg.find('>', i);
    if (close == std::string::npos) return "unterminated tag";
    const std::string tag = svg.substr(i + 1, close - i - 1);
    if (tag.find('<') != std::string::npos) return "'<' inside tag " + tag;
    i = close + 1;
    if (tag.front() == '?') continue;  // XML declaration
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return "unbalanced </" + tag.substr(1) + ">";
      open.pop_back();
      continue;
    }
    if (tag.back() == '/') continue;  // self-closing
    open.push_back(tag.substr(0, tag.find_first_of(" \n")));
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  return "";
}

// The points of every polyline, as (x, y) pairs. (Plain search: std::regex recurses per character
// and overflows the stack on a points attribute of 50 kB.)
std::vector<std::vector<std::pair<double, double>>> polylines(const std::string& svg) {
  std::vector<std::vector<std::pair<double, double>>> result;
  for (std::size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) {
    const std::size_t begin = svg.find("points=\"", at) + 8;
    const std::size_t end = svg.find('"', begin);
    std::vector<std::pair<double, double>> line;
    std::istringstream in(svg.substr(begin, end - begin));
    std::string pair;
    while (in >> pair) {
      const std::size_t comma = pair.find(',');
      line.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
    }
    result.push_back(line);
  }
  return result;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

ForcePlotData noisy_data(std::size_t samples, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 10.0);
  ForcePlotData data;
  data.title = "noisy";
  ForcePlotSeries s;
  s.label = "|F_xy|";
  for (std::size_t i = 0; i < samples; ++i) {
    data.t_s.push_back(static_cast<double>(i) * 1e-4);
    s.values_n.push_back(200.0 + 100.0 * std::sin(static_cast<double>(i) * 0.0628) + noise(rng));
  }
  data.series.push_back(s);
  return data;
}

TEST(MinMaxDecimation, KeepsGlobalExtremesExactlyAndEverySpike) {
  const std::uint64_t seed = 20240611;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(-50.0, 50.0);
  const std::size_t n = 100000;
  std::vector<double> t(n), v(n);
  for (std::size_t i = 0; i < n; ++i) {
    t[i] = 1.5 + static_cast<double>(i) * 2e-5;
    v[i] = uniform(rng);
  }
  // One spike every 3000 samples (columns hold 100 samples), each the largest value of its column.
  std::set<std::size_t> spikes;
  for (std::size_t i = 1234; i < n; i += 3000) {
    v[i] = 1000.0 + static_cast<double>(i);
    spikes.insert(i);
  }
  const auto kept = min_max_decimation(t, v, 1000);
  SCOPED_TRACE("seed " + std::to_string(seed));
  EXPECT_LE(kept.size(), 4000u);
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
  EXPECT_EQ(std::adjacent_find(kept.begin(), kept.end()), kept.end()) << "an index kept twice";
  double kept_max = -1e300, kept_min = 1e300;
  for (const std::size_t i : kept) {
    kept_max = std::max(kept_max, v[i]);
    kept_min = std::min(kept_min, v[i]);
  }
  EXPECT_EQ(kept_max, *std::max_element(v.begin(), v.end()));
  EXPECT_EQ(kept_min, *std::min_element(v.begin(), v.end()));
  for (const std::size_t spike : spikes) {
    EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), spike)) << "spike at " << spike << " lost";
  }
  EXPECT_EQ(kept.front(), 0u);
  EXPECT_EQ(kept.back(), n - 1);
}

TEST(MinMaxDecimation, ShortSeriesKeptWholeAndNaNDropped) {
  const std::vector<double> t = {0, 1, 2, 3, 4};
  const std::vector<double> v = {1, std::nan(""), 3, 2, 5};
  EXPECT_EQ(min_max_decimation(t, v, 10), (std::vector<std::size_t>{0, 2, 3, 4}));
}

TEST(ForcePlot, WellFormedWithTitleAxesTargetAndPeaks) {
  const force_log::ForceLog log = force_log::load_force_log(kKistlerDir + "n6000_f900_ap3_excerpt.csv");
  std::vector<double> t, fx, fy;
  for (const auto& r : log.rows) {
    t.push_back(r.t_s);
    fx.push_back(r.fx_n);
    fy.push_back(r.fy_n);
  }
  const auto peaks = force_log::revolution_peaks(t, fx, fy, 6000.0);
  const ForcePlotData data = force_plot_data(log, "Slot <f900> & 6000 rpm", peaks, 450.0);
  const std::string svg = force_plot_svg(data);
  EXPECT_EQ(well_formed(svg), "");
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_EQ(count(svg, "Slot &lt;f900&gt; &amp; 6000 rpm"), 2u) << "title element and visible title";
  EXPECT_NE(svg.find(">time t [s]</text>"), std::string::npos);
  EXPECT_NE(svg.find(">force F [N]</text>"), std::string::npos);
  EXPECT_NE(svg.find(">target 450 N</text>"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_EQ(count(svg, "<circle"), peaks.size());
  EXPECT_NE(svg.find(">|F_xy|</text>"), std::string::npos);
  EXPECT_NE(svg.find(">peak per revolution</text>"), std::string::npos);
  // Tick labels (step 0.02 s) on the time axis of the 3.0000–3.0999 s excerpt.
  EXPECT_NE(svg.find(">3.00</text>"), std::string::npos);
  EXPECT_NE(svg.find(">3.08</text>"), std::string::npos);
  // 1000 samples ≤ the limit: drawn whole.
  const auto lines = polylines(svg);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].size(), 1000u);
}

TEST(ForcePlot, LongSeriesDecimatedWithinLimitKeepingTheSpike) {
  for (const std::size_t limit : {std::size_t{4000}, std::size_t{400}}) {
    ForcePlotData data = noisy_data(200000, 7);
    data.max_points_per_series = limit;
    data.series[0].values_n[123457] = 5000.0;  // one sample far above the rest (≤ ~350 N)
    const std::string svg = force_plot_svg(data);
    ASSERT_EQ(well_formed(svg), "");
    const auto lines = polylines(svg);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_LE(lines[0].size(), limit);
    EXPECT_GE(lines[0].size(), limit / 4);
    // The spike is the one point near the top: the y range ends just above it.
    const double plot_top = 50.0, plot_bottom = data.height_px - 60.0;
    std::size_t high_points = 0;
    for (const auto& [x, y] : lines[0]) {
      if (y < plot_top + 0.25 * (plot_bottom - plot_top)) ++high_points;
    }
    EXPECT_EQ(high_points, 1u) << "limit " << limit;
  }
}

TEST(ForcePlot, EmptyDataStillAPlot) {
  ForcePlotData data;
  data.title = "nothing";
  const std::string svg = force_plot_svg(data);
  EXPECT_EQ(well_formed(svg), "");
  EXPECT_NE(svg.find(">no data</text>"), std::string::npos);
}

TEST(ForcePlot, ManyPeaksBecomeALine) {
  ForcePlotData data = noisy_data(100000, 3);
  for (int k = 0; k < 1000; ++k) {
    force_log::RevolutionPeak p;
    p.revolution = k;
    p.t_peak_s = k * 0.01;
    p.peak_xy_n = 300.0 + k % 7;
    data.peaks.push_back(p);
  }
  const std::string svg = force_plot_svg(data);
  EXPECT_EQ(well_formed(svg), "");
  EXPECT_EQ(count(svg, "<circle"), 0u);
  EXPECT_EQ(polylines(svg).size(), 2u);
}

TEST(ForcePlot, WriteIsAtomic) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "feedplan_force_plot_test";
  std::filesystem::create_directories(dir);
  const ForcePlotData data = noisy_data(1000, 1);
  ASSERT_EQ(write_force_plot((dir / "plot.svg").string(), data), "");
  std::ifstream in(dir / "plot.svg");
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), force_plot_svg(data));
  std::filesystem::remove_all(dir);
  EXPECT_NE(write_force_plot("/nonexistent-dir/plot.svg", data), "");
}

}  // namespace
}  // namespace feedplan::sim
