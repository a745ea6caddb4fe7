#pragma once
// The virtual machine: runs a Program on a stock the way a machining centre would — feeds under the
// acceleration limits (motion_profile.hpp), mechanistic forces tooth by tooth (milling_forces.hpp) on
// the material the path has not yet removed (layered_engagement.hpp), read by sensors
// (sensors.hpp) — and writes the force log a data-acquisition system would (docs/method.md §4, §6).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/geometry/stock.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/sim/cutting_coefficients.hpp"
#include "feedplan/sim/feed_override.hpp"
#include "feedplan/force_log/force_log.hpp"
#include "feedplan/force_log/force_log_sink.hpp"
#include "feedplan/sim/motion_profile.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"
#include "feedplan/sim/sensors.hpp"

namespace feedplan::sim {

//! Resolution and tool details of a simulation.
struct SimulationOptions {
  //! Spindle rotation per internal step, deg (rounded so a tooth period is a whole number of steps).
  double angle_step_deg = 1.0;
  //! Axial slice / stock layer thickness, mm; helices use at most 1/20 of their pitch (see summary).
  double layer_thickness_mm = 0.25;
  double engagement_ds_mm = 0.02;    //!< engagement sample spacing along the path, mm
  //! Radial runout per tooth, mm (tooth j cuts at r + runout_mm[j]); empty: none, else one per flute.
  std::vector<double> runout_mm;
  double flute_length_mm = 0.0;  //!< cutting length above the tip, mm; 0: longer than any cut
  double log_rate_hz = 10000.0;  //!< force log sample rate, Hz
  //! How far a flat track may lie from a helix track it re-cuts for the layers between to share the
  //! lowest layer's engagement from there on, mm (LayerOptions::recut_tolerance_mm). Unset: from the
  //! program's number resolution, √2 × Program::coordinate_resolution_mm — how far apart two written
  //! points of one intended track can lie, each rounded by half a digit per axis (1.4 µm for 3
  //! decimals in mm) — and exact (1e-9 mm) for a path that is not rounded. Within it the upper
  //! layers' material may differ from the lowest layer's by slivers thinner than the tolerance, which
  //! the run then does not see (their edge forces).
  std::optional<double> recut_tolerance_mm;
  //! Spindle speed for blocks that give none (no S word), rev/min; 0: such a block cutting is an error.
  double default_spindle_rpm = 0.0;
};

//! What a feedback controller sees each control period (for the feed-override controllers of seeds
//! 000–002, 004).
struct ControlInput {
  double t_s = 0.0;                //!< time, s
  SensorReading reading;           //!< what the sensors read now
  double override_ratio = 1.0;     //!< feed override the machine is applying now
  double s_mm = 0.0;               //!< path position, mm
  double spindle_rpm = 0.0;        //!< spindle speed, rev/min
};

//! An optional feed-override loop: every `period_s` the controller returns a new override command,
//! which reaches the feed through `channel` (lag and dead time). The override scales the planned
//! motion's time (the machine follows the planned profile at `ratio` times its speed).
struct OverrideLoop {
  double period_s = 0.01;             //!< control period, s
  FeedOverrideOptions channel;        //!< lag and dead time of the override path
  std::function<double(const ControlInput&)> controller;  //!< returns the commanded ratio; empty: off
};

//! Everything a run needs.
struct SimulationRequest {
  geometry::Program program;          //!< what the machine executes
  geometry::Tool tool;                //!< the end mill
  CuttingCoefficients coefficients;   //!< the tool–material pair's physics
  geometry::Stock stock;              //!< the workpiece before the program
  geometry::MachineLimits machine = kVirtualMachineLimits;  //!< feed drive limits
  SensorOptions sensors;              //!< what is measured and how
  SimulationOptions options;          //!< resolution, runout, log rate
  OverrideLoop override_loop;         //!< optional feedback controller on the feed override
  std::vector<std::pair<std::string, std::string>> log_metadata;  //!< extra `# key: value` lines
  //! Where the force log goes as it is recorded (header first, then every row; must outlive the run):
  //! a file, a plot, nothing. Null: kept whole in SimulationResult::log — about 100 bytes per row,
  //! 0.1 GB per 2 minutes at 10 kHz. With a sink the result's log holds the header and no rows.
  force_log::ForceLogSink* log_sink = nullptr;
  //! Called with the fraction of the whole run done (0..1, the stock's engagement and the program's
  //! time weighted by their expected cost), at least every 1 % and at the end; may be empty.
  std::function<void(double)> progress;
};

//! Totals of a run.
struct SimulationSummary {
  double cycle_time_s = 0.0;       //!< program duration including dwells, s
  double cutting_time_s = 0.0;     //!< time on cutting feed moves, s
  double air_time_s = 0.0;         //!< time on rapids and air feed moves, s
  double time_in_contact_s = 0.0;  //!< time with some tooth in the material, s
  double max_revolution_peak_n = 0.0;   //!< largest per-revolution peak |F_xy|, N
  double mean_force_in_contact_n = 0.0; //!< mean |F_xy| while in contact, N
  double max_force_z_n = 0.0;      //!< largest |F_z|, N
  long long steps = 0;             //!< internal steps simulated
  long long log_rows = 0;          //!< force log rows recorded (kept or given to the sink)
  double step_s = 0.0;             //!< internal step, s
  int stock_layers = 0;            //!< axial layers of the stock
  double layer_thickness_mm = 0.0; //!< layer thickness used, mm
  int engagement_bands = 0;        //!< distinct engagement computations
  long long engagement_samples = 0;  //!< engagement samples computed over all bands
  double recut_tolerance_mm = 0.0; //!< how far apart tracks counted as one re-cut (options.recut_tolerance_mm), mm
};

//! Result of a run. Warnings are things a user must see but that do not stop the run (a rapid into
//! material, feeding into material with the spindle stopped, M4 with a right-hand cutter).
struct SimulationResult {
  //! Sensor readings at options.log_rate_hz: header and rows, or the header only with a log_sink.
  force_log::ForceLog log;
  //! One per spindle revolution (by the simulated spindle angle), from the true force — unfiltered
  //! and noise-free, at every internal step.
  std::vector<force_log::RevolutionPeak> revolutions;
  SimulationSummary summary;
  std::vector<std::string> warnings;
};

//! Checks a request: tool, coefficients, options, machine limits, sensors, stock and that every
//! cutting move has a spindle speed. Field names are "tool.diameter_mm", "material.ktc_n_per_mm2",
//! "options.angle_step_deg", "line 12" (program lines) and so on.
std::vector<InputProblem> validate(const SimulationRequest& request);

//! Runs the program. Throws InputError with validate's problems (and plan_motion's) when the request
//! is invalid. Deterministic: the same request (including the sensor noise seed) gives the same log.
SimulationResult simulate(const SimulationRequest& request);

}  // namespace feedplan::sim
