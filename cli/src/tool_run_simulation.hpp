#pragma once
// A program of several tools on the virtual machine (`feedplan simulate PROGRAM --tools TOOLS.yaml`): each
// tool's run of moves (tool_runs.hpp) is simulated with that tool on the stock the runs before it left
// (geometry::after_cutting), from rest at its tool change, and the runs are put end to end on one clock.
//
// The milling simulation computes the forces of a cutter's flutes on its side, from the chip its XY feed
// cuts; a drill's forces come from its point, which it does not model (a plunge has no XY feed). So a run of
// drilling cycles (every feed move WrittenMove::fixed_feed) is not simulated: its holes are taken out of the
// stock and its time is the motion model's (sim::plan_motion), with no force recorded. A run of rapids only
// (a G28 before the first tool change) needs no tool and is timed the same way.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tool_runs.hpp"
#include "feedplan/force_log/force_log_sink.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::cli {

//! What a tool run is on the virtual machine.
enum class ToolRunKind {
  kMilling,   //!< simulated: forces tooth by tooth
  kDrilling,  //!< drilling cycles: cut from the stock, timed by the motion model, no forces
  kRapids,    //!< rapids only: timed by the motion model
};

//! One tool run of the program on the virtual machine.
struct SimulatedToolRun {
  ToolRun run;                   //!< its moves and tool
  ToolRunKind kind = ToolRunKind::kMilling;
  int first_line = 0;            //!< text line of its first move
  int last_line = 0;             //!< text line of its last move
  double start_s = 0.0;          //!< when it starts on the program's clock, s
  double duration_s = 0.0;       //!< its time, from rest at its start to rest at its end, s
  sim::SimulationSummary summary;  //!< the simulation's totals (kMilling; otherwise only the times)
  std::size_t revolutions = 0;   //!< spindle revolutions simulated
};

//! The whole program on the virtual machine.
struct ToolRunSimulation {
  std::vector<SimulatedToolRun> runs;  //!< in program order
  sim::SimulationSummary summary;      //!< the program's totals (step_s: the shortest of the runs')
  //! Every run's revolutions on the program's clock, numbered through, with the name of the run's tool
  //! (run_name) in `revolution_tools`.
  std::vector<force_log::RevolutionPeak> revolutions;
  std::vector<std::string> revolution_tools;
  std::vector<std::string> warnings;   //!< the runs' warnings, each prefixed with its tool ("T2: ")
};

//! What every run shares: the request (material, limits, sensors, options, log metadata; its tool,
//! program, stock, sink and progress are set per run) and the machine file, if any, to put in with each tool.
struct ToolRunRequest {
  sim::SimulationRequest base;
  std::optional<sim::MachineFile> machine;
  std::string tools_path;  //!< --tools, for messages
};

//! Checks every milling run before anything runs: the machine file's runout against each tool's flutes
//! (sim::apply_machine, as for one tool) and sim::validate of its request on `stock`. Returns the problems,
//! each message naming the tool ("… (T2 of --tools tools.yaml)"); empty when every run can be simulated.
std::vector<InputProblem> check_tool_runs(const ToolRunRequest& request, const geometry::Program& program,
                                          const std::vector<gcode::WrittenMove>& written,
                                          const std::vector<ToolRun>& runs, const geometry::Stock& stock);

//! The log's metadata lines for the runs: `tool_run_1: T1, lines 8–12, milling: SC EM D10 Z4 (D10 mm, 4 flutes,
//! helix 30 deg), t_s 0–4.2`, one per run, with the times of the motion model.
std::vector<std::pair<std::string, std::string>> tool_run_metadata(const ToolRunRequest& request,
                                                                   const geometry::Program& program,
                                                                   const std::vector<gcode::WrittenMove>& written,
                                                                   const std::vector<ToolRun>& runs);

//! Runs the program, tool run by tool run, on `stock`: the force log of all runs to `log` (one header, rows on
//! the program's clock), `progress` with the share of the runs done. Needs runs that passed check_tool_runs.
ToolRunSimulation simulate_tool_runs(const ToolRunRequest& request, const geometry::Program& program,
                                     const std::vector<gcode::WrittenMove>& written, const std::vector<ToolRun>& runs,
                                     geometry::Stock stock, force_log::ForceLogSink& log,
                                     const std::function<void(double)>& progress);

}  // namespace feedplan::cli
