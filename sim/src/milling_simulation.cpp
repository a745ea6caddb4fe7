#include "feedplan/sim/milling_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "cutter_contact.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/sim/layered_engagement.hpp"
#include "log_resampler.hpp"
#include "revolution_statistics.hpp"
#include "run_progress.hpp"

namespace feedplan::sim {

namespace {

// Layers per helix pitch: with 20 the per-revolution peaks of steady helical boring vary by about 3 %
// (4 layers per pitch: 30 %).
constexpr double kLayersPerHelixPitch = 20.0;

void check_positive(std::vector<InputProblem>& problems, const std::string& field, double value, const std::string& why) {
  if (!(std::isfinite(value) && value > 0.0)) {
    problems.push_back({field, "= " + six_digit_number_text(value) + ": must be a finite number > 0 — " + why});
  }
}

void check_non_negative(std::vector<InputProblem>& problems, const std::string& field, double value,
                        const std::string& why) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    problems.push_back({field, "= " + six_digit_number_text(value) + ": must be a finite number ≥ 0 — " + why});
  }
}

// "prog.ngc line 12:" (the reader's way of naming a place in a program), or "move 3:" for generated programs.
std::string line_of(const geometry::Program& program, std::size_t move) {
  const int line = move < program.blocks.size() ? program.blocks[move].source_line : 0;
  const std::string where = line > 0 ? "line " + std::to_string(line) : "move " + std::to_string(move);
  return (program.source_name.empty() ? where : program.source_name + " " + where) + ":";
}

double spindle_rpm_of(const geometry::BlockCommand& block, double default_rpm) {
  if (block.spindle == geometry::SpindleDirection::kOff) return 0.0;
  return block.spindle_rpm > 0.0 ? block.spindle_rpm : default_rpm;
}

// --- validate: one function per part of the request ---------------------------------------------

void check_tool(std::vector<InputProblem>& problems, const geometry::Tool& tool) {
  check_positive(problems, "tool.diameter_mm", tool.diameter_mm, "cutting diameter of the end mill");
  if (tool.flutes < 1 || tool.flutes > 32) {
    problems.push_back({"tool.flutes", "= " + std::to_string(tool.flutes) + ": must be in [1, 32] — number of teeth"});
  }
  if (!(std::isfinite(tool.helix_deg) && tool.helix_deg >= 0.0 && tool.helix_deg < 70.0)) {
    problems.push_back(
        {"tool.helix_deg", "= " + six_digit_number_text(tool.helix_deg) + ": must be in [0, 70) — helix angle"});
  }
}

void check_coefficients(std::vector<InputProblem>& problems, const CuttingCoefficients& k) {
  check_positive(problems, "material.ktc_n_per_mm2", k.ktc_n_per_mm2, "tangential cutting coefficient");
  check_non_negative(problems, "material.krc_n_per_mm2", k.krc_n_per_mm2, "radial cutting coefficient");
  check_non_negative(problems, "material.kac_n_per_mm2", k.kac_n_per_mm2, "axial cutting coefficient");
  check_non_negative(problems, "material.kte_n_per_mm", k.kte_n_per_mm, "tangential edge coefficient");
  check_non_negative(problems, "material.kre_n_per_mm", k.kre_n_per_mm, "radial edge coefficient");
  check_non_negative(problems, "material.kae_n_per_mm", k.kae_n_per_mm, "axial edge coefficient");
  if (!(std::isfinite(k.size_exponent) && k.size_exponent >= 0.0 && k.size_exponent < 1.0)) {
    problems.push_back({"material.size_effect.exponent", "= " + six_digit_number_text(k.size_exponent) +
                                                             ": must be in [0, 1) — m_c of k_c = k_1 h^(−m_c)"});
  }
  if (k.size_exponent > 0.0) {
    check_positive(problems, "material.size_effect.reference_chip_mm", k.size_reference_chip_mm,
                   "chip thickness the cutting coefficients hold at");
    check_positive(problems, "material.size_effect.min_chip_mm", k.size_min_chip_mm, "smallest chip evaluated");
  }
}

