// The plan plot (SVG): well-formed XML with the three panels, their labels and the target; numbers read
// back from the drawing through its own tick labels (an independent scale: the labels are the values the
// reader of the plot sees) match the plan — the highest force of a million samples survives decimation
// at its exact value, the programmed F steps sit at their F, the feed limit stays inside its panel; a
// million-sample plan stays under 2 MB.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/plan_plot.hpp"

namespace feedplan::planner {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// --- A tiny XML checker ---------------------------------------------------------------------------

// "" when `text` is well-formed as far as this SVG can go wrong: one root element, every start tag closed
// in order, attribute values quoted, no '<' inside a tag, every '&' one of the predefined entities (or a
// numeric one). Otherwise the first problem.
std::string xml_problem(const std::string& text) {
  std::vector<std::string> open;
  int roots = 0;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '&') {
      const std::size_t end = text.find(';', i);
      const std::string name = end == std::string::npos ? "" : text.substr(i + 1, end - i - 1);
      const bool numeric = name.size() > 1 && name[0] == '#' &&
                           name.find_first_not_of("0123456789", 1) == std::string::npos;
      if (!numeric && name != "lt" && name != "gt" && name != "amp" && name != "quot" && name != "apos") {
        return "bad entity at " + std::to_string(i);
      }
      i = end + 1;
      continue;
    }
    if (text[i] != '<') {
      ++i;
      continue;
    }
    if (text.compare(i, 2, "<?") == 0) {
      if (i != 0) return "processing instruction not at the start";
      i = text.find("?>", i) + 2;
      continue;
    }
    // The tag, up to the '>' outside quotes.
    std::size_t j = i + 1;
    bool quoted = false;
    for (; j < text.size() && (quoted || text[j] != '>'); ++j) {
      if (text[j] == '"') quoted = !quoted;
      if (text[j] == '<' && !quoted) return "'<' inside a tag at " + std::to_string(j);
      if (text[j] == '<' && quoted) return "'<' in an attribute value at " + std::to_string(j);
    }
    if (j == text.size()) return "unterminated tag at " + std::to_string(i);
    const std::string tag = text.substr(i + 1, j - i - 1);
    i = j + 1;
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return "</" + tag.substr(1) + "> closes nothing open";
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \n/"));
    if (open.empty() && ++roots > 1) return "second root element <" + name + ">";
    if (tag.back() != '/') open.push_back(name);
  }
  if (!open.empty()) return "<" + open.back() + "> not closed";
  return roots == 1 ? "" : "no root element";
}

TEST(XmlChecker, CatchesWhatItIsFor) {
  EXPECT_EQ(xml_problem("<svg><g><path d=\"M1,2\"/></g></svg>"), "");
  EXPECT_NE(xml_problem("<svg><g></svg>"), "");
  EXPECT_NE(xml_problem("<svg><text>a < b</text></svg>"), "");
  EXPECT_NE(xml_problem("<svg><text>a & b</text></svg>"), "");
  EXPECT_NE(xml_problem("<svg></svg><svg></svg>"), "");
}

// --- Reading the drawing back ---------------------------------------------------------------------

// The part of the SVG inside <g id="panel-NAME">, up to the next panel.
std::string panel_text(const std::string& svg, const std::string& name) {
  const std::size_t begin = svg.find("<g id=\"panel-" + name + "\">");
  EXPECT_NE(begin, std::string::npos) << name;
  if (begin == std::string::npos) return {};
  const std::size_t end = svg.find("<g id=\"panel-", begin + 1);
  return svg.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

// Coordinates and tick positions are written with one decimal: a value read back through the ticks is
// within 0.05 px of the point and the scale's ends within 0.05 px each.
constexpr double kHalfPixels = 0.15;

// The y scale of a panel from its tick labels: value = a + b · y_px.
struct Scale {
  double a = 0.0, b = 0.0;
  double value(double y_px) const { return a + b * y_px; }
  double pixels_per_unit() const { return std::abs(1.0 / b); }
};

// Each element of `text` that starts with `opening` (e.g. "<text class=\"y-tick\""): the start tag and, for
// elements with content, the text up to the next '<'.
struct Element {
  std::string tag;      // from '<' to '>'
  std::string content;  // text after the tag up to the next '<'
};

std::vector<Element> elements(const std::string& text, const std::string& opening) {
  std::vector<Element> found;
  for (std::size_t at = text.find(opening); at != std::string::npos; at = text.find(opening, at + 1)) {
    const std::size_t tag_end = text.find('>', at);
    const std::size_t content_end = text.find('<', tag_end);
    found.push_back({text.substr(at, tag_end - at + 1), text.substr(tag_end + 1, content_end - tag_end - 1)});
  }
  return found;
}

// The value of attribute `name` in a start tag ("" when absent).
std::string attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const std::size_t at = tag.find(key);
  if (at == std::string::npos) return {};
  const std::size_t begin = at + key.size();
  return tag.substr(begin, tag.find('"', begin) - begin);
}

