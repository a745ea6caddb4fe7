#include "target_sweep_summary.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace feedplan::cli {

void print_target_sweep(bool json, const std::string& cycle, const PlanModel& model,
                        const std::vector<planner::TargetSweepRow>& rows) {
  const auto& record = model.chosen.record;
  if (json) {
    nlohmann::json out{{"cycle", cycle},
                       {"model_id", record.id},
                       {"model_version", record.version},
                       {"model_kind", model.mechanistic ? "mechanistic" : "response_surface"},
                       {"model_kind_reason", model.kind_reason},
                       {"targets", nlohmann::json::array()}};
    for (const auto& r : rows) {
      nlohmann::json row{{"target_n", r.target_n},
                         {"status", planner::to_string(r.status)},
                         {"cycle_time_s", r.cycle_time_s},
                         {"max_predicted_force_n", r.max_predicted_force_n}};
      if (r.status == planner::PlanStatus::kTargetNotMet) {
        row["unreachable_samples"] = r.unreachable_samples;
        row["target_needed_n"] = r.target_needed_n;
      }
      out["targets"].push_back(row);
    }
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::printf("%s: cycle time against the target, model %s in %s v%d\n", cycle.c_str(), record.tool_name.c_str(),
              record.material_name.c_str(), record.version);
  std::printf("model kind: %s\n", model.kind_reason.c_str());
  std::printf("%10s  %-15s %12s %14s  %s\n", "target_n", "status", "cycle_time_s", "max_peak_n", "note");
  for (const auto& r : rows) {
    std::printf("%10.1f  %-15s %12.2f %14.1f", r.target_n, planner::to_string(r.status).c_str(), r.cycle_time_s,
                r.max_predicted_force_n);
    if (r.status == planner::PlanStatus::kTargetNotMet) {
      std::printf("  %d samples over the target even at a vanishing feed; met everywhere from %.1f N", r.unreachable_samples,
                  r.target_needed_n);
    }
    std::printf("\n");
  }
}

}  // namespace feedplan::cli