void check_options(std::vector<InputProblem>& problems, const SimulationOptions& o, const geometry::Tool& tool) {
  if (!(std::isfinite(o.angle_step_deg) && o.angle_step_deg > 0.0 && o.angle_step_deg <= 10.0)) {
    problems.push_back({"options.angle_step_deg", "= " + six_digit_number_text(o.angle_step_deg) +
                                                      ": must be in (0, 10] — spindle rotation per step"});
  }
  check_positive(problems, "options.layer_thickness_mm", o.layer_thickness_mm, "axial slice thickness");
  if (std::isfinite(o.layer_thickness_mm) && o.layer_thickness_mm > 0.0 && o.layer_thickness_mm < 0.005) {
    problems.push_back(
        {"options.layer_thickness_mm", "= " + six_digit_number_text(o.layer_thickness_mm) + ": must be ≥ 0.005"});
  }
  check_positive(problems, "options.engagement_ds_mm", o.engagement_ds_mm, "engagement sample spacing");
  if (std::isfinite(o.engagement_ds_mm) && o.engagement_ds_mm > 0.0 && o.engagement_ds_mm < 0.001) {
    problems.push_back(
        {"options.engagement_ds_mm", "= " + six_digit_number_text(o.engagement_ds_mm) + ": must be ≥ 0.001"});
  }
  check_positive(problems, "options.log_rate_hz", o.log_rate_hz, "force log sample rate");
  if (o.recut_tolerance_mm) {
    check_non_negative(problems, "options.recut_tolerance_mm", *o.recut_tolerance_mm, "distance of a re-cutting track");
  }
  check_non_negative(problems, "options.flute_length_mm", o.flute_length_mm, "0 means longer than any cut");
  check_non_negative(problems, "options.default_spindle_rpm", o.default_spindle_rpm, "spindle speed for blocks without S");
  if (!o.runout_mm.empty() && static_cast<int>(o.runout_mm.size()) != tool.flutes) {
    problems.push_back({"options.runout_mm", "has " + std::to_string(o.runout_mm.size()) +
                                                 " values: must have one per flute (" + std::to_string(tool.flutes) + ")"});
  }
  for (std::size_t j = 0; j < o.runout_mm.size(); ++j) {
    if (!(std::isfinite(o.runout_mm[j]) && std::abs(o.runout_mm[j]) < 0.5 * std::max(tool.diameter_mm, 0.0))) {
      problems.push_back(
          {"options.runout_mm[" + std::to_string(j) + "]",
           "= " + six_digit_number_text(o.runout_mm[j]) + ": must be finite and smaller than the tool radius"});
    }
  }
}

// Every feed move needs a spindle speed (the first five offenders are named).
void check_spindle_speeds(std::vector<InputProblem>& problems, const geometry::Program& program, double default_rpm) {
  int spindle_problems = 0;
  for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
    const auto& move = program.path.moves[i];
    if (move.kind == geometry::MoveKind::kRapid) continue;
    const double rpm = spindle_rpm_of(program.blocks[i], default_rpm);
    if (!(rpm > 0.0) && spindle_problems++ < 5) {
      const bool stopped = program.blocks[i].spindle == geometry::SpindleDirection::kOff;
      problems.push_back({line_of(program, i),
                          stopped ? std::string("feed move with the spindle stopped (no M3/M4 in effect): start the "
                                                "spindle with M3 S… before feeding")
                                  : std::string("feed move with no spindle speed (no S word): give S with M3, or a "
                                                "default spindle speed (--spindle-rpm)")});
    }
  }
}

void check_program(std::vector<InputProblem>& problems, const geometry::Program& program, double default_rpm) {
  if (program.path.moves.empty()) problems.push_back({"program", "has no moves: nothing to simulate"});
  if (program.blocks.size() != program.path.moves.size()) {
    problems.push_back({"program", "has " + std::to_string(program.blocks.size()) + " block commands for " +
                                       std::to_string(program.path.moves.size()) + " moves: expected one per move"});
    return;
  }
  for (const auto& defect : geometry::consistency_defects(program.path, 1e-6)) problems.push_back({"program", defect});
  check_spindle_speeds(problems, program, default_rpm);
}

// --- simulate: the steps before the run ----------------------------------------------------------

