#include "feedplan/sim/milling_simulation.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <optional>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/number_text.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/sim/layered_engagement.hpp"
#include "feedplan/sim/milling_forces.hpp"

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

// Tool-centre XY positions by spindle angle over the last few tooth periods, for the displacement
// since earlier tooth passages.
class PassageHistory {
 public:
  explicit PassageHistory(std::size_t capacity) : angle_(capacity), x_(capacity), y_(capacity) {}

  void push(double spindle_angle_rad, double x_mm, double y_mm) {
    head_ = (head_ + 1) % angle_.size();
    angle_[head_] = spindle_angle_rad;
    x_[head_] = x_mm;
    y_[head_] = y_mm;
    size_ = std::min(size_ + 1, angle_.size());
  }

  //! Centre position when the spindle angle was `angle_rad` (linear between steps; the oldest kept
  //! position before the history starts, which is where the tool stood before the program began).
  geometry::Point2 position_at(double angle_rad, std::size_t steps_back_hint) const {
    assert(size_ > 0);
    std::size_t back = std::min(steps_back_hint, size_ - 1);
    // Walk to the newest entry at or before the angle.
    while (back + 1 < size_ && at(back).angle > angle_rad) ++back;
    while (back > 0 && at(back - 1).angle <= angle_rad) --back;
    const Entry older = at(back);
    if (back == 0 || older.angle > angle_rad) return {older.x, older.y};
    const Entry newer = at(back - 1);
    const double span = newer.angle - older.angle;
    const double w = span > 0.0 ? (angle_rad - older.angle) / span : 0.0;
    return {older.x + w * (newer.x - older.x), older.y + w * (newer.y - older.y)};
  }

 private:
  struct Entry {
    double angle;
    double x;
    double y;
  };
  Entry at(std::size_t back) const {
    const std::size_t i = (head_ + angle_.size() - back) % angle_.size();
    return {angle_[i], x_[i], y_[i]};
  }
  std::vector<double> angle_;
  std::vector<double> x_;
  std::vector<double> y_;
  std::size_t head_ = 0;
  std::size_t size_ = 0;
};

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

}  // namespace