Scale y_scale(const std::string& panel) {
  std::vector<std::pair<double, double>> ticks;  // (y px, value)
  for (const Element& tick : elements(panel, "<text class=\"y-tick\"")) {
    ticks.emplace_back(std::stod(attribute(tick.tag, "y")), std::stod(tick.content));
  }
  EXPECT_GE(ticks.size(), 3u);
  if (ticks.size() < 2) return {};
  const auto [y0, v0] = ticks.front();
  const auto [y1, v1] = ticks.back();
  Scale scale;
  scale.b = (v1 - v0) / (y1 - y0);
  scale.a = v0 - scale.b * y0;
  return scale;
}

// The largest y tick label of a panel: the top of its scale.
double highest_tick(const std::string& panel) {
  double highest = -1e300;
  for (const Element& tick : elements(panel, "<text class=\"y-tick\"")) highest = std::max(highest, std::stod(tick.content));
  return highest;
}

// The points of the <path class="NAME"> in `panel`, each run of the path ("M x,y x,y …") separately.
std::vector<std::vector<std::pair<double, double>>> path_runs(const std::string& panel, const std::string& name) {
  std::vector<std::vector<std::pair<double, double>>> runs;
  const std::vector<Element> paths = elements(panel, "<path class=\"" + name + "\"");
  EXPECT_LE(paths.size(), 1u);
  if (paths.empty()) return runs;
  std::istringstream d(attribute(paths.front().tag, "d"));
  std::string token;
  while (d >> token) {
    if (token == "l0,0") continue;  // a lone point's dot
    if (token.front() == 'M') {
      runs.emplace_back();
      token.erase(0, 1);
    }
    const std::size_t comma = token.find(',');
    runs.back().emplace_back(std::stod(token.substr(0, comma)), std::stod(token.substr(comma + 1)));
  }
  return runs;
}

std::vector<std::pair<double, double>> path_points(const std::string& panel, const std::string& name) {
  std::vector<std::pair<double, double>> points;
  for (const auto& run : path_runs(panel, name)) points.insert(points.end(), run.begin(), run.end());
  return points;
}

// --- Plans to draw --------------------------------------------------------------------------------

// `n` engaged samples 0.01 mm apart at 1000 mm/min, one block per 100 samples, a force that wanders
// between 250 and 320 N — with one spike and one dip when asked.
PlanResult synthetic_plan(std::size_t n, std::optional<std::size_t> spike_at = {}, double spike_n = 0.0) {
  PlanResult result;
  result.samples.resize(n);
  std::uint64_t state = 12345;  // fixed seed: the same plan every run
  for (std::size_t i = 0; i < n; ++i) {
    PlannedSample& p = result.samples[i];
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const double noise = static_cast<double>(state >> 11) / 9007199254740992.0;  // [0, 1)
    p.s_mm = 0.01 * static_cast<double>(i);
    p.time_s = p.s_mm / (1000.0 / 60.0);
    p.engaged = true;
    p.engagement_rad = 0.6 + 0.2 * std::sin(0.001 * static_cast<double>(i));
    p.limit_reason = FeedLimitReason::kForce;
    p.feed_limit_mm_per_min = 1100.0 + 50.0 * noise;
    p.feed_mm_per_min = 1000.0;
    p.predicted_force_n = 285.0 + 25.0 * std::sin(0.0003 * static_cast<double>(i)) + 10.0 * noise;
    p.block_index = static_cast<int>(i / 100);
  }
  if (spike_at) result.samples[*spike_at].predicted_force_n = spike_n;
  for (std::size_t first = 0; first + 1 < n; first += 100) {
    PlannedBlock block;
    block.first_sample = static_cast<int>(first);
    block.last_sample = static_cast<int>(std::min(first + 100, n - 1));
    block.feed_mm_per_min = 1000.0;
    result.blocks.push_back(block);
  }
  return result;
}

// --- Tests ----------------------------------------------------------------------------------------