// Step 1. The stock layer thickness. A helix meets each layer in turn as it descends; the sum over
// layers is a quadrature in z whose error shows as a ripple at the layer-crossing rate, so helices get
// at least kLayersPerHelixPitch layers per pitch.
double layer_thickness_mm(const geometry::ToolPath& path, double requested_mm) {
  double layer_mm = requested_mm;
  for (const auto& move : path.moves) {
    const double dz = std::abs(move.end.z_mm - move.start.z_mm);
    if (move.kind == geometry::MoveKind::kArc && move.cutting && dz > 1e-9) {
      const double pitch = dz * kTwoPi / move.sweep_rad;
      layer_mm = std::min(layer_mm, pitch / kLayersPerHelixPitch);
    }
  }
  return layer_mm;
}

// Tracks closer than this are one in a path that is not rounded (floating-point noise), mm.
constexpr double kExactTrackMm = 1e-9;

// How far apart two tracks may lie and count as one re-cut, mm (SimulationOptions::recut_tolerance_mm).
double recut_tolerance_mm(const SimulationRequest& request) {
  if (request.options.recut_tolerance_mm) return *request.options.recut_tolerance_mm;
  return std::max(kExactTrackMm, std::sqrt(2.0) * request.program.coordinate_resolution_mm);
}

// The warning for the first feed move under M4, if any.
std::optional<std::string> m4_warning(const geometry::Program& program) {
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    if (program.blocks[i].spindle == geometry::SpindleDirection::kCounterClockwise &&
        program.path.moves[i].kind != geometry::MoveKind::kRapid) {
      return line_of(program, i) +
             " M4 (counter-clockwise spindle) on a feed move; simulated as a right-hand cutter "
             "turning clockwise (M3)";
    }
  }
  return std::nullopt;
}

// The fastest spindle speed of any block, rev/min; 1 for a program of rapids only (no cutting, the
// step only paces the log).
double fastest_spindle_rpm(const geometry::Program& program, double default_rpm) {
  double max_rpm = 0.0;
  for (const auto& block : program.blocks) max_rpm = std::max(max_rpm, spindle_rpm_of(block, default_rpm));
  if (max_rpm <= 0.0) max_rpm = 1.0;
  return max_rpm;
}

// Bandwidth of the fastest enabled sensor, Hz.
double fastest_sensor_hz(const SensorOptions& sensors) {
  double fastest_hz = sensors.dynamometer.bandwidth_hz;
  if (sensors.spindle_sensor.enabled) fastest_hz = std::max(fastest_hz, sensors.spindle_sensor.bandwidth_hz);
  if (sensors.servo_current.enabled) fastest_hz = std::max(fastest_hz, sensors.servo_current.bandwidth_hz);
  if (sensors.spindle_power.enabled) fastest_hz = std::max(fastest_hz, sensors.spindle_power.bandwidth_hz);
  return fastest_hz;
}

// The internal step of a run.
struct StepClock {
  double max_rpm = 0.0;          // fastest spindle speed, rev/min
  int steps_per_tooth = 0;       // steps per tooth period at max_rpm
  double dt = 0.0;               // internal step, s
  long long total_steps = 0;     // steps of the planned motion
};

// Step 2. A whole number of steps per tooth period at the fastest spindle speed, near the requested
// angle step; the step also resolves the fastest enabled sensor: at least four steps per period of
// its bandwidth.
StepClock step_clock(const SimulationRequest& request, const MotionProfile& motion) {
  StepClock clock;
  clock.max_rpm = fastest_spindle_rpm(request.program, request.options.default_spindle_rpm);
  const double tooth_angle_rad = kTwoPi / request.tool.flutes;
  const double max_omega_rad_per_s = clock.max_rpm * kTwoPi / 60.0;
  const double tooth_period_s = tooth_angle_rad / max_omega_rad_per_s;
  clock.steps_per_tooth = std::max(
      {1, static_cast<int>(std::lround(tooth_angle_rad / deg_to_rad(request.options.angle_step_deg))),
       static_cast<int>(std::ceil(tooth_period_s * 4.0 * fastest_sensor_hz(request.sensors)))});
  clock.dt = tooth_angle_rad / clock.steps_per_tooth / max_omega_rad_per_s;
  clock.total_steps = static_cast<long long>(std::ceil(motion.duration_s() / clock.dt - 1e-9));
  return clock;
}

// The tool's name, or "D<diameter>" for a tool without one.
std::string tool_name(const geometry::Tool& tool) {
  if (!tool.name.empty()) return tool.name;
  std::string name = "D";
  name += six_digit_number_text(tool.diameter_mm);
  return name;
}

