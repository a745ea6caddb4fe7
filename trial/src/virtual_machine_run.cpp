#include "feedplan/trial/virtual_machine_run.hpp"

#include <algorithm>
#include <cmath>

#include "feedplan/core/input_error.hpp"
#include "feedplan/sim/motion_profile.hpp"

namespace feedplan::trial {

namespace {

// A program point within this of the plan's end point is the plan's end (rounding at the writer's finest
// decimals, 6, moves a point by well under it), mm.
constexpr double kPlanEndToleranceMm = 1e-3;

// A force log nobody reads: the run's peaks and summary are all that is kept.
class RowsDropped final : public force_log::ForceLogSink {
 public:
  void begin(const force_log::ForceLog&) override {}
  void add(const force_log::ForceLogRow&) override {}
};

// Where the plan's path ends in `program`'s motion, mm of its path length: the end of the last move that
// ends at the plan's end point (within the grid the program's coordinates were written on). Moves after
// it — the return to the machine's Z home the G-code writer ends a program with, read back as a park —
// are not the plan's. The whole length when no move ends there.
double plan_end_s_mm(const geometry::Program& program, const sim::MotionProfile& motion, const planner::PlanResult& plan) {
  if (plan.program.path.moves.empty()) return motion.length_mm();
  const geometry::Point3& end = plan.program.path.moves.back().end;
  const double tolerance_mm = std::max(program.coordinate_resolution_mm, kPlanEndToleranceMm);
  const auto& moves = program.path.moves;
  for (std::size_t i = moves.size(); i-- > 0;) {
    const geometry::Point3& p = moves[i].end;
    if (std::hypot(std::hypot(p.x_mm - end.x_mm, p.y_mm - end.y_mm), p.z_mm - end.z_mm) <= tolerance_mm) {
      const sim::MoveTiming& timing = motion.moves()[i];
      return timing.start_s_mm + timing.length_mm;
    }
  }
  return motion.length_mm();
}

}  // namespace

void use_machine_file(VirtualMachine& machine, const sim::MachineFile& file, const geometry::Tool& tool) {
  sim::SimulationRequest physics;
  physics.tool = tool;
  if (auto problems = sim::apply_machine(file, physics); !problems.empty()) throw InputError(std::move(problems));
  machine.tool = physics.tool;
  machine.coefficients = physics.coefficients;
  machine.runout_mm = physics.options.runout_mm;
  machine.sensors.dynamometer = physics.sensors.dynamometer;
}

model::MechanisticModel own_physics(const VirtualMachine& machine) {
  const sim::CuttingCoefficients& k = machine.coefficients;
  model::MechanisticModel out;
  out.ktc_n_per_mm2 = k.ktc_n_per_mm2;
  out.krc_n_per_mm2 = k.krc_n_per_mm2;
  out.kac_n_per_mm2 = k.kac_n_per_mm2;
  out.kte_n_per_mm = k.kte_n_per_mm;
  out.kre_n_per_mm = k.kre_n_per_mm;
  out.kae_n_per_mm = k.kae_n_per_mm;
  out.size_exponent = k.size_exponent;
  out.size_reference_chip_mm = k.size_reference_chip_mm;
  out.size_min_chip_mm = k.size_min_chip_mm;
  out.runout_mm = machine.runout_mm;
  out.helix_deg = machine.tool.helix_deg;
  return out;
}

learning::SensorDynamics dynamometer_mode(const sim::DynamometerOptions& dynamometer) {
  const double zeta = dynamometer.damping_ratio;
  const double a = 1.0 - 2.0 * zeta * zeta;
  return {dynamometer.bandwidth_hz / std::sqrt(a + std::sqrt(a * a + 1.0)), zeta};
}

sim::SimulationResult simulate_on(const geometry::Program& program, const VirtualMachine& machine) {
  sim::SimulationRequest request;
  request.program = program;
  request.tool = machine.tool;
  request.coefficients = machine.coefficients;
  request.stock = machine.stock;
  request.machine = machine.machine;
  request.options.default_spindle_rpm = machine.spindle_rpm;
  request.sensors = machine.sensors;
  request.options.runout_mm = machine.runout_mm;
  request.progress = machine.progress;
  request.override_loop = machine.override_loop;
  RowsDropped dropped;
  if (!machine.keep_log) request.log_sink = &dropped;
  if (machine.log_sink) request.log_sink = machine.log_sink;
  return sim::simulate(request);
}

VirtualMachineRun run_on_virtual_machine(const geometry::Program& program, const VirtualMachine& machine,
                                         const planner::PlanResult& plan, double target_force_n) {
  VirtualMachineRun run;
  run.simulation = simulate_on(program, machine);

  const sim::MotionProfile motion = sim::plan_motion(program, machine.machine);
  const double offset_mm = plan.samples.empty() ? 0.0 : plan_end_s_mm(program, motion, plan) - plan.samples.back().s_mm;
  std::vector<planner::MeasuredRevolution> revolutions;
  revolutions.reserve(run.simulation.revolutions.size());
  for (const force_log::RevolutionPeak& peak : run.simulation.revolutions) {
    revolutions.push_back({motion.state_at_time(peak.t_start_s).s_mm - offset_mm,
                           motion.state_at_time(peak.t_end_s).s_mm - offset_mm, peak.peak_xy_n});
  }
  run.comparison = planner::compare_peaks(plan, target_force_n, revolutions);
  return run;
}

}  // namespace feedplan::trial
