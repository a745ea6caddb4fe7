// Seed 004 §VI: the cost of the continuous-time force against the continuous reference model, for the
// multi-model scheme 1, the basic ZOH model-reference controller and the multi-model scheme 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>

#include "feedplan/control/froh_model_reference_controller.hpp"
#include "feedplan/control/milling_plant.hpp"
#include "feedplan/control/reference_model.hpp"
#include "milling_runge_kutta.hpp"

namespace feedplan::control {
namespace {

constexpr std::array<double, 4> kDepthsMm{3.0, 5.0, 2.0, 4.0};
constexpr int kPeriodsPerDepth = 30;
constexpr int kSubsteps = 4096;
int kNotificationDelay = 1;

struct SchemeRun {
  double absolute_cost_n_s = 0.0;
  double signed_cost_n_s = 0.0;
  double peak_force_n = 0.0;
  double largest_ratio = 0.0;
  double smallest_ratio = 1e9;
  int switches = 0;
  std::vector<double> betas;
};

SchemeRun run(const FrohModelReferenceParameters& p) {
  const double period = spindle_period_s(p.plant);
  FrohModelReferenceController controller(p);
  test::ContinuousTruth truth;
  const test::ReferenceOde reference{p.reference_model.damping_ratio, natural_frequency_rad_per_s(p.reference_model, period)};
  SchemeRun out;
  double force = 0.0;
  for (std::size_t segment = 0; segment < kDepthsMm.size(); ++segment) {
    const double depth = kDepthsMm[segment];
    const test::PlantOde plant{process_gain_n_s_per_mm(p.plant, depth), p.plant.feed_drive_time_constant_s,
                               p.plant.cutting_time_constant_s};
    for (int k = 0; k < kPeriodsPerDepth; ++k) {
      if (segment > 0 && k == kNotificationDelay) controller.set_depth_of_cut_mm(depth);
      const double ratio = controller.step(force, period);
      out.largest_ratio = std::max(out.largest_ratio, ratio);
      out.smallest_ratio = std::min(out.smallest_ratio, ratio);
      out.betas.push_back(controller.active_beta());
      force = truth.step(plant, reference, controller.commanded_feed_mm_per_s(), controller.previous_commanded_feed_mm_per_s(),
                         controller.active_beta(), p.reference_force_n, period, kSubsteps);
      out.peak_force_n = std::max(out.peak_force_n, force);
    }
  }
  out.absolute_cost_n_s = truth.absolute_area_n_s;
  out.signed_cost_n_s = truth.signed_area_n_s;
  out.switches = controller.switches();
  return out;
}

void print(const char* name, const SchemeRun& r) {
  std::printf("%-10s J_c = %.5f kN·s (signed %.5f), peak %.0f N, ratio %.3f–%.3f, %d switches, β:", name,
              r.absolute_cost_n_s / 1000.0, r.signed_cost_n_s / 1000.0, r.peak_force_n, r.smallest_ratio, r.largest_ratio,
              r.switches);
  for (std::size_t i = 0; i < r.betas.size(); i += 1) std::printf(" %.2g", r.betas[i]);
  std::printf("\n");
}

TEST(FrohMillingScenario, CostOrdering) {
  FrohModelReferenceParameters scheme1;
  FrohModelReferenceParameters zoh;
  zoh.betas = {0.0};
  FrohModelReferenceParameters scheme2;
  scheme2.scheme = SwitchingScheme::kNeighbourSearch;
  const SchemeRun r1 = run(scheme1), r0 = run(zoh), r2 = run(scheme2);
  print("scheme 1", r1);
  print("ZOH", r0);
  print("scheme 2", r2);
  for (double b0 : {0.0, -0.5, 0.5, -1.0}) {
    FrohModelReferenceParameters s2 = scheme2;
    s2.neighbour_search.initial_beta = b0;
    const SchemeRun r = run(s2);
    std::printf("scheme2 start %.1f: J_c = %.5f switches %d\n", b0, r.absolute_cost_n_s / 1000, r.switches);
  }
  for (int m : {2, 3}) {
    FrohModelReferenceParameters s1 = scheme1;
    s1.index_window_periods = m;
    const SchemeRun r = run(s1);
    std::printf("scheme1 M=%d: J_c = %.5f switches %d\n", m, r.absolute_cost_n_s / 1000, r.switches);
  }
  EXPECT_LT(r1.absolute_cost_n_s, r0.absolute_cost_n_s);
  EXPECT_LT(r0.absolute_cost_n_s, r2.absolute_cost_n_s);
}

}  // namespace
}  // namespace feedplan::control