// The stock layers the flutes may reach: from the lowest feed-move tip (or the stock bottom) to the
// stock top (LayeredEngagement's layers, known before they are computed).
int expected_layers(const SimulationRequest& request, double layer_mm) {
  double lowest = request.stock.z_top_mm;
  for (const auto& move : request.program.path.moves) {
    if (move.kind != geometry::MoveKind::kRapid) lowest = std::min({lowest, move.start.z_mm, move.end.z_mm});
  }
  const double depth_mm = request.stock.z_top_mm - std::max(lowest, request.stock.z_bottom_mm);
  return static_cast<int>(std::ceil(std::max(depth_mm, 0.0) / layer_mm));
}

// Step 3. The log's header: where it comes from, its rate, the tool and the spindle speed, then the
// request's own entries.
void start_log(force_log::ForceLog& log, const SimulationRequest& request, double max_rpm) {
  log.has_currents = request.sensors.servo_current.enabled;
  log.metadata = {{"source", "feedplan simulate (virtual machine, mechanistic forces)"},
                  {"sample_rate_hz", six_digit_number_text(request.options.log_rate_hz)},
                  {"tool", tool_name(request.tool)},
                  {"tool_diameter_mm", six_digit_number_text(request.tool.diameter_mm)},
                  {"flutes", std::to_string(request.tool.flutes)},
                  {"helix_deg", six_digit_number_text(request.tool.helix_deg)},
                  {"spindle_rpm", six_digit_number_text(max_rpm)}};
  for (const auto& entry : request.log_metadata) log.metadata.push_back(entry);
}

// --- simulate: the run ---------------------------------------------------------------------------

// Where the machine is at one internal step.
struct StepState {
  double t_s = 0.0;      // time of the step, s
  MotionState motion;    // on the planned motion (at time tau, not t, under a feed override)
  double rpm = 0.0;      // spindle speed of the move being run, rev/min
};

// Time in contact and the force summed over it.
struct ContactTotals {
  double force_sum_n = 0.0;
  long long steps = 0;
};

// Step 4. The internal steps from the start to the end of the planned motion: the motion (under the
// feed override, if any), the cutter in the stock, the sensors, the statistics, the log and the
// controller, in this order at every step.
class MachineRun {
 public:
  MachineRun(const SimulationRequest& request, const MotionProfile& motion, const LayeredEngagement& layers,
             const StepClock& clock, force_log::ForceLogSink& log, detail::RunProgress& progress,
             SimulationResult& result)
      : request_(request),
        motion_(motion),
        clock_(clock),
        result_(result),
        sensors_(request.sensors, clock.dt),
        override_channel_(make_override_channel(request, clock.dt)),
        control_every_(override_channel_
                           ? std::max<long long>(1, std::llround(request.override_loop.period_s / clock.dt))
                           : 0),
        contact_(request, layers, clock.steps_per_tooth),
        log_(log, request.options.log_rate_hz),
        progress_(progress) {}

  // Runs every step; gives the log its rows, fills the result's revolutions, max_force_z_n, steps,
  // log_rows and the warning of a run stopped by the override. Returns the time in contact.
  ContactTotals run();

 private:
  static std::optional<FeedOverride> make_override_channel(const SimulationRequest& request, double dt) {
    std::optional<FeedOverride> channel;
    if (request.override_loop.controller) channel.emplace(request.override_loop.channel, dt);
    return channel;
  }
  StepState advance(long long step);
  void record_statistics(const detail::ContactForce& cut, double fxy);
  force_log::ForceLogRow log_row(const StepState& now, const SensorReading& reading) const;
  void control(long long step, const StepState& now, const SensorReading& reading);
  void report_progress();

  const SimulationRequest& request_;
  const MotionProfile& motion_;
  const StepClock& clock_;
  SimulationResult& result_;
  Sensors sensors_;
  std::optional<FeedOverride> override_channel_;
  long long control_every_;
  detail::CutterContact contact_;
  detail::LogResampler log_;
  detail::RunProgress& progress_;
  detail::RevolutionStatistics revolutions_;
  ContactTotals contact_totals_;
  double omega_angle_ = 0.0;     // spindle angle Ω, rad
  double tau_ = 0.0;             // time along the planned motion (differs from t under a feed override)
  double last_direction_ = 0.0;  // feed direction of the last feed move, rad
};