TEST(PlanPlot, IsWellFormedWithThreeLabelledPanelsAndTheTarget) {
  const std::string svg = plan_plot_svg(synthetic_plan(2000), 312.5);
  EXPECT_EQ(xml_problem(svg), "");
  for (const char* id : {"panel-engagement", "panel-feed", "panel-force"}) EXPECT_THAT(svg, HasSubstr(id));
  EXPECT_THAT(svg, HasSubstr(">engagement α_en [deg]<"));
  EXPECT_THAT(svg, HasSubstr(">feed [mm/min]<"));
  EXPECT_THAT(svg, HasSubstr(">force F [N]<"));
  EXPECT_THAT(svg, HasSubstr(">path length s [mm]<"));
  EXPECT_THAT(svg, HasSubstr(">target 312.5 N<"));
  EXPECT_THAT(svg, HasSubstr(">programmed F (blocks)<"));
  EXPECT_THAT(svg, HasSubstr(">predicted feed<"));
  EXPECT_THAT(svg, HasSubstr(">feed limit<"));
  EXPECT_THAT(svg, HasSubstr(">predicted force<"));
  EXPECT_THAT(svg, Not(HasSubstr("measured peaks")));
  EXPECT_THAT(svg, Not(HasSubstr("\"nan")));
  EXPECT_THAT(svg, Not(HasSubstr(",nan")));
  EXPECT_THAT(svg, Not(HasSubstr("inf")));

  PlanPlotOptions options;
  options.x_is_time = true;
  EXPECT_THAT(plan_plot_svg(synthetic_plan(10), 300.0, options), HasSubstr(">time t [s]<"));
}

TEST(PlanPlot, TitleIsEscaped) {
  PlanPlotOptions options;
  options.title = "slot <A&B> \"x\" 'y'";
  const std::string svg = plan_plot_svg(synthetic_plan(100), 300.0, options);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_THAT(svg, HasSubstr("slot &lt;A&amp;B&gt; &quot;x&quot; &#39;y&#39;"));
}

TEST(PlanPlot, TargetLineIsAtTheTargetOnTheForceScale) {
  const std::string force = panel_text(plan_plot_svg(synthetic_plan(2000), 312.5), "force");
  const std::vector<Element> target = elements(force, "<line class=\"target\"");
  ASSERT_EQ(target.size(), 1u);
  const Scale scale = y_scale(force);
  EXPECT_NEAR(scale.value(std::stod(attribute(target.front().tag, "y1"))), 312.5, kHalfPixels / scale.pixels_per_unit() + 1e-9);
}

