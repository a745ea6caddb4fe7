#pragma once
// Test helper: seed 000/001's Fig. 4 scenario — the depth of cut changed in steps while a force controller
// holds the reference — run on the seeds' own plant (control::TurningProcess), sampled every Δt = 0.1 s.
//
// Fig. 4 itself is lost with the seeds' figures; its caption and text keep the shape: steps of the depth
// up to a large depth, where the conventional ACC turns unstable (Fig. 5), and back down to small depths,
// where the estimate of K_m misbehaves for a large c1 (Fig. 11). Reconstructed here as 1 → 2 → 4 → 2 → 1 mm,
// 5 s each. With the default TurningProcess (K_p = 4 N per mm/min per mm of depth) and F_R = 1000 N the
// feed that holds F_R is 250, 125, 62.5, 125, 250 mm/min; the programmed feed is 200 mm/min, so the
// 0–150 % override spans 0–300 mm/min and holds every one of them.

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "feedplan/control/turning_process.hpp"

namespace feedplan::control::test {

inline constexpr double kPeriodS = 0.1;               // the seeds' Δt
inline constexpr double kReferenceForceN = 1000.0;    // F_R
inline constexpr double kProgrammedFeedMmPerMin = 200.0;
inline constexpr std::array<double, 5> kDepthsMm{1.0, 2.0, 4.0, 2.0, 1.0};
inline constexpr int kStepsPerSegment = 50;           // 5 s per depth at kPeriodS
inline constexpr int kSteps = kStepsPerSegment * static_cast<int>(kDepthsMm.size());

//! The depth in effect over step k (k = 0 … kSteps − 1).
inline double depth_at_step(int k) { return kDepthsMm[static_cast<std::size_t>(k / kStepsPerSegment)]; }

//! What a run recorded, one entry per step: the force at the step's end, the override held over it.
struct ScenarioRun {
  std::vector<double> force_n;
  std::vector<double> override_ratio;
  double absolute_error_n_s = 0.0;  //!< Fig. 12's criterion: Σ |F − F_R| Δt over the run, N·s
};

//! Runs the scenario with `controller` (measured force, Δt → override ratio), the plant starting in steady
//! state at 1 mm depth with the force at F_R.
inline ScenarioRun run_step_depth_scenario(const std::function<double(double, double)>& controller) {
  const TurningProcessParameters plant_parameters;
  const double start_feed = kReferenceForceN / process_gain_n_per_mm_per_min(plant_parameters, kDepthsMm[0]);
  TurningProcess plant(plant_parameters, kPeriodS, kDepthsMm[0], start_feed);
  ScenarioRun run;
  double force = plant.force_n();
  for (int k = 0; k < kSteps; ++k) {
    plant.set_depth_mm(depth_at_step(k));
    const double ratio = controller(force, kPeriodS);
    force = plant.step(ratio * kProgrammedFeedMmPerMin);
    run.force_n.push_back(force);
    run.override_ratio.push_back(ratio);
    run.absolute_error_n_s += std::abs(force - kReferenceForceN) * kPeriodS;
  }
  return run;
}

//! Largest |F − F_R| over steps [first, last), N.
inline double max_error_n(const ScenarioRun& run, int first, int last) {
  double worst = 0.0;
  for (int k = first; k < last; ++k) worst = std::max(worst, std::abs(run.force_n[static_cast<std::size_t>(k)] - kReferenceForceN));
  return worst;
}

}  // namespace feedplan::control::test