ContactTotals MachineRun::run() {
  // Under a feed override the run takes longer than planned; a controller that holds the feed at
  // zero for more than 100 times the planned duration stops the run with a warning.
  const long long max_steps = override_channel_ ? 100 * clock_.total_steps + 1 : clock_.total_steps;
  for (long long step = 0; step <= max_steps; ++step) {
    const StepState now = advance(step);
    const detail::ContactForce cut =
        now.rpm > 0.0 ? contact_.force(step, now.motion, omega_angle_, last_direction_) : detail::ContactForce{};
    const double fxy = std::hypot(cut.force.fx_n, cut.force.fy_n);
    // P = M ω: torque in N·mm, ω in rad/s.
    const double power_w = cut.force.torque_nmm * 1e-3 * now.rpm * kTwoPi / 60.0;
    const SensorReading reading = sensors_.update(cut.force.fx_n, cut.force.fy_n, cut.force.fz_n, power_w);
    revolutions_.add(now.t_s, omega_angle_, fxy);
    record_statistics(cut, fxy);
    log_.add(log_row(now, reading));
    control(step, now, reading);
    report_progress();
    result_.summary.steps = step + 1;
    if (tau_ >= motion_.duration_s()) break;
    if (step == max_steps) {
      result_.warnings.push_back("the feed override held the machine back for over 100 times the planned cycle "
                                 "time; the run was stopped at s = " + six_digit_number_text(now.motion.s_mm) + " mm");
    }
  }
  result_.revolutions = revolutions_.finish(result_.summary.steps * clock_.dt);
  result_.summary.log_rows = log_.rows();
  progress_.finish();
  return contact_totals_;
}

// The machine one step on: the planned profile, run at the override ratio when a controller is
// active; the spindle turned at the speed of the move; the tool position recorded.
StepState MachineRun::advance(long long step) {
  const geometry::Program& program = request_.program;
  StepState now;
  now.t_s = step * clock_.dt;
  if (step > 0) {
    const double ratio = override_channel_ ? override_channel_->step() : 1.0;
    tau_ = std::min(motion_.duration_s(), tau_ + ratio * clock_.dt);
  }
  now.motion = motion_.state_at_time(tau_);
  const std::size_t mi = std::min(now.motion.move_index, program.path.moves.size() - 1);
  const geometry::Move& move = program.path.moves[mi];
  now.rpm = spindle_rpm_of(program.blocks[mi], request_.options.default_spindle_rpm);
  if (step > 0) omega_angle_ += now.rpm * kTwoPi / 60.0 * clock_.dt;
  contact_.record(omega_angle_, now.motion.position);
  const double direction = geometry::tangent_angle_rad(move, now.motion.fraction);
  if (!std::isnan(direction) && move.kind != geometry::MoveKind::kRapid) last_direction_ = direction;
  return now;
}

// Contact time and force, and the largest axial force, of the true force.
void MachineRun::record_statistics(const detail::ContactForce& cut, double fxy) {
  if (cut.contact) {
    contact_totals_.force_sum_n += fxy;
    ++contact_totals_.steps;
  }
  result_.summary.max_force_z_n = std::max(result_.summary.max_force_z_n, std::abs(cut.force.fz_n));
}

// What the data-acquisition system records at this step.
force_log::ForceLogRow MachineRun::log_row(const StepState& now, const SensorReading& reading) const {
  force_log::ForceLogRow row;
  row.t_s = now.t_s;
  row.x_mm = now.motion.position.x_mm;
  row.y_mm = now.motion.position.y_mm;
  row.z_mm = now.motion.position.z_mm;
  row.fx_n = reading.dynamometer_fx_n;
  row.fy_n = reading.dynamometer_fy_n;
  row.fz_n = reading.dynamometer_fz_n;
  row.feed_mm_per_min = now.motion.speed_mm_per_s * 60.0 * (override_channel_ ? override_channel_->actual() : 1.0);
  row.spindle_rpm = now.rpm;
  row.ix_a = reading.ix_a;
  row.iy_a = reading.iy_a;
  row.iz_a = reading.iz_a;
  return row;
}

