#include "simulate_command.hpp"

#include "data_path.hpp"
#include "number_flag.hpp"
#include "output_files.hpp"
#include "output_path.hpp"
#include "program_stock.hpp"
#include "progress_bar.hpp"
#include "tool_flag.hpp"
#include "tool_run_simulation.hpp"
#include "tool_runs.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <iostream>
#include <sstream>

#include "feedplan/core/atomic_file.hpp"
#include "feedplan/core/bounded_read.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/gcode/reader.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/sim/cutting_test.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/force_log_file_writer.hpp"
#include "feedplan/sim/force_plot.hpp"
#include "feedplan/sim/force_plot_collector.hpp"
#include "feedplan/sim/machine_file.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::cli {

namespace {

std::vector<double> parse_runout(const std::string& text, std::vector<InputProblem>& problems) {
  std::vector<double> values;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (item.empty() || !end || *end != '\0' || !std::isfinite(value)) {
      problems.push_back({"--runout-mm", "item '" + item + "' is not a finite number (mm per tooth, comma separated)"});
      continue;
    }
    values.push_back(value);
  }
  return values;
}

// What the job runs with: flags, else the spec.
struct SimulateInputs {
  std::optional<cycles::CycleSpec> spec;  // --spec
  geometry::Tool tool;                    // --tool, else the spec's (unset with --tools)
  std::map<int, geometry::Tool> library;  // --tools: the end mill of each T number
  std::string material_name;              // --material, else the spec's
  double rpm = 0.0;                       // --spindle-rpm, else the spec's, rev/min
  std::vector<double> runout;             // --runout-mm, mm per tooth
};

// What runs: its name and what the user should know about it.
struct SimulationJob {
  std::string name;                // the cutting test in words, or the program path
  std::vector<std::string> notes;  // e.g. where the stock came from
};

// A program read with its tool changes: its moves, how each was written, and the tools' runs of moves.
struct ToolProgram {
  geometry::Program program;
  std::vector<gcode::WrittenMove> written;
  std::vector<ToolRun> runs;
};

// The log (and the plot's collector) a run records into, and the run's wall time.
struct LogRecording {
  double wall_s = 0.0;           // wall time of the simulation, s
  std::string log_error;         // why the log could not be written, or empty
  sim::ForcePlotCollector plot;  // the force for --plot
};

// The simulation and its log.
struct SimulationRun {
  sim::SimulationResult result;  // log header, revolutions, summary, warnings
  LogRecording recording;
};

// Every numeric flag against its range (the virtual machine's), named after the flag.
void check_number_flags(const SimulateOptions& o, std::vector<InputProblem>& problems) {
  check_flag(problems, "--spindle-rpm", o.spindle_rpm, {0.0, false}, "rev/min (leave it out to use the spec's)");
  check_flag(problems, "--max-accel", o.max_accel_mm_per_s2, {0.0, false}, "mm/s² (leave it out for the spec's or the default)");
  check_flag(problems, "--rapid", o.rapid_feed_mm_per_min, {0.0, false}, "mm/min (leave it out for the spec's or the default)");
  check_flag(problems, "--max-feed", o.max_feed_mm_per_min, {0.0, false}, "mm/min (leave it out for the spec's or the default)");
  check_flag(problems, "--noise-n", o.noise_n, {0.0, true}, "RMS N");
  check_flag(problems, "--log-rate", o.log_rate_hz, {0.0, false}, "Hz");
  check_flag(problems, "--angle-step", o.angle_step_deg, {0.0, false, 10.0, true}, "deg of spindle rotation per step");
  check_flag(problems, "--layer-mm", o.layer_mm, {0.005, true}, "mm");
  check_flag(problems, "--cut-length-mm", o.cut_length_mm, {0.0, false}, "mm");
  check_flag(problems, "--radial-depth-mm", o.radial_depth_mm, {0.0, false}, "mm");
  check_flag(problems, "--axial-depth-mm", o.axial_depth_mm, {0.0, false}, "mm");
  check_flag(problems, "--feed-mm-per-min", o.feed_mm_per_min, {0.0, false}, "mm/min");
}

