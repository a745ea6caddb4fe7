// Planning with the mechanistic kind (sample_force_model.hpp) checked on the virtual machine: the trochoid
// sample planned at 400 N with the virtual machine's own S50C coefficients (data/materials.yaml: known
// here, not fitted), the written program run on the virtual machine (its own force integration on its
// own layered stock, an ideal sensor), its true per-revolution peaks compared with the target. What is
// left is not the coefficients but the kernel's reading of the path (the samples' spacing, the
// controller's speed): tests/planner/mechanistic_transfer_test.cpp measures it at a constant feed.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "simulator_coefficients.hpp"

namespace feedplan::planner {
namespace {

using testing::mechanistic;

TEST(MechanisticPlan, TheTrochoidHoldsTheTargetOnTheVirtualMachine) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(FEEDPLAN_SAMPLES_DIR "/trochoid.yaml");
  const cycles::Cycle cycle = cycles::generate(spec);
  const PlanGeometry geometry = analyse(cycle.path, cycle.stock, spec.tool, 0.05);
  const sim::MaterialLibrary materials = sim::load_materials(FEEDPLAN_SAMPLES_DIR "/../data/materials.yaml");
  const sim::CuttingCoefficients coefficients = materials.get(spec.material).coefficients;
  const double target_n = 400.0;

  PlanSettings settings;
  settings.model.range = {0.005, 0.1, 1.0, 6.0};  // the tests' range: only read to flag extrapolation
  settings.mechanistic = mechanistic(coefficients);
  settings.target_force_n = target_n;
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  const PlanResult plan_result = plan(geometry, settings);
  ASSERT_NE(plan_result.status, PlanStatus::kUnsafe);
  ASSERT_NE(plan_result.status, PlanStatus::kTargetNotMet);
  EXPECT_LE(plan_result.summary.max_predicted_force_n, target_n * (1.0 + 1e-6));

  sim::SimulationRequest request;
  request.program = plan_result.program;
  request.tool = spec.tool;
  request.coefficients = coefficients;
  request.stock = cycle.stock;
  request.machine = spec.machine;
  request.options.default_spindle_rpm = spec.spindle_rpm;
  const sim::SimulationResult result = sim::simulate(request);

  std::vector<double> errors;
  double largest_n = 0.0;
  for (const auto& rev : result.revolutions) {
    largest_n = std::max(largest_n, rev.peak_xy_n);
    if (rev.peak_xy_n > 0.5 * target_n) errors.push_back(rev.peak_xy_n / target_n - 1.0);
  }
  ASSERT_GT(errors.size(), 300u);
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  std::printf("mechanistic plan on the virtual machine: %zu revolutions above half the target, error percentiles "
              "10/50/90 %.1f / %.1f / %.1f %%, largest peak %.1f N (%+.1f %%), cycle time %.2f s\n",
              errors.size(), 100 * errors[errors.size() / 10], 100 * median, 100 * errors[errors.size() * 9 / 10],
              largest_n, 100 * (largest_n / target_n - 1.0), plan_result.summary.cycle_time_s);
  EXPECT_NEAR(median, 0.0, 0.02);
  EXPECT_LT(errors[errors.size() * 9 / 10], 0.02);
  // Measured +0.9 % (median −0.5 %). Where the machine slows down into a loop front the chip is the
  // distance travelled since the previous tooth, so each force limit is held over one tooth's travel
  // before its place (feed_plan.cpp): without that hold this peak was +27 %. Reading the chip along the
  // tangent instead of the last tooth's chord (tooth_chord.hpp) left +5.7 % here.
  EXPECT_LT(largest_n, 1.03 * target_n);
}

}  // namespace
}  // namespace feedplan::planner