// The feedback controller, if any, every control period.
void MachineRun::control(long long step, const StepState& now, const SensorReading& reading) {
  if (!override_channel_ || step % control_every_ != 0) return;
  ControlInput input;
  input.t_s = now.t_s;
  input.reading = reading;
  input.override_ratio = override_channel_->actual();
  input.s_mm = now.motion.s_mm;
  input.spindle_rpm = now.rpm;
  override_channel_->command(request_.override_loop.controller(input));
}

// The fraction of planned time done.
void MachineRun::report_progress() {
  progress_.motion(motion_.duration_s() > 0.0 ? tau_ / motion_.duration_s() : 1.0);
}

// Step 5. The totals of the run.
void summarize(SimulationResult& result, const SimulationRequest& request, const MotionProfile& motion,
               const LayeredEngagement& layers, double layer_mm, double dt, const ContactTotals& contact) {
  SimulationSummary& summary = result.summary;
  summary.cycle_time_s = request.override_loop.controller ? (summary.steps - 1) * dt : motion.duration_s();
  summary.cutting_time_s = motion.time_in_cut_s();
  summary.air_time_s = motion.time_in_air_s();
  summary.time_in_contact_s = contact.steps * dt;
  summary.mean_force_in_contact_n = contact.steps > 0 ? contact.force_sum_n / contact.steps : 0.0;
  for (const auto& rev : result.revolutions) summary.max_revolution_peak_n = std::max(summary.max_revolution_peak_n, rev.peak_xy_n);
  summary.step_s = dt;
  summary.stock_layers = layers.layer_count();
  summary.layer_thickness_mm = layer_mm;
  summary.engagement_bands = layers.band_count();
  summary.engagement_samples = static_cast<long long>(layers.samples_computed());
  summary.recut_tolerance_mm = recut_tolerance_mm(request);
}

}  // namespace

std::vector<InputProblem> validate(const SimulationRequest& request) {
  std::vector<InputProblem> problems;
  check_tool(problems, request.tool);
  check_coefficients(problems, request.coefficients);
  check_options(problems, request.options, request.tool);
  for (auto& p : geometry::validate(request.machine)) problems.push_back(std::move(p));
  for (auto& p : validate(request.sensors)) problems.push_back(std::move(p));
  for (auto& p : geometry::validate(request.stock, "stock")) problems.push_back(std::move(p));
  if (request.override_loop.controller) {
    check_positive(problems, "override.period_s", request.override_loop.period_s, "control period");
  }
  check_program(problems, request.program, request.options.default_spindle_rpm);
  return problems;
}

SimulationResult simulate(const SimulationRequest& request) {
  if (auto problems = validate(request); !problems.empty()) throw InputError(std::move(problems));
  const MotionProfile motion = plan_motion(request.program, request.machine);
  SimulationResult result;
  const double layer_mm = layer_thickness_mm(request.program.path, request.options.layer_thickness_mm);
  const StepClock clock = step_clock(request, motion);
  detail::RunProgress progress(request.progress, clock.total_steps, expected_layers(request, layer_mm),
                               request.options.engagement_ds_mm);
  LayerOptions layer_options;
  layer_options.layer_thickness_mm = layer_mm;
  layer_options.ds_mm = request.options.engagement_ds_mm;
  layer_options.recut_tolerance_mm = recut_tolerance_mm(request);
  layer_options.progress = [&progress](double done_mm, double total_mm) { progress.engagement(done_mm, total_mm); };
  const LayeredEngagement layers(request.program.path, request.stock, request.tool.radius_mm(), layer_options);
  result.warnings = layers.warnings();
  if (auto warning = m4_warning(request.program)) result.warnings.push_back(std::move(*warning));
  start_log(result.log, request, clock.max_rpm);
  force_log::ForceLogInMemory in_memory(result.log);
  force_log::ForceLogSink& sink = request.log_sink ? *request.log_sink : in_memory;
  sink.begin(result.log);
  // Kept whole: room for every row at once (growing by doubling would need up to twice as much).
  if (!request.log_sink) result.log.rows.reserve(static_cast<std::size_t>(motion.duration_s() * request.options.log_rate_hz) + 2);
  MachineRun machine(request, motion, layers, clock, sink, progress, result);
  const ContactTotals contact = machine.run();
  summarize(result, request, motion, layers, layer_mm, clock.dt, contact);
  return result;
}

}  // namespace feedplan::sim
