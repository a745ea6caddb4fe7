#include "feedplan/report/plan_page.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "feedplan/core/number_text.hpp"
#include "feedplan/report/html_page.hpp"

namespace feedplan::report {
namespace {

using nlohmann::json;

// The reasons a feed is limited, in FeedLimitReason's order: the page reads a sample's reason by index.
constexpr planner::FeedLimitReason kReasons[] = {
    planner::FeedLimitReason::kForce,    planner::FeedLimitReason::kModelRange, planner::FeedLimitReason::kMaxFeed,
    planner::FeedLimitReason::kCentripetal, planner::FeedLimitReason::kAirFeed, planner::FeedLimitReason::kMinFeed,
    planner::FeedLimitReason::kRapid,    planner::FeedLimitReason::kPlunge};

int reason_index(planner::FeedLimitReason reason) {
  for (int i = 0; i < static_cast<int>(std::size(kReasons)); ++i) {
    if (kReasons[i] == reason) return i;
  }
  assert(false && "a FeedLimitReason missing from kReasons");
  return 0;
}

// `value` rounded to `decimals` as the plan CSV writes it; null (NaN) stays null in JSON.
double rounded(double value, int decimals) {
  if (!std::isfinite(value)) return value;
  const double scale = std::pow(10.0, decimals);
  return std::round(value * scale) / scale;
}

constexpr int kLengthDecimals = 4;
constexpr int kAngleDecimals = 4;
constexpr int kChipDecimals = 6;
constexpr int kFeedForceDecimals = 3;
constexpr int kTimeDecimals = 6;

// A column of the samples: `value(sample)` rounded to `decimals`.
template <typename Value>
json column(const std::vector<planner::PlannedSample>& samples, int decimals, Value value) {
  json out = json::array();
  for (const planner::PlannedSample& sample : samples) out.push_back(rounded(value(sample), decimals));
  return out;
}

// Per-sample forces measured (0: none) as JSON, null where nothing was measured.
json measured_column(const std::vector<double>& measured_n) {
  json out = json::array();
  for (const double f : measured_n) {
    if (f > 0.0) {
      out.push_back(rounded(f, kFeedForceDecimals));
    } else {
      out.push_back(nullptr);
    }
  }
  return out;
}

json samples_json(const planner::PlanResult& result, const PlanPage& page) {
  const auto& s = result.samples;
  json out;
  out["s_mm"] = column(s, kLengthDecimals, [](const auto& p) { return p.s_mm; });
  out["x_mm"] = column(s, kLengthDecimals, [](const auto& p) { return p.position.x_mm; });
  out["y_mm"] = column(s, kLengthDecimals, [](const auto& p) { return p.position.y_mm; });
  out["engagement_deg"] = column(s, kAngleDecimals, [](const auto& p) { return p.engagement_rad * 180.0 / std::numbers::pi; });
  out["chip_thickness_mm"] = column(s, kChipDecimals, [](const auto& p) { return p.chip_thickness_mm; });
  out["contact_length_mm"] = column(s, kLengthDecimals, [](const auto& p) { return p.contact_length_mm; });
  out["feed_mm_per_min"] = column(s, kFeedForceDecimals, [](const auto& p) { return p.feed_mm_per_min; });
  out["feed_limit_mm_per_min"] = column(s, kFeedForceDecimals, [](const auto& p) { return p.feed_limit_mm_per_min; });
  out["predicted_force_n"] = column(s, kFeedForceDecimals, [](const auto& p) { return p.predicted_force_n; });
  out["upper_force_n"] = column(s, kFeedForceDecimals, [](const auto& p) { return p.upper_force_n; });
  out["time_s"] = column(s, kTimeDecimals, [](const auto& p) { return p.time_s; });
  json reasons = json::array();
  json engaged = json::array();
  json extrapolated = json::array();
  for (const planner::PlannedSample& p : s) {
    reasons.push_back(reason_index(p.limit_reason));
    engaged.push_back(p.engaged ? 1 : 0);
    extrapolated.push_back(p.extrapolated ? 1 : 0);
  }
  out["limit_reason"] = std::move(reasons);
  out["engaged"] = std::move(engaged);
  out["extrapolated"] = std::move(extrapolated);
  if (!page.measured_peak_n.empty()) {
    assert(page.measured_peak_n.size() == s.size());
    out["measured_peak_n"] = measured_column(page.measured_peak_n);
  }
  return out;
}

// The largest peak measured against the target, (max − target) / target in %: how far the worst place
// overshoots (negative: every peak below it); NaN when nothing was measured.
double peak_error_percent(const std::vector<double>& measured_n, double target_n) {
  double largest = 0.0;
  for (const double f : measured_n) largest = std::max(largest, f);
  return largest > 0.0 ? 100.0 * (largest - target_n) / target_n : std::nan("");
}

json history_json(const PlanPage& page, double target_n, std::size_t sample_count) {
  json cycles = json::array();
  for (const planner::PathHistoryCycle& c : page.history) {
    assert(c.feed_mm_per_min.size() == sample_count && c.predicted_n.size() == sample_count &&
           c.measured_n.size() == sample_count);
    (void)sample_count;
    json feed = json::array();
    json predicted = json::array();
    for (std::size_t i = 0; i < c.feed_mm_per_min.size(); ++i) {
      feed.push_back(rounded(c.feed_mm_per_min[i], kFeedForceDecimals));
      predicted.push_back(rounded(c.predicted_n[i], kFeedForceDecimals));
    }
    cycles.push_back({{"cycle", c.cycle},
                      {"cycle_time_s", rounded(c.cycle_time_s, kTimeDecimals)},
                      {"peak_error_percent", rounded(peak_error_percent(c.measured_n, target_n), 2)},
                      {"feed_mm_per_min", std::move(feed)},
                      {"predicted_n", std::move(predicted)},
                      {"measured_n", measured_column(c.measured_n)}});
  }
  return {{"cycles", std::move(cycles)},
          {"table", {{"columns", page.cycle_table.columns}, {"rows", page.cycle_table.rows}}}};
}

std::string seconds_text(double s) { return fixed_number_text(s, 2) + " s"; }
std::string newtons_text(double n) { return fixed_number_text(n, 1) + " N"; }
std::string feed_text(double f) { return fixed_number_text(f, 0) + " mm/min"; }

}  // namespace

std::vector<SummaryLine> plan_summary_lines(const planner::PlanResult& result, const planner::PlanSettings& settings) {
  const planner::PlanSummary& s = result.summary;
  std::vector<SummaryLine> lines;
  lines.emplace_back("status", planner::to_string(result.status));
  lines.emplace_back("target force", newtons_text(settings.target_force_n));
  lines.emplace_back("spindle speed", fixed_number_text(settings.spindle_rpm, 0) + " rev/min");
  lines.emplace_back("cycle time, planned", seconds_text(s.cycle_time_s));
  lines.emplace_back("cutting time", seconds_text(s.cutting_time_s));
  lines.emplace_back("air time", seconds_text(s.air_time_s));
  lines.emplace_back("constant feed with the plan's predicted peak",
                     feed_text(s.baseline.feed_mm_per_min) + ": " + seconds_text(s.baseline.cycle_time_s));
  lines.emplace_back("time saved against it", fixed_number_text(s.time_saved_percent, 1) + " %");
  lines.emplace_back("largest predicted force", newtons_text(s.max_predicted_force_n));
  lines.emplace_back("block feeds", feed_text(s.min_feed_mm_per_min) + " to " + feed_text(s.max_feed_mm_per_min));
  lines.emplace_back("machine feed range", feed_text(settings.machine.min_feed_mm_per_min) + " to " +
                                               feed_text(settings.machine.max_feed_mm_per_min));
  lines.emplace_back("samples", std::to_string(result.samples.size()) + " (" + std::to_string(s.engaged_samples) +
                                    " engaged, " + std::to_string(s.force_limited_samples) + " force-limited, " +
                                    std::to_string(s.extrapolated_samples) + " extrapolated, " +
                                    std::to_string(s.over_target_samples) + " over the target)");
  lines.emplace_back("blocks", std::to_string(result.blocks.size()));
  if (settings.uncertainty) {
    lines.emplace_back("cautious bound", "F̂ + " + shortest_number_text(settings.uncertainty->sigmas) +
                                             "σ held at the target (r = " +
                                             shortest_number_text(settings.uncertainty->relative) + ")");
  }
  return lines;
}

std::string plan_page_json(const planner::PlanResult& result, const planner::PlanSettings& settings,
                           const PlanPage& page) {
  json data;
  data["format"] = "feedplan-html-report";
  data["kind"] = page.history.empty() ? "plan" : "history";
  data["title"] = page.title;
  json summary = json::array();
  for (const auto& [label, value] : page.summary) summary.push_back({label, value});
  data["summary"] = std::move(summary);
  data["notes"] = page.notes;
  data["status"] = planner::to_string(result.status);
  data["target_force_n"] = settings.target_force_n;
  data["cautious"] = settings.uncertainty.has_value();
  data["machine"] = {{"min_feed_mm_per_min", settings.machine.min_feed_mm_per_min},
                     {"max_feed_mm_per_min", settings.machine.max_feed_mm_per_min}};
  json reasons = json::array();
  for (const planner::FeedLimitReason reason : kReasons) reasons.push_back(planner::to_string(reason));
  data["limit_reasons"] = std::move(reasons);
  data["samples"] = samples_json(result, page);
  if (!page.history.empty()) data["history"] = history_json(page, settings.target_force_n, result.samples.size());
  return data.dump();
}

std::string plan_page_html(const planner::PlanResult& result, const planner::PlanSettings& settings,
                           const PlanPage& page) {
  return html_page(page.title, plan_page_json(result, settings, page));
}

}  // namespace feedplan::report
