#include "tool_runs.hpp"

namespace feedplan::cli {

std::vector<ToolRun> tool_runs(const geometry::Program& program, const std::vector<gcode::WrittenMove>& written,
                               const std::optional<geometry::Tool>& tool, const std::map<int, geometry::Tool>& library,
                               const std::string& tools_path, std::vector<InputProblem>& problems) {
  std::vector<ToolRun> runs;
  for (std::size_t m = 0; m < written.size(); ++m) {
    if (runs.empty() || written[m].tool != runs.back().number) runs.push_back({m, m, written[m].tool, {}, 0.0});
    runs.back().end = m + 1;
  }
  std::map<int, int> first_line;  // T number → the line of its first move
  for (const ToolRun& run : runs) {
    if (!rapids_only(program, run)) first_line.emplace(run.number, written[run.first].line);
  }
  if (library.empty() && first_line.size() > 1) {
    std::string which;
    for (const auto& [number, line] : first_line) {
      if (!which.empty()) which += ", ";
      if (number < 0) {
        which += "no tool";
      } else {
        which += 'T';
        which += std::to_string(number);
      }
      which += " from line " + std::to_string(line);
    }
    problems.push_back({"--tools", "is required: the program changes tools (" + which +
                                       "); give --tools TOOLS.yaml with the end mill of each T number"});
    return runs;
  }
  for (ToolRun& run : runs) {
    if (rapids_only(program, run)) continue;  // no tool needed: nothing is cut
    if (library.empty()) {
      if (tool) run.tool = *tool;
    } else if (const auto it = library.find(run.number); it != library.end()) {
      run.tool = it->second;
    } else {
      std::string known;
      for (const auto& [number, t] : library) known += (known.empty() ? "T" : ", T") + std::to_string(number);
      std::string which(run.number < 0 ? "tool for the moves before any tool change" : "T");
      if (run.number >= 0) which += std::to_string(run.number);
      problems.push_back({"--tools", "= " + tools_path + ": has no " + which + " (line " +
                                         std::to_string(written[run.first].line) + "); it has " + known});
    }
  }
  return runs;
}

bool rapids_only(const geometry::Program& program, const ToolRun& run) {
  for (std::size_t i = run.first; i < run.end; ++i) {
    if (program.path.moves[i].kind != geometry::MoveKind::kRapid) return false;
  }
  return true;
}

bool feeds_kept(const geometry::Program& program, const std::vector<gcode::WrittenMove>& written, const ToolRun& run) {
  for (std::size_t i = run.first; i < run.end; ++i) {
    if (program.path.moves[i].kind != geometry::MoveKind::kRapid && !written[i].fixed_feed) return false;
  }
  return true;
}

geometry::ToolPath run_path(const geometry::Program& program, const ToolRun& run) {
  geometry::ToolPath path;
  path.part_names = program.path.part_names;
  path.moves.assign(program.path.moves.begin() + static_cast<long>(run.first),
                    program.path.moves.begin() + static_cast<long>(run.end));
  return path;
}

geometry::Program run_program(const geometry::Program& program, const ToolRun& run) {
  geometry::Program part;
  part.path = run_path(program, run);
  part.blocks.assign(program.blocks.begin() + static_cast<long>(run.first),
                     program.blocks.begin() + static_cast<long>(run.end));
  if (run.end == program.path.moves.size()) part.dwell_at_end_s = program.dwell_at_end_s;
  part.coordinate_resolution_mm = program.coordinate_resolution_mm;
  part.source_name = program.source_name;
  return part;
}

std::string run_name(const ToolRun& run) {
  if (run.number < 0) return "moves";
  std::string name(1, 'T');
  name += std::to_string(run.number);
  return name;
}

gcode::ReaderOptions tool_change_reader(const std::map<int, geometry::Tool>& library,
                                        const std::optional<geometry::Tool>& tool) {
  gcode::ReaderOptions reader;
  reader.tool_changes = true;
  // Cutter compensation (G41/G42 D<tool>) offsets by the diameters of the tools given.
  for (const auto& [number, t] : library) reader.tool_diameters_mm[number] = t.diameter_mm;
  if (tool) reader.any_tool_diameter_mm = tool->diameter_mm;
  return reader;
}

}  // namespace feedplan::cli
