#pragma once
// The moves of a program of several tools (gcode::ReaderOptions::tool_changes), grouped by the tool that
// makes them: each run is a stretch between tool changes, with its end mill from a tool library (--tools)
// by T number, or the one tool of a program of one tool (--tool). `feedplan optimize` plans each run and
// `feedplan simulate` runs each on the virtual machine, both on the stock the runs before it left.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/tool.hpp"

namespace feedplan::cli {

//! The moves [first, end) of the program one tool makes, between its tool changes.
struct ToolRun {
  std::size_t first = 0;     //!< index of its first move
  std::size_t end = 0;       //!< one past its last move
  int number = -1;           //!< T number (−1: the moves before any tool change)
  geometry::Tool tool;       //!< its end mill (unset on a run of rapids only: no tool needed)
  double spindle_rpm = 0.0;  //!< the one speed its feeds are planned for (optimize), rev/min; 0: not set
};

//! The program's moves by the tool that makes them (WrittenMove::tool), in program order, each with its end
//! mill: from `library` by T number, else `tool` for a program of one tool. A run of rapids only needs no
//! tool. Problems, named after `tools_flag` ("--tools") with `tools_path`: a program with feed moves of
//! more than one tool and no library ("--tools is required: the program changes tools (T1 from line 8, …)"),
//! a T number the library does not have. Returns the runs found (tools unset where a problem was found).
std::vector<ToolRun> tool_runs(const geometry::Program& program, const std::vector<gcode::WrittenMove>& written,
                               const std::optional<geometry::Tool>& tool, const std::map<int, geometry::Tool>& library,
                               const std::string& tools_path, std::vector<InputProblem>& problems);

//! True when `run` has no feed moves (a G28 before the first tool change): nothing is cut.
bool rapids_only(const geometry::Program& program, const ToolRun& run);

//! True when every feed move of `run` keeps the F it was written with (a drilling cycle's,
//! WrittenMove::fixed_feed): a drill, not a milling cutter.
bool feeds_kept(const geometry::Program& program, const std::vector<gcode::WrittenMove>& written, const ToolRun& run);

//! The moves [run.first, run.end) as a path of their own.
geometry::ToolPath run_path(const geometry::Program& program, const ToolRun& run);

//! The moves of `run` as a program of their own: its blocks, the program's coordinate resolution and source
//! name, and the dwell at the program's end when it is the last run.
geometry::Program run_program(const geometry::Program& program, const ToolRun& run);

//! "T2", or "moves" for the moves before any tool change.
std::string run_name(const ToolRun& run);

//! The reader options for a program of several tools: tool changes anywhere, and cutter compensation by
//! the diameters of `library` (or `tool`'s for every tool of a program of one tool).
gcode::ReaderOptions tool_change_reader(const std::map<int, geometry::Tool>& library,
                                        const std::optional<geometry::Tool>& tool);

}  // namespace feedplan::cli
