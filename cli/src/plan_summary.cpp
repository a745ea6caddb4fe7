#include "plan_summary.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>

#include "plan_baselines.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/planner/peak_comparison.hpp"

namespace feedplan::cli {
namespace {

namespace mdb = model_db;

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

// The caution part of the model-match line.
std::string caution_text(const PlanModel& model) {
  const double delta = model.chosen.borrowing.borrowed_fraction;
  const std::string r = shortest_number_text(model.relative_uncertainty);
  if (model.relative_uncertainty > 0.0) {
    const std::string why = model.uncertainty_requested ? " as asked (--cautious)"
                                                        : " from the borrowing; --cautious R to change";
    return "planned cautiously: F̂ + " + shortest_number_text(kBorrowedModelSigmas) + "σ held at the target, r = " + r +
           " (the bound ≥ the model's force + " + fixed(100.0 * kBorrowedModelSigmas * model.relative_uncertainty, 0) +
           " %)" + why;
  }
  if (delta > 0.0) {
    return "planned on the model alone as asked (--cautious 0): the true force may be " +
           fixed(100.0 * delta, 0) + " % above the prediction";
  }
  return "planned on the model alone";
}

std::string model_match_line(const PlanModel& model) {
  return mdb::describe(model.chosen.borrowing) + " — " + caution_text(model);
}

// "  vs F560, the spec's feed_mm_per_min: 38.32 s on the virtual machine: 20.3 % saved" (or "% more time").
void print_saving(const char* label, double feed, const std::string& what, double baseline_s, double planned_s) {
  const double saved = time_saved_percent(baseline_s, planned_s);
  std::printf("  vs F%.0f, %s: %.2f s%s: %.1f %% %s\n", feed, label, baseline_s, what.c_str(), std::abs(saved),
              saved >= 0.0 ? "saved" : "MORE time (the plan is slower)");
}

void print_predicted_baselines(const planner::PlanSummary& s, const PlanBaselines& b) {
  std::printf("cycle time: planned %.2f s (cutting %.2f s)\n", s.cycle_time_s, s.cutting_time_s);
  if (b.spec_feed) {
    print_saving("the spec's feed_mm_per_min", b.spec_feed->feed_mm_per_min,
                 " predicted, peak " + fixed(b.spec_feed->peak_force_n, 1) + " N by the model", b.spec_feed->cycle_time_s,
                 s.cycle_time_s);
  } else {
    std::printf("  (the spec gives no feed_mm_per_min: add the constant feed you would program to see the time saved "
                "against it)\n");
  }
  print_saving(("the constant feed with the plan's predicted peak " + fixed(s.max_predicted_force_n, 1) + " N").c_str(),
               s.baseline.feed_mm_per_min, " predicted by the model", s.baseline.cycle_time_s, s.cycle_time_s);
}

// "  blocks: F levels 2 % apart, each at least 0.006 s: +1.0 % time against every acceleration ramp written out
// (30.64 s, --feed-step 0)".
void print_block_cost(const planner::PlanOptions& options, const planner::PlanSummary& s, double ramps_written_out_s) {
  std::printf("  blocks: F levels %s %% apart, each at least %s s: %+.1f %% time against every acceleration ramp "
              "written out (%.2f s, --feed-step 0)\n",
              shortest_number_text(100.0 * options.feed_step).c_str(),
              shortest_number_text(options.min_block_duration_s).c_str(),
              100.0 * (s.cycle_time_s - ramps_written_out_s) / ramps_written_out_s, ramps_written_out_s);
}

void print_simulated_baselines(const trial::PlanCheck& check, const PlanBaselines& b) {
  if (b.spec_feed_simulated) {
    const trial::ConstantFeedRun& r = *b.spec_feed_simulated;
    print_saving("the spec's feed_mm_per_min", r.feed_mm_per_min,
                 " on the virtual machine, largest peak " + fixed(r.max_peak_n, 1) + " N", r.cycle_time_s,
                 check.cycle_time_s);
  }
  if (b.equal_simulated_peak) {
    const trial::EqualPeakFeed& e = *b.equal_simulated_peak;
    print_saving("the constant feed with the plan's simulated largest peak", e.run.feed_mm_per_min,
                 " on the virtual machine, largest peak " + fixed(e.run.max_peak_n, 1) + " N", e.run.cycle_time_s,
                 check.cycle_time_s);
    std::printf("    (%s)\n", e.method.c_str());
  }
}

// The virtual machine's part: the largest peak anywhere first, then the times and the comparison.
void print_simulation(const trial::PlanCheck& check, const PlanBaselines& baselines, double target_force_n) {
  const std::string comparison = planner::describe(check.comparison, target_force_n);
  const auto first_line_end = comparison.find('\n') + 1;
  std::printf("virtual machine: %s", comparison.substr(0, first_line_end).c_str());
  std::printf("virtual machine: cycle time %.2f s\n", check.cycle_time_s);
  print_simulated_baselines(check, baselines);
  std::printf("%s", comparison.substr(first_line_end).c_str());
}

nlohmann::json saving_json(const std::string& label, double feed, double cycle_time_s, double planned_s) {
  return {{"label", label}, {"feed_mm_per_min", feed}, {"cycle_time_s", cycle_time_s},
          {"time_saved_percent", time_saved_percent(cycle_time_s, planned_s)}};
}

nlohmann::json model_match_json(const PlanModel& model) {
  const mdb::ModelBorrowing& b = model.chosen.borrowing;
  nlohmann::json differences = nlohmann::json::array();
  for (const mdb::ModelDifference& d : b.differences) {
    differences.push_back({{"property", d.property}, {"wanted", d.wanted}, {"used", d.used}, {"relative", d.relative}});
  }
  return {{"status", mdb::to_string(b.status)},
          {"differences", differences},
          {"borrowed_fraction", b.borrowed_fraction},
          {"relative_uncertainty", model.relative_uncertainty},
          {"sigmas", model.relative_uncertainty > 0.0 ? kBorrowedModelSigmas : 0.0},
          {"uncertainty_from", model.uncertainty_requested ? "--cautious" : "borrowing"}};
}

nlohmann::json baselines_json(const planner::PlanSummary& s, const PlanOutputs& outputs) {
  const PlanBaselines& b = outputs.baselines;
  nlohmann::json out;
  if (b.spec_feed) {
    out["spec_feed"] = saving_json("the spec's feed_mm_per_min, predicted", b.spec_feed->feed_mm_per_min,
                                   b.spec_feed->cycle_time_s, s.cycle_time_s);
    out["spec_feed"]["peak_force_n"] = b.spec_feed->peak_force_n;
  }
  out["equal_predicted_peak"] = saving_json("the constant feed with the plan's predicted peak, predicted",
                                            s.baseline.feed_mm_per_min, s.baseline.cycle_time_s, s.cycle_time_s);
  out["equal_predicted_peak"]["peak_force_n"] = s.baseline.peak_force_n;
  if (!outputs.check) return out;
  const double vm_s = outputs.check->cycle_time_s;
  if (b.spec_feed_simulated) {
    out["spec_feed_simulated"] = saving_json("the spec's feed_mm_per_min, on the virtual machine",
                                             b.spec_feed_simulated->feed_mm_per_min, b.spec_feed_simulated->cycle_time_s, vm_s);
    out["spec_feed_simulated"]["max_peak_n"] = b.spec_feed_simulated->max_peak_n;
  }
  if (b.equal_simulated_peak) {
    const trial::EqualPeakFeed& e = *b.equal_simulated_peak;
    nlohmann::json& j = out["equal_simulated_peak"];
    j = saving_json("the constant feed with the plan's simulated largest peak, on the virtual machine",
                    e.run.feed_mm_per_min, e.run.cycle_time_s, vm_s);
    j["max_peak_n"] = e.run.max_peak_n;
    j["converged"] = e.converged;
    j["method"] = e.method;
    j["runs"] = nlohmann::json::array();
    for (const auto& r : e.runs) j["runs"].push_back({{"feed_mm_per_min", r.feed_mm_per_min}, {"max_peak_n", r.max_peak_n}, {"cycle_time_s", r.cycle_time_s}});
  }
  return out;
}

nlohmann::json largest_peak_json(const planner::PeakComparison& c) {
  if (c.largest_peak < 0) return nullptr;
  const planner::RevolutionComparison& r = c.revolutions[static_cast<std::size_t>(c.largest_peak)];
  return {{"peak_n", r.revolution.peak_n},
          {"error_percent", r.error_percent},
          {"s_mm", 0.5 * (r.revolution.s_start_mm + r.revolution.s_end_mm)},
          {"x_mm", r.position.x_mm},
          {"y_mm", r.position.y_mm},
          {"z_mm", r.position.z_mm},
          {"in_cut", r.in_cut}};
}

nlohmann::json simulation_json(const trial::PlanCheck& check) {
  const auto& c = check.comparison;
  return {{"largest_peak", largest_peak_json(c)},
          {"cycle_time_s", check.cycle_time_s},
          {"max_peak_n", check.max_peak_n},
          {"revolutions", c.revolutions.size()},
          {"in_cut", c.in_cut},
          {"held", c.held},
          {"steady", c.steady},
          {"steady_max_abs_error_percent", c.steady_max_abs_error_percent},
          {"steady_rms_error_percent", c.steady_rms_error_percent},
          {"max_abs_error_percent", c.max_abs_error_percent},
          {"rms_error_percent", c.rms_error_percent},
          {"max_overshoot_percent", c.max_overshoot_percent},
          {"warnings", check.warnings}};
}

}  // namespace

std::string plan_status_text(const planner::PlanResult& result, const PlanModel& model) {
  std::string text = planner::to_string(result.status) + ", model " + mdb::to_string(model.chosen.borrowing.status);
  if (model.relative_uncertainty > 0.0) {
    text += " (planned cautiously, r = " + shortest_number_text(model.relative_uncertainty) + ")";
  } else if (model.chosen.borrowing.status == mdb::ModelMatchStatus::kBorrowed) {
    text += " (NOT planned cautiously: --cautious 0)";
  }
  return text;
}

void print_plan_json(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                     const PlannedCycle& planned, const PlanOutputs& outputs) {
  const planner::PlanResult& result = planned.result;
  const planner::PlanSummary& s = result.summary;
  const mdb::ModelRecord& record = model.chosen.record;
  nlohmann::json out;
  out["status"] = planner::to_string(result.status);
  out["model_match"] = mdb::to_string(model.chosen.borrowing.status);
  out["messages"] = result.messages;
  out["spec"] = o.spec_path;
  out["model"] = {{"id", record.id}, {"version", record.version}, {"tool", record.tool_name},
                  {"material", record.material_name}, {"match", model.chosen.match},
                  {"explanation", model.chosen.explanation}, {"match_status", model_match_json(model)}};
  out["model_kind"] = model.mechanistic ? "mechanistic" : "response_surface";
  out["model_kind_reason"] = model.kind_reason;
  if (model.mechanistic) out["mechanistic_model"] = {{"id", model.mechanistic->id}, {"version", model.mechanistic->version}};
  out["target_force_n"] = in.target_force_n;
  out["blocks"] = result.blocks.size();
  out["samples"] = result.samples.size();
  out["feed_min_mm_per_min"] = s.min_feed_mm_per_min;
  out["feed_max_mm_per_min"] = s.max_feed_mm_per_min;
  out["cycle_time_s"] = s.cycle_time_s;
  out["cutting_time_s"] = s.cutting_time_s;
  if (planned.ramps_written_out_s) {
    out["controller_friendly"] = {{"feed_step", planned.settings.options.feed_step},
                                  {"min_block_duration_s", planned.settings.options.min_block_duration_s},
                                  {"ramps_written_out_cycle_time_s", *planned.ramps_written_out_s}};
  }
  out["max_predicted_force_n"] = s.max_predicted_force_n;
  out["baselines"] = baselines_json(s, outputs);
  out["engagement_time_s"] = planned.analyse_s;
  out["plan_time_s"] = planned.plan_s;
  out["written"] = outputs.written;
  if (outputs.check) out["virtual_machine"] = simulation_json(*outputs.check);
  std::cout << out.dump(2) << "\n";
}

void print_plan_text(const PlanCommandOptions& o, const PlanInputs& in, const PlanModel& model,
                     const PlannedCycle& planned, const PlanOutputs& outputs) {
  const cycles::CycleSpec& spec = in.spec;
  const planner::PlanResult& result = planned.result;
  const planner::PlanSummary& s = result.summary;
  const mdb::ModelRecord& record = model.chosen.record;
  std::printf("%s: %s, tool %s, %s, target %s N\n", o.spec_path.c_str(), spec.cycle.c_str(), spec.tool.name.c_str(),
              spec.material.c_str(), shortest_number_text(in.target_force_n).c_str());
  std::printf("model: id %lld v%d (%s in %s) — %s\n", static_cast<long long>(record.id), record.version,
              record.tool_name.c_str(), record.material_name.c_str(), model.chosen.explanation.c_str());
  std::printf("model kind: %s\n", model.kind_reason.c_str());
  std::printf("status: %s\n", plan_status_text(result, model).c_str());
  std::printf("model match: %s\n", model_match_line(model).c_str());
  std::printf("plan: %zu samples, %zu blocks, F %.0f–%.0f mm/min, predicted peak %.1f N (engagement %.3f s, plan %.3f s)\n",
              result.samples.size(), result.blocks.size(), s.min_feed_mm_per_min, s.max_feed_mm_per_min,
              s.max_predicted_force_n, planned.analyse_s, planned.plan_s);
  print_predicted_baselines(s, outputs.baselines);
  if (planned.ramps_written_out_s) print_block_cost(planned.settings.options, s, *planned.ramps_written_out_s);
  if (outputs.check) print_simulation(*outputs.check, outputs.baselines, in.target_force_n);
  for (const std::string& path : outputs.written) std::printf("wrote %s\n", path.c_str());
}

void print_plan_notes(const planner::PlanResult& result, const PlanOutputs& out) {
  if (out.check) {
    for (const std::string& warning : out.check->warnings) std::cerr << "feedplan: virtual machine: " << warning << "\n";
  }
  for (const std::string& message : result.messages) std::cerr << "feedplan: note: " << message << "\n";
}

}  // namespace feedplan::cli
