#include "comparison_report.hpp"

#include "feedplan/core/number_text.hpp"
#include "feedplan/learning/infeasible_places.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::cli {

namespace {

// A percentage with its sign: "+12.3 %", "-4.0 %".
std::string signed_percent(double percent) {
  std::string text = fixed_number_text(percent, 1);
  if (text == "-0.0") text = "0.0";
  if (text.front() != '-') text.insert(text.begin(), '+');
  text += " %";
  return text;
}

std::string markdown_row(const trial::StrategyRow& row) {
  const trial::ControlJudgement& j = row.judgement;
  std::string line = "| ";
  line += row.name;
  line += " | ";
  line += fixed_number_text(j.max_peak_n, 1);
  line += " | ";
  line += signed_percent(j.max_overshoot_percent);
  line += " | ";
  line += fixed_number_text(j.rms_error_n, 1);
  line += " (";
  line += fixed_number_text(j.rms_error_percent, 1);
  line += " %) | ";
  line += fixed_number_text(100.0 * j.within_5_percent_share, 0);
  line += " % | ";
  line += fixed_number_text(j.cycle_time_s, 2);
  line += " | ";
  line += fixed_number_text(j.time_above_target_s, 2);
  line += " |\n";
  return line;
}

nlohmann::json row_json(const trial::StrategyRow& row) {
  const trial::ControlJudgement& j = row.judgement;
  nlohmann::json out = {{"name", row.name},
                        {"kind", std::string(trial::to_string(row.kind))},
                        {"max_peak_n", j.max_peak_n},
                        {"max_overshoot_percent", j.max_overshoot_percent},
                        {"in_cut_revolutions", j.in_cut_revolutions},
                        {"rms_error_n", j.rms_error_n},
                        {"rms_error_percent", j.rms_error_percent},
                        {"within_5_percent_share", j.within_5_percent_share},
                        {"cycle_time_s", j.cycle_time_s},
                        {"time_above_target_s", j.time_above_target_s},
                        {"revolutions", row.revolutions.size()}};
  if (row.controller) {
    out["controller"] = std::string(trial::to_string(*row.controller));
    out["controller_steps"] = row.controller_steps;
  }
  if (row.plan_cycle > 0) {
    out["plan_cycle"] = row.plan_cycle;
    out["planned_cycle_time_s"] = row.planned_cycle_time_s;
    out["plan_status"] = planner::to_string(row.plan_status);
  }
  out["warnings"] = row.warnings;
  return out;
}

}  // namespace

std::string comparison_markdown(const ComparisonContext& context, const trial::StrategyComparison& comparison) {
  std::string text = "## ";
  text += context.spec_path;
  text += " (";
  text += context.cycle;
  text += "): target ";
  text += shortest_number_text(comparison.target_force_n);
  text += " N on the virtual machine ";
  text += context.machine;
  text += "\n\n";
  text += "| strategy | largest peak, N | vs target | RMS error in cut, N | within ±5 % | cycle time, s | above target, s |\n";
  text += "|---|---:|---:|---:|---:|---:|---:|\n";
  for (const trial::StrategyRow& row : comparison.rows) text += markdown_row(row);
  text += "\nEvery row on the same machine, judged on its true per-revolution peaks of |F_xy| (which no strategy "
          "sees); in cut: a true peak of at least ";
  text += fixed_number_text(100.0 * trial::kJudgedInCutFraction, 0);
  text += " % of the target. Model: ";
  text += context.model;
  text += ". Constant feed: ";
  text += context.constant_feed_source;
  text += ". Feedback alone: the dynamometer's per-revolution peak, override 10–150 %; hybrid: override 70–130 %.\n";
  if (!comparison.learning.empty()) {
    text += "\nLearning before cycle ";
    text += std::to_string(comparison.learning_cycles);
    text += " (the loop's own runs):";
    for (const trial::LoopCycle& c : comparison.learning) {
      text += " cycle ";
      text += std::to_string(c.cycle);
      text += " ";
      text += fixed_number_text(c.simulated_cycle_time_s, 2);
      text += " s, held RMS ";
      text += fixed_number_text(c.comparison.rms_error_percent, 1);
      text += " %, largest over ";
      text += signed_percent(c.comparison.max_overshoot_percent);
      text += ";";
    }
    text.back() = '.';
    const trial::LoopCycle& last = comparison.learning.back();
    if (const std::string infeasible = learning::describe(last.infeasible, comparison.target_force_n); !infeasible.empty()) {
      text += " Cycle ";
      text += std::to_string(last.cycle);
      text += ": ";
      text += infeasible;
    }
    text += "\n";
  }
  for (const std::string& note : context.notes) {
    text += "\nNote: ";
    text += note;
    text += "\n";
  }
  return text;
}

nlohmann::json comparison_json(const ComparisonContext& context, const trial::StrategyComparison& comparison) {
  nlohmann::json out;
  out["spec"] = context.spec_path;
  out["cycle"] = context.cycle;
  out["target_force_n"] = comparison.target_force_n;
  out["machine"] = context.machine;
  out["model"] = context.model;
  out["constant_feed_mm_per_min"] = comparison.constant_feed_mm_per_min;
  out["constant_feed_source"] = context.constant_feed_source;
  out["learning_cycles"] = comparison.learning_cycles;
  out["in_cut_fraction"] = trial::kJudgedInCutFraction;
  out["rows"] = nlohmann::json::array();
  for (const trial::StrategyRow& row : comparison.rows) out["rows"].push_back(row_json(row));
  out["learning"] = nlohmann::json::array();
  for (const trial::LoopCycle& c : comparison.learning) {
    out["learning"].push_back({{"cycle", c.cycle},
                               {"plan_status", planner::to_string(c.plan_status)},
                               {"planned_cycle_time_s", c.planned_cycle_time_s},
                               {"simulated_cycle_time_s", c.simulated_cycle_time_s},
                               {"held", c.comparison.held},
                               {"held_rms_error_percent", c.comparison.rms_error_percent},
                               {"max_overshoot_percent", c.comparison.max_overshoot_percent},
                               {"infeasible_revolutions", c.infeasible.revolutions},
                               {"infeasible_largest_peak_n", c.infeasible.largest_peak_n}});
  }
  out["notes"] = context.notes;
  return out;
}

}  // namespace feedplan::cli