// The cutting test's flags: each required with --cutting-test, none without.
void check_cutting_test_flags(const SimulateOptions& o, std::vector<InputProblem>& problems) {
  const std::pair<const char*, const std::optional<double>*> flags[] = {
      {"--radial-depth-mm", &o.radial_depth_mm}, {"--axial-depth-mm", &o.axial_depth_mm}, {"--feed-mm-per-min", &o.feed_mm_per_min}};
  for (const auto& [flag, value] : flags) {
    if (o.cutting_test && !value->has_value()) problems.push_back({flag, "is required with --cutting-test"});
    if (!o.cutting_test && value->has_value()) problems.push_back({flag, "only applies with --cutting-test"});
  }
  if (!o.cutting_test && o.up_milling) problems.push_back({"--up", "only applies with --cutting-test"});
}

// --machine sets the physics the flags --material, --runout-mm and --noise-n would set: giving both is a
// conflict, not a silent precedence (the machine file is the record of what was run).
void check_machine_flags(const SimulateOptions& o, std::vector<InputProblem>& problems) {
  if (o.machine_path.empty()) return;
  const std::string why = "conflicts with --machine " + o.machine_path + ", which sets ";
  if (!o.material_name.empty()) problems.push_back({"--material", why + "the material and its coefficients; give one of them"});
  if (!o.runout_text.empty()) problems.push_back({"--runout-mm", why + "the runout per tooth; give one of them"});
  if (o.noise_n) problems.push_back({"--noise-n", why + "the dynamometer noise; give one of them"});
}