std::vector<InputProblem> validate(const SimulationRequest& request) {
  std::vector<InputProblem> problems;
  check_tool(problems, request.tool);
  check_coefficients(problems, request.coefficients);
  check_options(problems, request.options, request.tool);
  for (auto& p : validate(request.machine)) problems.push_back(std::move(p));
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
  const geometry::Program& program = request.program;
  const SimulationOptions& options = request.options;
  const MotionProfile motion = plan_motion(program, request.machine);
  const double r = request.tool.radius_mm();
  const int n = request.tool.flutes;

  SimulationResult result;
  // 1. The stock, layer by layer, with the engagement along the whole path. A helix meets each layer
  //    in turn as it descends; the sum over layers is a quadrature in z whose error shows as a ripple
  //    at the layer-crossing rate, so helices get at least kLayersPerHelixPitch layers per pitch.
  double layer_mm = options.layer_thickness_mm;
  for (const auto& move : program.path.moves) {
    const double dz = std::abs(move.end.z_mm - move.start.z_mm);
    if (move.kind == geometry::MoveKind::kArc && move.cutting && dz > 1e-9) {
      const double pitch = dz * kTwoPi / move.sweep_rad;
      layer_mm = std::min(layer_mm, pitch / kLayersPerHelixPitch);
    }
  }
  const LayeredEngagement layers(program.path, request.stock, r,
                                 {.layer_thickness_mm = layer_mm, .ds_mm = options.engagement_ds_mm});
  result.warnings = layers.warnings();

  // 2. The internal step: a whole number of steps per tooth period at the fastest spindle speed.
  double max_rpm = 0.0;
  bool warned_m4 = false;
  for (std::size_t i = 0; i < program.blocks.size(); ++i) {
    max_rpm = std::max(max_rpm, spindle_rpm_of(program.blocks[i], options.default_spindle_rpm));
    if (!warned_m4 && program.blocks[i].spindle == geometry::SpindleDirection::kCounterClockwise &&
        program.path.moves[i].kind != geometry::MoveKind::kRapid) {
      warned_m4 = true;
      result.warnings.push_back(line_of(program, i) +
                                " M4 (counter-clockwise spindle) on a feed move; simulated as a right-hand cutter "
                                "turning clockwise (M3)");
    }
  }
  if (max_rpm <= 0.0) max_rpm = 1.0;  // rapids only: no cutting, the step only paces the log
  // The step also resolves the fastest enabled sensor: at least four steps per period of its bandwidth.
  const double tooth_angle_rad = kTwoPi / n;
  const double max_omega_rad_per_s = max_rpm * kTwoPi / 60.0;
  double fastest_sensor_hz = request.sensors.dynamometer.bandwidth_hz;
  if (request.sensors.spindle_sensor.enabled) fastest_sensor_hz = std::max(fastest_sensor_hz, request.sensors.spindle_sensor.bandwidth_hz);
  if (request.sensors.servo_current.enabled) fastest_sensor_hz = std::max(fastest_sensor_hz, request.sensors.servo_current.bandwidth_hz);
  const double tooth_period_s = tooth_angle_rad / max_omega_rad_per_s;
  const int steps_per_tooth =
      std::max({1, static_cast<int>(std::lround(tooth_angle_rad / deg_to_rad(options.angle_step_deg))),
                static_cast<int>(std::ceil(tooth_period_s * 4.0 * fastest_sensor_hz))});
  const double dt = tooth_angle_rad / steps_per_tooth / max_omega_rad_per_s;
  const long long total_steps = static_cast<long long>(std::ceil(motion.duration_s() / dt - 1e-9));

  Sensors sensors(request.sensors, dt);
  std::optional<FeedOverride> override_channel;
  if (request.override_loop.controller) override_channel.emplace(request.override_loop.channel, dt);
  const long long control_every =
      override_channel ? std::max<long long>(1, std::llround(request.override_loop.period_s / dt)) : 0;

  // 3. The cutter.
  const CutterGeometry cutter{r, n, request.tool.helix_deg, options.runout_mm};
  const std::size_t previous_teeth = options.runout_mm.empty() ? 1 : static_cast<std::size_t>(n);
  PassageHistory history(static_cast<std::size_t>(steps_per_tooth) * (previous_teeth + 1) * 8 + 16);
  std::vector<geometry::Point2> displacement(previous_teeth);
  std::vector<ForceSlice> slices;
  std::vector<LayeredEngagement::Cursor> cursors(layers.band_count());
  std::vector<std::span<const geometry::EngagedInterval>> band_arcs(layers.band_count());
  std::vector<long long> band_stamp(layers.band_count(), -1);
  const double flute_top = options.flute_length_mm > 0.0 ? options.flute_length_mm : 1e300;

  // 4. Log and statistics.
  force_log::ForceLog& log = result.log;
  log.has_currents = request.sensors.servo_current.enabled;
  log.metadata = {{"source", "feedplan simulate (virtual machine, mechanistic forces)"},
                  {"sample_rate_hz", six_digit_number_text(options.log_rate_hz)},
                  {"tool", request.tool.name.empty() ? "D" + six_digit_number_text(request.tool.diameter_mm)
                                                     : request.tool.name},
                  {"tool_diameter_mm", six_digit_number_text(request.tool.diameter_mm)},
                  {"flutes", std::to_string(n)},
                  {"helix_deg", six_digit_number_text(request.tool.helix_deg)},
                  {"spindle_rpm", six_digit_number_text(max_rpm)}};
  for (const auto& entry : request.log_metadata) log.metadata.push_back(entry);
  const double log_dt = 1.0 / options.log_rate_hz;
  long long next_log = 0;
  force_log::ForceLogRow previous_row;
  bool have_previous_row = false;

  double omega_angle = 0.0;  // spindle angle Ω, rad
  double tau = 0.0;          // time along the planned motion (differs from t under a feed override)
  double last_direction = 0.0;
  int revolution = 0;
  force_log::RevolutionPeak current_rev;
  double rev_sum = 0.0;
  long long rev_steps = 0;
  double contact_force_sum = 0.0;
  long long contact_steps = 0;
  double next_progress = 0.0;
  ControlInput control;

  // Under a feed override the run takes longer than planned; a controller that holds the feed at
  // zero for more than 100 times the planned duration stops the run with a warning.
  const long long max_steps = override_channel ? 100 * total_steps + 1 : total_steps;
  for (long long step = 0; step <= max_steps; ++step) {
    const double t = step * dt;
    // Motion: the planned profile, run at the override ratio when a controller is active.
    if (step > 0) {
      const double ratio = override_channel ? override_channel->step() : 1.0;
      tau = std::min(motion.duration_s(), tau + ratio * dt);
    }
    const MotionState state = motion.state_at_time(tau);
    const std::size_t mi = std::min(state.move_index, program.path.moves.size() - 1);
    const geometry::Move& move = program.path.moves[mi];
    const double rpm = spindle_rpm_of(program.blocks[mi], options.default_spindle_rpm);
    if (step > 0) omega_angle += rpm * kTwoPi / 60.0 * dt;
    history.push(omega_angle, state.position.x_mm, state.position.y_mm);
    const double direction = geometry::tangent_angle_rad(move, state.fraction);
    if (!std::isnan(direction) && move.kind != geometry::MoveKind::kRapid) last_direction = direction;

    // Forces from every layer the flutes reach.
    Force3 force;
    bool contact = false;
    if (rpm > 0.0 && layers.layer_count() > 0) {
      slices.clear();
      const double tip = state.position.z_mm;
      for (int layer = 0; layer < layers.layer_count(); ++layer) {
        const double lo = std::max(layers.layer_bottom_mm(layer), tip);
        const double hi = std::min(layers.layer_top_mm(layer), tip + flute_top);
        if (hi <= lo) continue;
        const int band = layers.band_of(layer);
        if (band_stamp[band] != step) {
          band_arcs[band] = layers.intervals_at(layer, state.s_mm, cursors[band]);
          band_stamp[band] = step;
        }
        if (band_arcs[band].empty()) continue;
        slices.push_back({0.5 * (lo + hi) - tip, hi - lo, band_arcs[band]});
      }
      if (!slices.empty()) {
        for (std::size_t k = 1; k <= previous_teeth; ++k) {
          const geometry::Point2 before =
              history.position_at(omega_angle - static_cast<double>(k) * tooth_angle_rad, k * steps_per_tooth);
          displacement[k - 1] = {state.position.x_mm - before.x_mm, state.position.y_mm - before.y_mm};
        }
        CutterState cutter_state;
        cutter_state.spindle_angle_rad = omega_angle;
        cutter_state.feed_direction_rad = last_direction;
        cutter_state.displacement_since_tooth_mm = displacement;
        force = milling_force(cutter, request.coefficients, cutter_state, slices);
        contact = force.fx_n != 0.0 || force.fy_n != 0.0 || force.fz_n != 0.0;
      }
    }
    const double fxy = std::hypot(force.fx_n, force.fy_n);
    const SensorReading reading = sensors.update(force.fx_n, force.fy_n, force.fz_n);

    // Per-revolution statistics of the true force.
    const int rev_now = static_cast<int>(std::floor(omega_angle / kTwoPi + 1e-9));
    if (rev_now != revolution && rev_steps > 0) {
      current_rev.t_end_s = t;
      current_rev.mean_xy_n = rev_sum / rev_steps;
      current_rev.samples = static_cast<std::size_t>(rev_steps);
      result.revolutions.push_back(current_rev);
      current_rev = force_log::RevolutionPeak{};
      current_rev.revolution = rev_now;
      current_rev.t_start_s = t;
      rev_sum = 0.0;
      rev_steps = 0;
    }
    revolution = rev_now;
    if (fxy > current_rev.peak_xy_n || rev_steps == 0) {
      current_rev.peak_xy_n = fxy;
      current_rev.t_peak_s = t;
    }
    rev_sum += fxy;
    ++rev_steps;
    if (contact) {
      contact_force_sum += fxy;
      ++contact_steps;
    }
    result.summary.max_force_z_n = std::max(result.summary.max_force_z_n, std::abs(force.fz_n));

    // Log rows on the log clock, interpolated between internal steps.
    force_log::ForceLogRow row;
    row.t_s = t;
    row.x_mm = state.position.x_mm;
    row.y_mm = state.position.y_mm;
    row.z_mm = state.position.z_mm;
    row.fx_n = reading.dynamometer_fx_n;
    row.fy_n = reading.dynamometer_fy_n;
    row.fz_n = reading.dynamometer_fz_n;
    row.feed_mm_per_min = state.speed_mm_per_s * 60.0 * (override_channel ? override_channel->actual() : 1.0);
    row.spindle_rpm = rpm;
    row.ix_a = reading.ix_a;
    row.iy_a = reading.iy_a;
    row.iz_a = reading.iz_a;
    while (next_log * log_dt <= t + 1e-12) {
      const double tl = next_log * log_dt;
      if (!have_previous_row || t <= previous_row.t_s) {
        force_log::ForceLogRow out = row;
        out.t_s = tl;
        log.rows.push_back(out);
      } else {
        const double w = (tl - previous_row.t_s) / (t - previous_row.t_s);
        auto mix = [&](double a, double b) { return a + w * (b - a); };
        force_log::ForceLogRow out;
        out.t_s = tl;
        out.x_mm = mix(previous_row.x_mm, row.x_mm);
        out.y_mm = mix(previous_row.y_mm, row.y_mm);
        out.z_mm = mix(previous_row.z_mm, row.z_mm);
        out.fx_n = mix(previous_row.fx_n, row.fx_n);
        out.fy_n = mix(previous_row.fy_n, row.fy_n);
        out.fz_n = mix(previous_row.fz_n, row.fz_n);
        out.feed_mm_per_min = mix(previous_row.feed_mm_per_min, row.feed_mm_per_min);
        out.spindle_rpm = w < 0.5 ? previous_row.spindle_rpm : row.spindle_rpm;
        out.ix_a = mix(previous_row.ix_a, row.ix_a);
        out.iy_a = mix(previous_row.iy_a, row.iy_a);
        out.iz_a = mix(previous_row.iz_a, row.iz_a);
        log.rows.push_back(out);
      }
      ++next_log;
    }
    previous_row = row;
    have_previous_row = true;

    // The feedback controller, if any.
    if (override_channel && step % control_every == 0) {
      control.t_s = t;
      control.reading = reading;
      control.override_ratio = override_channel->actual();
      control.s_mm = state.s_mm;
      control.spindle_rpm = rpm;
      override_channel->command(request.override_loop.controller(control));
    }
    const double done = motion.duration_s() > 0.0 ? tau / motion.duration_s() : 1.0;
    if (request.progress && done >= next_progress) {
      request.progress(done);
      next_progress = done + 0.01;
    }
    result.summary.steps = step + 1;
    if (tau >= motion.duration_s()) break;
    if (step == max_steps) {
      result.warnings.push_back("the feed override held the machine back for over 100 times the planned cycle "
                                "time; the run was stopped at s = " + six_digit_number_text(state.s_mm) + " mm");
    }
  }
  if (rev_steps > 0) {
    current_rev.t_end_s = result.summary.steps * dt;
    current_rev.mean_xy_n = rev_sum / rev_steps;
    current_rev.samples = static_cast<std::size_t>(rev_steps);
    result.revolutions.push_back(current_rev);
  }
  if (request.progress) request.progress(1.0);

  SimulationSummary& summary = result.summary;
  summary.cycle_time_s = override_channel ? (result.summary.steps - 1) * dt : motion.duration_s();
  summary.cutting_time_s = motion.time_in_cut_s();
  summary.air_time_s = motion.time_in_air_s();
  summary.time_in_contact_s = contact_steps * dt;
  summary.mean_force_in_contact_n = contact_steps > 0 ? contact_force_sum / contact_steps : 0.0;
  for (const auto& rev : result.revolutions) summary.max_revolution_peak_n = std::max(summary.max_revolution_peak_n, rev.peak_xy_n);
  summary.step_s = dt;
  summary.stock_layers = layers.layer_count();
  summary.layer_thickness_mm = layer_mm;
  summary.engagement_bands = layers.band_count();
  return result;
}

}  // namespace feedplan::sim
