// Seed 004 §VI (Rubio & De la Sen 2007): the continuous-time force of three controllers on the paper's plant,
// scored by the paper's cost, J_c = Σ_j ∫_{(j−1)T}^{jT} (F_p − F_p,m) dτ, "the area between the continuous-time
// domain system output response and the continuous-time model reference response" — taken here with the
// absolute value the text describes (as printed, without it, overshoot and undershoot would cancel; the
// signed sum is printed too). The paper reports 0.0277 (multi-model scheme 1) < 0.083 (ZOH model reference)
// < 0.2365 (multi-model scheme 2), without units or the figures' numbers.
//
// The run. The plant is MillingPlantParameters' (K_c = 1200 N/mm², 4 teeth, 715 rev/min, τ_m = 0.1 ms from
// the paper; full immersion a = √2 and τ_c = one tooth period chosen), sampled once per revolution, and is
// integrated here by Runge–Kutta (milling_runge_kutta.hpp, 4096 steps per period) — not by the module's
// simulator. Choices where the paper's Fig. 1 and Figs. 4–7 are lost:
//   - from rest, the reference switched to 1.2 kN at the first sample; F_p,m is the continuous reference
//     model's step response (the same truth for all three);
//   - depths of 3, 5, 2 and 4 mm, 30 revolutions (2.5 s) each, changed at a sample;
//   - the controller is told of a new depth one sample after it took effect — it learns it from the force,
//     not from a CAD model; seed 004 reports "large output overshoots" at the depth changes and says that
//     avoiding them needs a priori geometry ([14]); told at once, the overshoots vanish;
//   - scheme 2 starts at β = 1 (NeighbourSearchParameters' default; the paper: "arbitrary").
// The other settings are the paper's: scheme 1's bank 1, 0.9, …, −0.4, residence one period, M = 1, λ = 1;
// scheme 2 Δβ = 0.2, m = 2.
//
// Tolerance. The ordering is asserted strictly. Numerically it is settled: Runge–Kutta's error is some 1e-12
// of the force and the trapezoid rule's on 20 µs steps below 1e-3 N·s over the run, against margins of a few
// N·s. Physically the margin between scheme 1 and the ZOH is thin (well under 1 %): the cost is dominated by
// the depth-change overshoots, which no choice of hold removes.

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
constexpr int kRungeKuttaSteps = 4096;

struct SchemeRun {
  double absolute_cost_n_s = 0.0;  // J_c with |·|
  double signed_cost_n_s = 0.0;    // J_c as printed
  double peak_force_n = 0.0;
  double largest_ratio = 0.0;
  int switches = 0;
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
      if (segment > 0 && k == 1) controller.set_depth_of_cut_mm(depth);
      out.largest_ratio = std::max(out.largest_ratio, controller.step(force, period));
      force = truth.step(plant, reference, controller.commanded_feed_mm_per_s(), controller.previous_commanded_feed_mm_per_s(),
                         controller.active_beta(), p.reference_force_n, period, kRungeKuttaSteps);
      out.peak_force_n = std::max(out.peak_force_n, force);
    }
  }
  out.absolute_cost_n_s = truth.absolute_area_n_s;
  out.signed_cost_n_s = truth.signed_area_n_s;
  out.switches = controller.switches();
  return out;
}

void print(const char* name, const SchemeRun& r) {
  std::printf("%-24s J_c = %.4f kN·s (signed %.4f kN·s), peak force %.0f N, largest override %.2f, %d switches of β\n",
              name, r.absolute_cost_n_s / 1000.0, r.signed_cost_n_s / 1000.0, r.peak_force_n, r.largest_ratio, r.switches);
}

TEST(FrohMillingScenario, SchemeOneBeatsTheZohWhichBeatsSchemeTwo) {
  const FrohModelReferenceParameters scheme1;
  FrohModelReferenceParameters zoh;
  zoh.betas = {0.0};
  FrohModelReferenceParameters scheme2;
  scheme2.scheme = SwitchingScheme::kNeighbourSearch;
  const SchemeRun r1 = run(scheme1), r0 = run(zoh), r2 = run(scheme2);
  print("multi-model scheme 1", r1);
  print("ZOH model reference", r0);
  print("multi-model scheme 2", r2);
  EXPECT_LT(r1.absolute_cost_n_s, r0.absolute_cost_n_s);
  EXPECT_LT(r0.absolute_cost_n_s, r2.absolute_cost_n_s);
  // The override range (0–400 %) never binds, so each loop is the one designed.
  EXPECT_LT(std::max({r1.largest_ratio, r0.largest_ratio, r2.largest_ratio}), 4.0);
  // The overshoots seed 004 describes: the step from 2 to 4 mm doubles the force before the controller knows.
  EXPECT_GT(r0.peak_force_n, 2000.0);
}

}  // namespace
}  // namespace feedplan::control
