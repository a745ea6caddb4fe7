#include "plan_check.hpp"

#include <algorithm>

#include "feedplan/gcode/reader.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "feedplan/sim/motion_profile.hpp"

namespace feedplan::cli {

PlanCheck check_on_virtual_machine(const std::string& program_text, const cycles::CycleSpec& spec,
                                   const cycles::Cycle& cycle, const planner::PlanResult& plan, double target_force_n,
                                   const std::string& materials_path) {
  const sim::MaterialLibrary materials = sim::load_materials(materials_path);
  const sim::Material& material = materials.get(spec.material, "material");
  sim::SimulationRequest request;
  request.program = gcode::read_program(program_text, "planned program");
  request.tool = spec.tool;
  request.coefficients = material.coefficients;
  request.stock = cycle.stock;
  request.machine.max_accel_mm_per_s2 = spec.machine.max_accel_mm_per_s2;
  request.machine.rapid_feed_mm_per_min = spec.machine.rapid_feed_mm_per_min;
  request.machine.max_feed_mm_per_min = spec.machine.max_feed_mm_per_min;
  request.options.default_spindle_rpm = spec.spindle_rpm;
  const sim::SimulationResult result = sim::simulate(request);

  // Revolutions onto the path: the machine's motion (the same profile the simulation ran) gives the path
  // length at each revolution's start and end. The program read back starts with the move from the
  // machine's start position to the cycle's first point, which the plan does not have: both end at the
  // same point, so the plan's s is the machine's minus the difference in length.
  const sim::MotionProfile motion = sim::plan_motion(request.program, request.machine);
  const double offset_mm = plan.samples.empty() ? 0.0 : motion.length_mm() - plan.samples.back().s_mm;
  std::vector<planner::MeasuredRevolution> revolutions;
  revolutions.reserve(result.revolutions.size());
  for (const sim::RevolutionPeak& peak : result.revolutions) {
    revolutions.push_back({motion.state_at_time(peak.t_start_s).s_mm - offset_mm,
                           motion.state_at_time(peak.t_end_s).s_mm - offset_mm, peak.peak_xy_n});
  }
  PlanCheck check;
  check.cycle_time_s = result.summary.cycle_time_s;
  check.max_peak_n = result.summary.max_revolution_peak_n;
  check.comparison = planner::compare_peaks(plan, target_force_n, revolutions);
  check.warnings = result.warnings;
  return check;
}

}  // namespace feedplan::cli
