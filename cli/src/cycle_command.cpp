#include "cycle_command.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "number_flag.hpp"
#include "output_path.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/geometry/engagement.hpp"
#include "feedplan/geometry/engagement_csv.hpp"
#include "feedplan/geometry/engagement_summary.hpp"

namespace feedplan::cli {

void add_cycle_command(CLI::App& app, CycleOptions& options) {
  CLI::App* cmd = app.add_subcommand("cycle", "Generate a canned cycle from its spec and profile the cutter engagement");
  cmd->add_option("spec", options.spec_path, "Cycle spec (YAML), e.g. samples/trochoid.yaml")->required();
  add_number_flag(cmd, "--ds", options.ds_mm, "Engagement sample spacing along the path, mm (default 0.05)");
  cmd->add_option("--engagement", options.engagement_path, "Write the engagement profile as CSV to this file");
  cmd->add_flag("--json", options.json, "Print the summary as JSON");
}

int run_cycle_command(const CycleOptions& options) {
  std::vector<InputProblem> path_problems;
  check_outputs({{"SPEC", options.spec_path}}, {{"--engagement", options.engagement_path}}, path_problems);
  if (!path_problems.empty()) throw InputError(std::move(path_problems));
  const cycles::CycleSpec spec = cycles::load_cycle_spec(options.spec_path);
  const double tool_radius_mm = spec.tool.radius_mm();
  if (!(options.ds_mm >= 0.001 && options.ds_mm <= tool_radius_mm)) {
    std::ostringstream message;
    message << "= " << options.ds_mm << ": must be in [0.001, " << tool_radius_mm
            << "] mm (at least 1 µm, at most the tool radius)";
    throw InputError("--ds", message.str());
  }
  const cycles::Cycle cycle = cycles::generate(spec);

  const auto started = std::chrono::steady_clock::now();
  const auto profile = geometry::compute_engagement(cycle.path, cycle.stock, tool_radius_mm, {.ds_mm = options.ds_mm});
  const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const auto summary = geometry::summarize(cycle.path, profile);

  if (!options.engagement_path.empty()) {
    const std::string error = write_file_atomically(options.engagement_path, geometry::engagement_csv(profile));
    if (!error.empty()) {
      std::cerr << "feedplan: failed: " << error << "\n";
      return 1;
    }
  }

  if (options.json) {
    nlohmann::json out;
    out["spec"] = options.spec_path;
    out["cycle"] = spec.cycle;
    out["tool"] = {{"name", spec.tool.name}, {"diameter_mm", spec.tool.diameter_mm}, {"flutes", spec.tool.flutes}};
    out["ds_mm"] = options.ds_mm;
    out["length_mm"] = summary.length_mm;
    out["cutting_length_mm"] = summary.cutting_length_mm;
    out["air_length_mm"] = summary.air_length_mm;
    out["rapid_length_mm"] = summary.rapid_length_mm;
    out["samples"] = summary.samples;
    out["engagement_max_deg"] = rad_to_deg(summary.engagement_max_rad);
    out["engagement_time_s"] = elapsed_s;
    out["parts"] = nlohmann::json::array();
    for (const auto& part : summary.parts) {
      out["parts"].push_back({{"name", part.name},
                              {"length_mm", part.length_mm},
                              {"cutting_length_mm", part.cutting_length_mm},
                              {"cutting_samples", part.cutting_samples},
                              {"engagement_min_deg", rad_to_deg(part.engagement_min_rad)},
                              {"engagement_max_deg", rad_to_deg(part.engagement_max_rad)},
                              {"engagement_mean_deg", rad_to_deg(part.engagement_mean_rad)},
                              {"chip_factor_max", part.chip_factor_max}});
    }
    out["notes"] = cycle.notes;
    out["warnings"] = profile.warnings;
    if (!options.engagement_path.empty()) out["engagement_csv"] = options.engagement_path;
    std::cout << out.dump(2) << "\n";
  } else {
    std::printf("%s: %s cycle, tool %s (D%.3g mm, %d flutes)\n", options.spec_path.c_str(), spec.cycle.c_str(),
                spec.tool.name.empty() ? "-" : spec.tool.name.c_str(), spec.tool.diameter_mm, spec.tool.flutes);
    std::printf("path %.2f mm: cutting %.2f mm, air feed %.2f mm, rapid %.2f mm\n", summary.length_mm,
                summary.cutting_length_mm, summary.air_length_mm, summary.rapid_length_mm);
    std::printf("engagement: %d samples at ds %.3g mm in %.3f s, max %.2f deg\n", summary.samples, options.ds_mm,
                elapsed_s, rad_to_deg(summary.engagement_max_rad));
    std::printf("%-28s %10s %8s %8s %8s %8s\n", "part", "cut_mm", "min_deg", "max_deg", "mean_deg", "k_max");
    for (const auto& part : summary.parts) {
      if (part.cutting_samples == 0) {
        std::printf("%-28s %10.2f %8s %8s %8s %8s\n", part.name.c_str(), part.cutting_length_mm, "-", "-", "-", "-");
        continue;
      }
      std::printf("%-28s %10.2f %8.2f %8.2f %8.2f %8.3f\n", part.name.c_str(), part.cutting_length_mm,
                  rad_to_deg(part.engagement_min_rad), rad_to_deg(part.engagement_max_rad),
                  rad_to_deg(part.engagement_mean_rad), part.chip_factor_max);
    }
    for (const auto& note : cycle.notes) std::printf("note: %s\n", note.c_str());
    if (!options.engagement_path.empty()) std::printf("engagement profile written to %s\n", options.engagement_path.c_str());
  }
  for (const auto& warning : profile.warnings) std::cerr << "feedplan: warning: " << warning << "\n";
  return 0;
}

}  // namespace feedplan::cli
