#include "tool_run_simulation.hpp"

#include <algorithm>

#include "joined_force_log.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/sim/motion_profile.hpp"

namespace feedplan::cli {
namespace {

ToolRunKind kind_of(const geometry::Program& program, const std::vector<gcode::WrittenMove>& written, const ToolRun& run) {
  if (rapids_only(program, run)) return ToolRunKind::kRapids;
  if (feeds_kept(program, written, run)) return ToolRunKind::kDrilling;
  return ToolRunKind::kMilling;
}

const char* kind_text(ToolRunKind kind) {
  switch (kind) {
    case ToolRunKind::kMilling: return "milling";
    case ToolRunKind::kDrilling: return "drilling cycles";
    case ToolRunKind::kRapids: return "rapids only";
  }
  return "";
}

// " (T2 of --tools tools.yaml)": which tool a problem of a run's request is about.
std::string of_tool(const ToolRunRequest& request, const ToolRun& run) {
  return " (" + run_name(run) + " of --tools " + request.tools_path + ")";
}

// The request for one milling run on `stock`, the machine file put in with its tool; the problems that
// needs the tool (runout per flute) are added to `problems`, named after the tool.
sim::SimulationRequest run_request(const ToolRunRequest& request, const geometry::Program& program, const ToolRun& run,
                                   const geometry::Stock& stock, std::vector<InputProblem>& problems) {
  sim::SimulationRequest r = request.base;
  r.tool = run.tool;
  r.program = run_program(program, run);
  r.stock = stock;
  if (request.machine) {
    for (InputProblem& p : sim::apply_machine(*request.machine, r)) {
      p.message += of_tool(request, run);
      problems.push_back(std::move(p));
    }
  }
  return r;
}

// A run the milling simulation does not take (drilling, rapids): its time by the motion model.
sim::SimulationSummary motion_only(const ToolRunRequest& request, const geometry::Program& part) {
  const sim::MotionProfile motion = sim::plan_motion(part, request.base.machine);
  sim::SimulationSummary s;
  s.cycle_time_s = motion.duration_s();
  s.cutting_time_s = motion.time_in_cut_s();
  s.air_time_s = motion.time_in_air_s();
  return s;
}

// The program's totals with one more run's.
void add_to_summary(const sim::SimulationSummary& run, sim::SimulationSummary& whole) {
  const double contact_s = whole.time_in_contact_s + run.time_in_contact_s;
  if (contact_s > 0.0) {
    whole.mean_force_in_contact_n = (whole.mean_force_in_contact_n * whole.time_in_contact_s +
                                     run.mean_force_in_contact_n * run.time_in_contact_s) / contact_s;
  }
  whole.cycle_time_s += run.cycle_time_s;
  whole.cutting_time_s += run.cutting_time_s;
  whole.air_time_s += run.air_time_s;
  whole.time_in_contact_s = contact_s;
  whole.max_revolution_peak_n = std::max(whole.max_revolution_peak_n, run.max_revolution_peak_n);
  whole.max_force_z_n = std::max(whole.max_force_z_n, run.max_force_z_n);
  whole.steps += run.steps;
  whole.log_rows += run.log_rows;
  if (run.step_s > 0.0) whole.step_s = whole.step_s > 0.0 ? std::min(whole.step_s, run.step_s) : run.step_s;
  whole.stock_layers = std::max(whole.stock_layers, run.stock_layers);
  whole.layer_thickness_mm = std::max(whole.layer_thickness_mm, run.layer_thickness_mm);
  whole.engagement_bands += run.engagement_bands;
  whole.engagement_samples += run.engagement_samples;
  whole.recut_tolerance_mm = std::max(whole.recut_tolerance_mm, run.recut_tolerance_mm);
}

// The run's revolutions on the program's clock, numbered on from the ones before.
void add_revolutions(const std::vector<force_log::RevolutionPeak>& run_revolutions, const SimulatedToolRun& run,
                     ToolRunSimulation& out) {
  for (force_log::RevolutionPeak rev : run_revolutions) {
    rev.revolution = static_cast<long>(out.revolutions.size());
    rev.t_start_s += run.start_s;
    rev.t_end_s += run.start_s;
    rev.t_peak_s += run.start_s;
    out.revolutions.push_back(rev);
    out.revolution_tools.push_back(run_name(run.run));
  }
}

// The header of a log no milling run gave one to (a program of drills and rapids): no rows follow.
force_log::ForceLog header_without_runs(const sim::SimulationRequest& base) {
  force_log::ForceLog header;
  header.has_currents = base.sensors.servo_current.enabled;
  header.metadata = {{"source", "feedplan simulate (virtual machine, mechanistic forces)"},
                     {"sample_rate_hz", six_digit_number_text(base.options.log_rate_hz)}};
  for (const auto& entry : base.log_metadata) header.metadata.push_back(entry);
  return header;
}

}  // namespace

std::vector<InputProblem> check_tool_runs(const ToolRunRequest& request, const geometry::Program& program,
                                          const std::vector<gcode::WrittenMove>& written,
                                          const std::vector<ToolRun>& runs, const geometry::Stock& stock) {
  std::vector<InputProblem> problems;
  for (const ToolRun& run : runs) {
    if (kind_of(program, written, run) != ToolRunKind::kMilling) continue;
    std::vector<InputProblem> machine_problems;
    const sim::SimulationRequest r = run_request(request, program, run, stock, machine_problems);
    if (!machine_problems.empty()) {
      problems.insert(problems.end(), machine_problems.begin(), machine_problems.end());
      continue;
    }
    for (InputProblem& p : sim::validate(r)) {
      p.message += of_tool(request, run);
      problems.push_back(std::move(p));
    }
  }
  return problems;
}

std::vector<std::pair<std::string, std::string>> tool_run_metadata(const ToolRunRequest& request,
                                                                   const geometry::Program& program,
                                                                   const std::vector<gcode::WrittenMove>& written,
                                                                   const std::vector<ToolRun>& runs) {
  std::vector<std::pair<std::string, std::string>> lines;
  double start_s = 0.0;
  for (const ToolRun& run : runs) {
    const ToolRunKind kind = kind_of(program, written, run);
    const double duration_s = motion_only(request, run_program(program, run)).cycle_time_s;
    std::string text = run_name(run) + ", lines " + std::to_string(written[run.first].line) + "–" +
                       std::to_string(written[run.end - 1].line) + ", " + kind_text(kind);
    if (kind != ToolRunKind::kRapids) {
      text += ": " + run.tool.name + " (D" + shortest_number_text(run.tool.diameter_mm) + " mm, " +
              std::to_string(run.tool.flutes) + " flutes, helix " + shortest_number_text(run.tool.helix_deg) + " deg)";
    }
    text += ", t_s " + six_digit_number_text(start_s) + "–" + six_digit_number_text(start_s + duration_s);
    if (kind != ToolRunKind::kMilling) text += ", no forces recorded";
    lines.push_back({"tool_run_" + std::to_string(lines.size() + 1), text});
    start_s += duration_s;
  }
  return lines;
}

ToolRunSimulation simulate_tool_runs(const ToolRunRequest& request, const geometry::Program& program,
                                     const std::vector<gcode::WrittenMove>& written, const std::vector<ToolRun>& runs,
                                     geometry::Stock stock, force_log::ForceLogSink& log,
                                     const std::function<void(double)>& progress) {
  ToolRunSimulation out;
  JoinedForceLog joined(log);
  const auto milling_runs = static_cast<double>(std::count_if(runs.begin(), runs.end(), [&](const ToolRun& run) {
    return kind_of(program, written, run) == ToolRunKind::kMilling;
  }));
  double milling_done = 0.0;
  for (const ToolRun& run : runs) {
    SimulatedToolRun done{run, kind_of(program, written, run), written[run.first].line, written[run.end - 1].line,
                          out.summary.cycle_time_s, 0.0, {}, 0};
    if (done.kind == ToolRunKind::kMilling) {
      std::vector<InputProblem> problems;
      sim::SimulationRequest r = run_request(request, program, run, stock, problems);
      if (!problems.empty()) throw InputError(std::move(problems));  // check_tool_runs found none
      joined.start_run_at(done.start_s);
      r.log_sink = &joined;
      if (progress) {
        r.progress = [&progress, milling_done, milling_runs](double f) { progress((milling_done + f) / milling_runs); };
      }
      const sim::SimulationResult result = sim::simulate(r);
      milling_done += 1.0;
      done.summary = result.summary;
      done.revolutions = result.revolutions.size();
      add_revolutions(result.revolutions, done, out);
      for (const std::string& warning : result.warnings) out.warnings.push_back(run_name(run) + ": " + warning);
    } else {
      done.summary = motion_only(request, run_program(program, run));
    }
    done.duration_s = done.summary.cycle_time_s;
    if (done.kind != ToolRunKind::kRapids) stock = geometry::after_cutting(stock, run_path(program, run), run.tool.radius_mm());
    add_to_summary(done.summary, out.summary);
    out.runs.push_back(std::move(done));
  }
  if (!joined.begun()) log.begin(header_without_runs(request.base));
  if (progress) progress(1.0);
  return out;
}

}  // namespace feedplan::cli