// Where the tool, material, machine and stock come from: flags, else the spec; every flag checked.
SimulateInputs read_simulate_inputs(const SimulateOptions& options) {
  std::vector<InputProblem> problems;
  SimulateInputs in;
  std::optional<cycles::CycleSpec>& spec = in.spec;
  if (!options.spec_path.empty()) spec = cycles::load_cycle_spec(options.spec_path);
  if (options.cutting_test == !options.program_path.empty()) {
    problems.push_back({"simulate", options.cutting_test
                                        ? "give either a PROGRAM or --cutting-test, not both"
                                        : "needs a PROGRAM to run, or --cutting-test for a straight cut"});
  }
  if (!options.tools_path.empty()) {
    if (!options.tool_text.empty()) {
      problems.push_back({"--tool", "conflicts with --tools " + options.tools_path +
                                        ": give --tool for a program of one tool, or --tools TOOLS.yaml with the end "
                                        "mill of each T number"});
    }
    if (options.cutting_test) problems.push_back({"--tools", "only applies to a PROGRAM; the cutting test takes --tool"});
  } else if (!options.tool_text.empty()) {
    in.tool = parse_tool(options.tool_text, problems);
  } else if (spec) {
    in.tool = spec->tool;
  } else {
    problems.push_back({"--tool", "is required (or --spec, or --tools TOOLS.yaml for a program of several tools): e.g. "
                                  "--tool diameter_mm=10,flutes=4,helix_deg=30"});
  }
  check_machine_flags(options, problems);
  in.material_name = options.material_name;
  if (in.material_name.empty() && spec) in.material_name = spec->material;
  if (in.material_name.empty() && options.machine_path.empty()) problems.push_back({"--material", "is required (or a --spec with material:), e.g. --material S50C"});
  in.rpm = options.spindle_rpm.value_or(spec ? spec->spindle_rpm : 0.0);  // 0: the program's S words only
  check_number_flags(options, problems);
  check_cutting_test_flags(options, problems);
  if (!options.runout_text.empty()) in.runout = parse_runout(options.runout_text, problems);
  check_outputs({{"PROGRAM", options.program_path},
                 {"--spec", options.spec_path},
                 {"--stock", options.stock_path},
                 {"--machine", options.machine_path},
                 {"--tools", options.tools_path},
                 {"--materials", options.materials_path.empty() ? bundled_materials_path() : options.materials_path}},
                {{"--log", options.log_path}, {"--peaks", options.peaks_path}, {"--plot", options.plot_path}}, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  if (!options.tools_path.empty()) in.library = cycles::load_tool_library(options.tools_path);
  return in;
}

// Material and machine: the spec's limits, each replaced by its flag when given; sensors and options.
sim::SimulationRequest simulation_request(const SimulateOptions& options, const SimulateInputs& in,
                                          const sim::Material& material) {
  sim::SimulationRequest request;
  request.tool = in.tool;
  request.coefficients = material.coefficients;
  if (in.spec) {
    request.machine = in.spec->machine;
  }
  if (options.max_accel_mm_per_s2) request.machine.max_accel_mm_per_s2 = *options.max_accel_mm_per_s2;
  if (options.rapid_feed_mm_per_min) request.machine.rapid_feed_mm_per_min = *options.rapid_feed_mm_per_min;
  if (options.max_feed_mm_per_min) request.machine.max_feed_mm_per_min = *options.max_feed_mm_per_min;
  request.sensors.dynamometer.noise_n = options.noise_n.value_or(0.0);
  request.sensors.servo_current.enabled = options.currents;
  request.sensors.seed = options.seed;
  request.options.angle_step_deg = options.angle_step_deg;
  request.options.layer_thickness_mm = options.layer_mm;
  request.options.log_rate_hz = options.log_rate_hz;
  request.options.runout_mm = in.runout;
  request.options.default_spindle_rpm = in.rpm;
  return request;
}

// --cutting-test: a straight cut into a block, its program and stock into `request`.
SimulationJob set_cutting_test(const SimulateOptions& options, const SimulateInputs& in, sim::SimulationRequest& request) {
  const double rpm = in.rpm;
  sim::CuttingTest test;
  test.radial_depth_mm = *options.radial_depth_mm;  // given: check_cutting_test_flags
  test.axial_depth_mm = *options.axial_depth_mm;
  test.feed_mm_per_min = *options.feed_mm_per_min;
  test.spindle_rpm = rpm;
  test.cut_length_mm = options.cut_length_mm;
  test.mode = options.up_milling ? sim::MillingMode::kUp : sim::MillingMode::kDown;
  if (auto problems = sim::validate(test, in.tool); !problems.empty()) {
    for (InputProblem& p : problems) {  // cutting_test.radial_depth_mm → --radial-depth-mm: the flag that set it
      p.field = p.field == "cutting_test.spindle_rpm" ? "--spindle-rpm" : "--" + p.field.substr(p.field.find('.') + 1);
      std::replace(p.field.begin(), p.field.end(), '_', '-');
    }
    throw InputError(std::move(problems));
  }
  sim::CuttingTestSetup setup = sim::make_cutting_test(test, in.tool);
  request.program = std::move(setup.program);
  request.stock = std::move(setup.stock);
  std::ostringstream name;
  name << "cutting test: " << (options.up_milling ? "up" : "down") << " milling, a_e " << test.radial_depth_mm
       << " mm, a_p " << test.axial_depth_mm << " mm, F " << test.feed_mm_per_min << " mm/min, S " << rpm << " rpm";
  SimulationJob job;
  job.name = name.str();
  request.log_metadata = {{"cutting_test", job.name},
                          {"radial_depth_mm", six_digit_number_text(test.radial_depth_mm)},
                          {"axial_depth_mm", six_digit_number_text(test.axial_depth_mm)},
                          {"feed_per_tooth_mm", six_digit_number_text(test.feed_mm_per_min / (rpm * in.tool.flutes))}};
  return job;
}

// PROGRAM read with its tool changes and cutter compensation by the tools' diameters, its moves grouped by
// tool: several tools need --tools, each a tool of the file.
ToolProgram read_tool_program(const SimulateOptions& options, const SimulateInputs& in) {
  ToolProgram p;
  std::optional<geometry::Tool> tool;
  if (options.tools_path.empty()) tool = in.tool;
  const gcode::ReaderOptions reader = tool_change_reader(in.library, tool);
  const std::string text = read_input_file(options.program_path, {"a G-code program of a milling job", reader.max_file_bytes,
                                                                  "ReaderOptions::max_file_bytes"});
  p.program = gcode::read_program(text, options.program_path, reader, p.written);
  std::vector<InputProblem> problems;
  p.runs = tool_runs(p.program, p.written, tool, in.library, options.tools_path, problems);
  if (!problems.empty()) throw InputError(std::move(problems));
  return p;
}

// The largest radius of the program's tools, mm.
double largest_tool_radius_mm(const std::vector<ToolRun>& runs) {
  double radius_mm = 0.0;
  for (const ToolRun& run : runs) radius_mm = std::max(radius_mm, run.tool.radius_mm());
  return radius_mm;
}

// The stock from --stock, else the spec, else a block around the program (grown by its largest tool).
geometry::Stock program_stock(const SimulateOptions& options, const SimulateInputs& in, const ToolProgram& p,
                              SimulationJob& job) {
  if (!options.stock_path.empty()) return cycles::load_stock_spec(options.stock_path);
  if (in.spec) {
    job.notes.push_back("stock: the one " + options.spec_path + " implies");
    return cycles::generate(*in.spec).stock;
  }
  job.notes.push_back(kDefaultStockNote);
  return default_stock(p.program, largest_tool_radius_mm(p.runs));
}

// PROGRAM of one tool: the program into `request`, on its stock.
SimulationJob set_program(const SimulateOptions& options, const SimulateInputs& in, sim::SimulationRequest& request) {
  SimulationJob job;
  ToolProgram p = read_tool_program(options, in);
  job.notes = p.program.notes;
  job.name = options.program_path;
  request.log_metadata = {{"program", options.program_path}};
  request.stock = program_stock(options, in, p, job);
  request.program = std::move(p.program);
  return job;
}

// Runs `simulate` with a progress bar on a terminal. The log goes to its file as it is recorded (and to
// the plot's collector with --plot): memory stays bounded however long the program.
void record_log(const SimulateOptions& options, LogRecording& recording,
                const std::function<void(force_log::ForceLogSink&, const std::function<void(double)>&)>& simulate) {
  force_log::ForceLogFileWriter log_file(options.log_path);
  if (!log_file.error().empty()) {
    recording.log_error = log_file.error();
    return;
  }
  std::vector<force_log::ForceLogSink*> sinks = {&log_file};
  if (!options.plot_path.empty()) sinks.push_back(&recording.plot);
  force_log::ForceLogFanOut log(sinks);
  ProgressBar progress("simulating");
  const auto started = std::chrono::steady_clock::now();
  simulate(log, [&progress](double fraction) { progress(fraction); });
  recording.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  recording.log_error = log_file.finish();
}

// Runs the simulation of one tool (record_log).
SimulationRun run_simulation(sim::SimulationRequest request, const SimulateOptions& options) {
  SimulationRun run;
  record_log(options, run.recording, [&](force_log::ForceLogSink& log, const std::function<void(double)>& progress) {
    request.log_sink = &log;
    request.progress = progress;
    run.result = sim::simulate(request);
  });
  return run;
}

// Outputs, each complete or untouched: the log (streamed to a staged file during the run and put in
// place at its end), then --peaks and --plot, staged and put in place together. Returns the first error,
// or empty.
std::string write_simulation_outputs(const SimulateOptions& options, const LogRecording& recording,
                                     const std::vector<force_log::RevolutionPeak>& revolutions,
                                     const std::string& peaks_text, const std::string& job) {
  if (!recording.log_error.empty()) return recording.log_error;
  OutputFiles files;
  if (!options.peaks_path.empty()) files.add(options.peaks_path, peaks_text);
  if (!options.plot_path.empty()) {
    files.add(options.plot_path, sim::force_plot_svg(recording.plot.data(job, revolutions)));
  }
  return files.commit();
}

// The peaks CSV (force_log::format_revolution_peaks) with a last column `tool`: the T number of each
// revolution's tool.
std::string peaks_with_tools(const std::vector<force_log::RevolutionPeak>& revolutions,
                             const std::vector<std::string>& tools) {
  std::istringstream lines(force_log::format_revolution_peaks(revolutions));
  std::string out, line;
  for (std::size_t row = 0; std::getline(lines, line); ++row) {
    out += line;
    out += ',';
    out += row == 0 ? std::string("tool") : tools[row - 1];
    out += '\n';
  }
  return out;
}

// The figures a run of one tool and a run of several share (sim::SimulationSummary, ToolRunSimulation's).
template <typename Summary>
void add_summary_json(const Summary& s, nlohmann::json& out) {
  out["cycle_time_s"] = s.cycle_time_s;
  out["cutting_time_s"] = s.cutting_time_s;
  out["air_time_s"] = s.air_time_s;
  out["time_in_contact_s"] = s.time_in_contact_s;
  out["max_revolution_peak_n"] = s.max_revolution_peak_n;
  out["mean_force_in_contact_n"] = s.mean_force_in_contact_n;
  out["max_force_z_n"] = s.max_force_z_n;
  out["steps"] = s.steps;
}

void print_simulation_json(const SimulateOptions& options, const geometry::Tool& tool, const std::string& material,
                           const SimulationJob& job, const SimulationRun& run) {
  const sim::SimulationResult& result = run.result;
  const auto& s = result.summary;
  nlohmann::json out;
  out["job"] = job.name;
  out["tool"] = {{"name", tool.name}, {"diameter_mm", tool.diameter_mm}, {"flutes", tool.flutes}, {"helix_deg", tool.helix_deg}};
  out["material"] = material;
  add_summary_json(s, out);
  out["step_s"] = s.step_s;
  out["stock_layers"] = s.stock_layers;
  out["engagement_bands"] = s.engagement_bands;
  out["recut_tolerance_mm"] = s.recut_tolerance_mm;
  out["log"] = options.log_path;
  out["log_rows"] = s.log_rows;
  if (!options.plot_path.empty()) out["plot"] = options.plot_path;
  if (!options.peaks_path.empty()) out["peaks"] = options.peaks_path;
  out["wall_time_s"] = run.recording.wall_s;
  out["revolutions"] = nlohmann::json::array();
  for (const auto& rev : result.revolutions) {
    out["revolutions"].push_back({{"t_start_s", rev.t_start_s}, {"peak_xy_n", rev.peak_xy_n}, {"mean_xy_n", rev.mean_xy_n}});
  }
  out["notes"] = job.notes;
  out["warnings"] = result.warnings;
  std::cout << out.dump(2) << "\n";
}

void print_simulation_text(const SimulateOptions& options, const geometry::Tool& tool, const std::string& material,
                           const SimulationJob& job, const SimulationRun& run) {
  const sim::SimulationResult& result = run.result;
  const auto& s = result.summary;
  const double wall_s = run.recording.wall_s;
  std::printf("%s\n", job.name.c_str());
  std::printf("tool %s (D%.4g mm, %d flutes, helix %.3g deg), material %s\n", tool.name.c_str(), tool.diameter_mm,
              tool.flutes, tool.helix_deg, material.c_str());
  std::printf("cycle time %.3f s: cutting moves %.3f s, air %.3f s; tool in contact %.3f s\n", s.cycle_time_s,
              s.cutting_time_s, s.air_time_s, s.time_in_contact_s);
  std::printf("force |F_xy|: max per-revolution peak %.1f N, mean in contact %.1f N; max |F_z| %.1f N\n",
              s.max_revolution_peak_n, s.mean_force_in_contact_n, s.max_force_z_n);
  std::printf("simulated %lld steps of %.1f us on %d stock layers (%d engagement computations) in %.2f s wall "
              "(%.1f simulated s per wall s)\n",
              s.steps, s.step_s * 1e6, s.stock_layers, s.engagement_bands, wall_s,
              wall_s > 0 ? s.cycle_time_s / wall_s : 0.0);
  std::printf("force log (%lld rows) written to %s\n", s.log_rows, options.log_path.c_str());
  if (!options.peaks_path.empty()) {
    std::printf("per-revolution peaks (%zu) written to %s\n", result.revolutions.size(), options.peaks_path.c_str());
  }
  if (!options.plot_path.empty()) std::printf("plot written to %s\n", options.plot_path.c_str());
  for (const auto& note : job.notes) std::printf("note: %s\n", note.c_str());
}

// --tools: what the user should know about each run the milling simulation does not take.
std::vector<std::string> tool_run_notes(const ToolRunSimulation& simulation) {
  std::vector<std::string> notes;
  for (const SimulatedToolRun& r : simulation.runs) {
    if (r.kind != ToolRunKind::kDrilling) continue;
    notes.push_back(run_name(r.run) + ", lines " + std::to_string(r.first_line) + "–" + std::to_string(r.last_line) +
                    ": drilling cycles are not simulated (the milling simulation has no model of a drill's point): "
                    "holes of Ø" + shortest_number_text(r.run.tool.diameter_mm) +
                    " mm cut from the stock, timed by the motion model, no forces in the log");
  }
  return notes;
}

const char* kind_name(ToolRunKind kind) {
  switch (kind) {
    case ToolRunKind::kMilling: return "milling";
    case ToolRunKind::kDrilling: return "drilling";
    case ToolRunKind::kRapids: return "rapids";
  }
  return "";
}

void print_tool_runs_json(const SimulateOptions& options, const std::string& material, const SimulationJob& job,
                          const ToolRunSimulation& simulation, const LogRecording& recording) {
  const auto& s = simulation.summary;
  nlohmann::json out;
  out["job"] = job.name;
  out["tools"] = options.tools_path;
  out["material"] = material;
  add_summary_json(s, out);
  out["engagement_bands"] = s.engagement_bands;
  out["log"] = options.log_path;
  out["log_rows"] = s.log_rows;
  if (!options.plot_path.empty()) out["plot"] = options.plot_path;
  if (!options.peaks_path.empty()) out["peaks"] = options.peaks_path;
  out["wall_time_s"] = recording.wall_s;
  out["tool_runs"] = nlohmann::json::array();
  for (const SimulatedToolRun& r : simulation.runs) {
    nlohmann::json run = {{"name", run_name(r.run)},
                          {"first_line", r.first_line},
                          {"last_line", r.last_line},
                          {"kind", kind_name(r.kind)},
                          {"start_s", r.start_s},
                          {"cycle_time_s", r.duration_s},
                          {"cutting_time_s", r.summary.cutting_time_s},
                          {"max_revolution_peak_n", r.summary.max_revolution_peak_n},
                          {"mean_force_in_contact_n", r.summary.mean_force_in_contact_n},
                          {"time_in_contact_s", r.summary.time_in_contact_s},
                          {"revolutions", r.revolutions}};
    run["tool_number"] = r.run.number;
    if (r.kind != ToolRunKind::kRapids) {
      run["tool"] = {{"name", r.run.tool.name}, {"diameter_mm", r.run.tool.diameter_mm}, {"flutes", r.run.tool.flutes},
                     {"helix_deg", r.run.tool.helix_deg}};
    }
    out["tool_runs"].push_back(run);
  }
  out["revolutions"] = nlohmann::json::array();
  for (std::size_t i = 0; i < simulation.revolutions.size(); ++i) {
    const auto& rev = simulation.revolutions[i];
    out["revolutions"].push_back({{"t_start_s", rev.t_start_s}, {"peak_xy_n", rev.peak_xy_n}, {"mean_xy_n", rev.mean_xy_n},
                                  {"tool", simulation.revolution_tools[i]}});
  }
  out["notes"] = job.notes;
  out["warnings"] = simulation.warnings;
  std::cout << out.dump(2) << "\n";
}

void print_tool_runs_text(const SimulateOptions& options, const std::string& material, const SimulationJob& job,
                          const ToolRunSimulation& simulation, const LogRecording& recording) {
  const auto& s = simulation.summary;
  std::printf("%s\n", job.name.c_str());
  std::printf("tools from %s, material %s\n", options.tools_path.c_str(), material.c_str());
  std::printf("cycle time %.3f s: cutting moves %.3f s, air %.3f s; tool in contact %.3f s\n", s.cycle_time_s,
              s.cutting_time_s, s.air_time_s, s.time_in_contact_s);
  std::printf("force |F_xy|: max per-revolution peak %.1f N, mean in contact %.1f N; max |F_z| %.1f N\n",
              s.max_revolution_peak_n, s.mean_force_in_contact_n, s.max_force_z_n);
  std::printf("per tool:\n");
  for (const SimulatedToolRun& r : simulation.runs) {
    std::printf("  %s, lines %d–%d: ", run_name(r.run).c_str(), r.first_line, r.last_line);
    if (r.kind == ToolRunKind::kRapids) {
      std::printf("rapids only, %.3f s (motion model)\n", r.duration_s);
      continue;
    }
    std::printf("%s (D%s mm, %d flutes): ", r.run.tool.name.c_str(), shortest_number_text(r.run.tool.diameter_mm).c_str(),
                r.run.tool.flutes);
    if (r.kind == ToolRunKind::kDrilling) {
      std::printf("drilling, %.3f s (motion model, not simulated)\n", r.duration_s);
    } else {
      std::printf("%.3f s from t = %.3f s, max per-revolution peak %.1f N\n", r.duration_s, r.start_s,
                  r.summary.max_revolution_peak_n);
    }
  }
  std::printf("simulated %lld steps (%d engagement computations) in %.2f s wall (%.1f simulated s per wall s)\n", s.steps,
              s.engagement_bands, recording.wall_s, recording.wall_s > 0 ? s.cycle_time_s / recording.wall_s : 0.0);
  std::printf("force log (%lld rows) written to %s\n", s.log_rows, options.log_path.c_str());
  if (!options.peaks_path.empty()) {
    std::printf("per-revolution peaks (%zu) written to %s\n", simulation.revolutions.size(), options.peaks_path.c_str());
  }
  if (!options.plot_path.empty()) std::printf("plot written to %s\n", options.plot_path.c_str());
  for (const auto& note : job.notes) std::printf("note: %s\n", note.c_str());
}

// PROGRAM --tools: each tool's run on the stock the runs before it left (tool_run_simulation.hpp).
int run_tool_program(const SimulateOptions& options, const SimulateInputs& in, const sim::Material& material,
                     const std::optional<sim::MachineFile>& machine, sim::SimulationRequest base) {
  SimulationJob job;
  job.name = options.program_path;
  const ToolProgram p = read_tool_program(options, in);
  job.notes = p.program.notes;
  const geometry::Stock stock = program_stock(options, in, p, job);
  base.log_metadata = {{"program", options.program_path}, {"tools", options.tools_path}, {"material", material.name}};
  if (machine) base.log_metadata.push_back({"machine", machine->name + " (" + options.machine_path + ")"});
  ToolRunRequest request{std::move(base), machine, options.tools_path};
  if (auto problems = check_tool_runs(request, p.program, p.written, p.runs, stock); !problems.empty()) {
    throw InputError(std::move(problems));
  }
  for (auto& entry : tool_run_metadata(request, p.program, p.written, p.runs)) request.base.log_metadata.push_back(entry);
  ToolRunSimulation simulation;
  LogRecording recording;
  record_log(options, recording, [&](force_log::ForceLogSink& log, const std::function<void(double)>& progress) {
    simulation = simulate_tool_runs(request, p.program, p.written, p.runs, stock, log, progress);
  });
  const std::string peaks_text = peaks_with_tools(simulation.revolutions, simulation.revolution_tools);
  if (const std::string error = write_simulation_outputs(options, recording, simulation.revolutions, peaks_text, job.name);
      !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return 1;
  }
  for (std::string& note : tool_run_notes(simulation)) job.notes.push_back(std::move(note));
  if (options.json) {
    print_tool_runs_json(options, material.name, job, simulation, recording);
  } else {
    print_tool_runs_text(options, material.name, job, simulation, recording);
  }
  for (const auto& warning : simulation.warnings) std::cerr << "feedplan: warning: " << warning << "\n";
  return 0;
}

}  // namespace