TEST(PlanPlot, MillionSamplesStaySmallAndKeepTheHighestForceExactly) {
  constexpr std::size_t kSamples = 1'000'000;
  constexpr std::size_t kSpikeAt = 612'345;
  constexpr double kSpikeN = 487.25;
  constexpr double kDipN = 121.5;
  PlanResult result = synthetic_plan(kSamples, kSpikeAt, kSpikeN);
  result.samples[345'678].predicted_force_n = kDipN;
  const std::string svg = plan_plot_svg(result, 300.0);
  EXPECT_LT(svg.size(), 2'000'000u);
  EXPECT_EQ(xml_problem(svg), "");

  const std::string force = panel_text(svg, "force");
  const Scale scale = y_scale(force);
  const std::vector<std::pair<double, double>> points = path_points(force, "predicted-force");
  ASSERT_FALSE(points.empty());
  EXPECT_LT(points.size(), 10'000u);
  const auto top = std::min_element(points.begin(), points.end(),
                                    [](const auto& a, const auto& b) { return a.second < b.second; });
  // Coordinates have one decimal: the value read back is within rounding of the spike.
  EXPECT_NEAR(scale.value(top->second), kSpikeN, kHalfPixels / scale.pixels_per_unit());
  // Without the spike the top would be near 320 N, tens of pixels lower: the test sees the difference.
  EXPECT_GT((kSpikeN - 320.0) * scale.pixels_per_unit(), 20.0);
  // The lowest sample (a dip of one sample) is kept exactly too.
  const auto bottom = std::max_element(points.begin(), points.end(),
                                       [](const auto& a, const auto& b) { return a.second < b.second; });
  EXPECT_NEAR(scale.value(bottom->second), kDipN, kHalfPixels / scale.pixels_per_unit());
}

TEST(PlanPlot, ProgrammedFeedIsAStepLineAtEachBlocksF) {
  PlanResult result = synthetic_plan(301);  // blocks [0,100], [100,200], [200,300]
  ASSERT_EQ(result.blocks.size(), 3u);
  result.blocks[1].feed_mm_per_min = 1500.0;
  result.blocks[2].feed_mm_per_min = 700.0;
  const std::string feed = panel_text(plan_plot_svg(result, 300.0), "feed");
  const Scale scale = y_scale(feed);
  const std::vector<std::pair<double, double>> points = path_points(feed, "block-feed");
  ASSERT_EQ(points.size(), 6u);
  const double tolerance = kHalfPixels / scale.pixels_per_unit();
  const double want[] = {1000.0, 1000.0, 1500.0, 1500.0, 700.0, 700.0};
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(scale.value(points[k].second), want[k], tolerance) << k;
  // Each step rises or falls where the next block starts.
  EXPECT_EQ(points[1].first, points[2].first);
  EXPECT_EQ(points[3].first, points[4].first);
  EXPECT_LT(points[0].first, points[1].first);
}

TEST(PlanPlot, FeedLimitAboveThePanelIsCutOffAtItsTop) {
  PlanResult result = synthetic_plan(500);
  for (std::size_t i = 200; i < 300; ++i) result.samples[i].feed_limit_mm_per_min = 1e7;
  const std::string feed = panel_text(plan_plot_svg(result, 300.0), "feed");
  const Scale scale = y_scale(feed);
  double highest = 0.0;
  for (const auto& [x, y] : path_points(feed, "feed-limit")) highest = std::max(highest, scale.value(y));
  EXPECT_GT(highest, 1000.0);  // drawn, and above the feed
  EXPECT_NEAR(highest, highest_tick(feed), kHalfPixels / scale.pixels_per_unit());  // at the top, not at 1e7
}

TEST(PlanPlot, RapidsAreGapsInTheLines) {
  PlanResult result = synthetic_plan(600);
  for (std::size_t i = 250; i < 350; ++i) {
    result.samples[i].limit_reason = FeedLimitReason::kRapid;
    result.samples[i].feed_mm_per_min = 30000.0;
  }
  result.blocks[2].feed_mm_per_min = 0.0;  // samples 200–300 as a rapid block
  const std::string svg = plan_plot_svg(result, 300.0);
  EXPECT_EQ(path_runs(panel_text(svg, "force"), "predicted-force").size(), 2u);
  EXPECT_EQ(path_runs(panel_text(svg, "feed"), "predicted-feed").size(), 2u);
  EXPECT_EQ(path_runs(panel_text(svg, "feed"), "block-feed").size(), 2u);
  // The rapid speed does not stretch the feed axis.
  EXPECT_LT(highest_tick(panel_text(svg, "feed")), 5000.0);
}

TEST(PlanPlot, MeasuredPeaksAreMarkersOnTheForcePanel) {
  PlanPlotOptions options;
  options.measured_peaks = std::vector<std::pair<double, double>>{};
  for (int k = 0; k < 10; ++k) options.measured_peaks->emplace_back(1.0 + 0.5 * k, 290.0 + k);
  options.measured_peaks->emplace_back(500.0, 900.0);  // beyond the path: not drawn, no effect on the scale
  const std::string svg = plan_plot_svg(synthetic_plan(1001), 300.0, options);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_THAT(svg, HasSubstr(">measured peaks<"));
  const std::string force = panel_text(svg, "force");
  const std::size_t group = force.find("<g class=\"measured-peaks\"");
  ASSERT_NE(group, std::string::npos);
  const std::string markers = force.substr(group, force.find("</g>", group) - group);
  std::vector<double> forces;
  const Scale scale = y_scale(force);
  for (const Element& circle : elements(markers, "<circle ")) forces.push_back(scale.value(std::stod(attribute(circle.tag, "cy"))));
  ASSERT_EQ(forces.size(), 10u);
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(forces[static_cast<std::size_t>(k)], 290.0 + k, 0.5);
}

TEST(PlanPlot, EmptyPlanGivesPanelsWithANote) {
  const std::string svg = plan_plot_svg(PlanResult{}, 300.0);
  EXPECT_EQ(xml_problem(svg), "");
  EXPECT_THAT(svg, HasSubstr("panel-force"));
  EXPECT_THAT(svg, HasSubstr(">no data<"));
}

TEST(PlanPlot, WriteIsAtomicAndReportsFailures) {
  const std::filesystem::path directory = std::filesystem::temp_directory_path() / "feedplan_plan_plot_test";
  std::filesystem::create_directories(directory);
  EXPECT_EQ(write_plan_plot(directory / "plan.svg", synthetic_plan(100), 300.0), "");
  EXPECT_TRUE(std::filesystem::file_size(directory / "plan.svg") > 1000u);
  const std::filesystem::path bad = directory / "missing" / "plan.svg";
  EXPECT_THAT(write_plan_plot(bad, synthetic_plan(100), 300.0), HasSubstr(bad.string()));
}

}  // namespace
}  // namespace feedplan::planner