void add_simulate_command(CLI::App& app, SimulateOptions& options) {
  auto* cmd = app.add_subcommand(
      "simulate",
      "Run a G-code program (or a virtual cutting test) on the virtual machine: mechanistic milling forces\n"
      "tooth by tooth on the stock, feeds under the acceleration limits, sensors; writes a force log");
  cmd->add_option("program", options.program_path, "G-code program (RS274/NGC subset) to run");
  cmd->add_option("--spec", options.spec_path,
                  "Cycle spec to take the tool, material, spindle speed, machine limits and stock from");
  cmd->add_option("--tool", options.tool_text, "End mill: diameter_mm=10,flutes=4,helix_deg=30[,name=...]");
  cmd->add_option("--tools", options.tools_path,
                  "The end mill of each T number of a program that changes tools (tools: {2: {diameter_mm: 6.35, "
                  "flutes: 2, helix_deg: 30}, ...}); each tool's moves run on the stock the tools before it left");
  cmd->add_option("--material", options.material_name, "Workpiece material (name or alias in the materials file)");
  cmd->add_option("--materials", options.materials_path, "Materials file (default: the bundled data/materials.yaml)");
  cmd->add_option("--stock", options.stock_path,
                  "Workpiece: a stock YAML (stock: {z_bottom_mm, z_top_mm, regions}) or a cycle spec; default: a "
                  "solid block around the program below z = 0");
  cmd->add_option("--log", options.log_path, "Force log to write (CSV, docs/method.md §4)")->required();
  cmd->add_option("--plot", options.plot_path, "Plot of the force to write (SVG)");
  cmd->add_option("--peaks", options.peaks_path, "Per-revolution peak and mean |F_xy| to write (CSV, true force)");
  cmd->add_flag("--json", options.json, "Print the summary as JSON");
  add_number_flag(cmd, "--spindle-rpm", options.spindle_rpm, "Spindle speed for blocks without S; the cutting test's S");
  add_number_flag(cmd, "--max-accel", options.max_accel_mm_per_s2, "Path acceleration limit, mm/s²");
  add_number_flag(cmd, "--rapid", options.rapid_feed_mm_per_min, "Rapid traverse rate, mm/min");
  add_number_flag(cmd, "--max-feed", options.max_feed_mm_per_min, "Highest feed the machine runs, mm/min");
  cmd->add_option("--machine", options.machine_path,
                  "Machine file (data/machines/*.yaml): material and coefficients, size effect, runout, true helix, "
                  "dynamometer; conflicts with --material, --runout-mm and --noise-n");
  cmd->add_option("--runout-mm", options.runout_text, "Radial runout per tooth, mm, comma separated (one per flute)");
  add_number_flag(cmd, "--noise-n", options.noise_n, "Dynamometer noise, RMS N");
  cmd->add_flag("--currents", options.currents, "Also log feed-drive servo currents (seed 002: I = a + b·F)");
  add_number_flag(cmd, "--log-rate", options.log_rate_hz, "Log sample rate, Hz");
  add_number_flag(cmd, "--angle-step", options.angle_step_deg, "Spindle rotation per simulation step, deg");
  add_number_flag(cmd, "--layer-mm", options.layer_mm, "Axial slice thickness, mm");
  add_integer_flag(cmd, "--seed", options.seed, "Sensor noise seed");
  cmd->add_flag("--cutting-test", options.cutting_test,
                "Simulate a straight cut (a dynamometer cutting test) instead of a program");
  add_number_flag(cmd, "--radial-depth-mm", options.radial_depth_mm, "Cutting test: radial depth a_e, mm");
  add_number_flag(cmd, "--axial-depth-mm", options.axial_depth_mm, "Cutting test: axial depth a_p, mm");
  add_number_flag(cmd, "--feed-mm-per-min", options.feed_mm_per_min, "Cutting test: feed F, mm/min");
  add_number_flag(cmd, "--cut-length-mm", options.cut_length_mm, "Cutting test: length of the block, mm");
  cmd->add_flag("--up", options.up_milling, "Cutting test: up (conventional) milling instead of down (climb)");
}

int run_simulate_command(const SimulateOptions& options) {
  const SimulateInputs in = read_simulate_inputs(options);
  const sim::MaterialLibrary materials =
      sim::load_materials(options.materials_path.empty() ? bundled_materials_path() : options.materials_path);
  std::optional<sim::MachineFile> machine;
  if (!options.machine_path.empty()) machine = sim::load_machine_file(options.machine_path, materials);
  const sim::Material& material =
      machine ? materials.get(machine->material, options.machine_path + ": material")
              : materials.get(in.material_name, options.material_name.empty() ? "spec.material" : "--material");
  sim::SimulationRequest request = simulation_request(options, in, material);
  if (!options.tools_path.empty()) return run_tool_program(options, in, material, machine, std::move(request));
  if (machine) {
    if (auto problems = sim::apply_machine(*machine, request); !problems.empty()) throw InputError(std::move(problems));
  }
  const SimulationJob job = options.cutting_test ? set_cutting_test(options, in, request) : set_program(options, in, request);
  request.log_metadata.push_back({"material", material.name});
  if (machine) request.log_metadata.push_back({"machine", machine->name + " (" + options.machine_path + ")"});
  const SimulationRun run = run_simulation(std::move(request), options);
  const std::string peaks_text = force_log::format_revolution_peaks(run.result.revolutions);
  if (const std::string error = write_simulation_outputs(options, run.recording, run.result.revolutions, peaks_text, job.name);
      !error.empty()) {
    std::cerr << "feedplan: failed: " << error << "\n";
    return 1;
  }
  if (options.json) {
    print_simulation_json(options, in.tool, material.name, job, run);
  } else {
    print_simulation_text(options, in.tool, material.name, job, run);
  }
  for (const auto& warning : run.result.warnings) std::cerr << "feedplan: warning: " << warning << "\n";
  return 0;
}

}  // namespace feedplan::cli
