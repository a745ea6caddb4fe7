// The mechanistic force kernel against the virtual machine (sim), an independent implementation of the
// same physics (docs/method.md §6.1): its instantaneous force on thin slices, and the per-revolution
// peaks of its true force (unfiltered, noise-free) on straight cutting tests, where the stock, not
// this test, decides which arcs are engaged.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <vector>

#include "feedplan/model/mechanistic_force.hpp"
#include "feedplan/sim/cutting_test.hpp"
#include "feedplan/sim/milling_forces.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::model {
namespace {

constexpr double kPi = std::numbers::pi;

sim::CuttingCoefficients sim_coefficients(const MechanisticModel& m) {
  sim::CuttingCoefficients k;
  k.ktc_n_per_mm2 = m.ktc_n_per_mm2;
  k.krc_n_per_mm2 = m.krc_n_per_mm2;
  k.kac_n_per_mm2 = m.kac_n_per_mm2;
  k.kte_n_per_mm = m.kte_n_per_mm;
  k.kre_n_per_mm = m.kre_n_per_mm;
  k.kae_n_per_mm = m.kae_n_per_mm;
  k.size_exponent = m.size_exponent;
  k.size_reference_chip_mm = m.size_reference_chip_mm;
  k.size_min_chip_mm = m.size_min_chip_mm;
  return k;
}

MechanisticModel al7075() {
  MechanisticModel k;
  k.ktc_n_per_mm2 = 796;
  k.krc_n_per_mm2 = 169;
  k.kac_n_per_mm2 = 222;
  k.kte_n_per_mm = 27.7;
  k.kre_n_per_mm = 30.8;
  k.kae_n_per_mm = 1.4;
  return k;
}

// The simulator's force at its spindle angle Ω_s for a straight cut along +x, the flutes on slices of
// `slice_mm` over [0, depth]. Its tooth j at the tip has immersion π/2 + Ω_s − j·2π/N
// (sim/milling_forces.hpp: world angle −Ω_s + j·2π/N, feed along +x), so it is this kernel's Ω = Ω_s + π/2
// with the same tooth numbers.
// The slices of `sections` (whose ends must be whole numbers of slices) with their arcs as the
// simulator's engaged intervals (kept alive in `intervals`).
std::vector<sim::ForceSlice> simulator_slices(std::span<const EngagedSection> sections, double slice_mm,
                                              std::vector<std::vector<geometry::EngagedInterval>>& intervals) {
  intervals.clear();
  for (const EngagedSection& section : sections) {
    intervals.emplace_back();
    for (const ImmersionArc& arc : section.arcs) intervals.back().push_back({arc.entry_rad, arc.exit_rad});
  }
  std::vector<sim::ForceSlice> slices;
  for (std::size_t s = 0; s < sections.size(); ++s) {
    const int first = static_cast<int>(std::round(sections[s].bottom_mm / slice_mm));
    const int last = static_cast<int>(std::round(sections[s].top_mm / slice_mm));
    for (int i = first; i < last; ++i) slices.push_back({(i + 0.5) * slice_mm, slice_mm, intervals[s]});
  }
  return slices;
}

sim::Force3 simulator_force(const MechanisticModel& model, const CutterGeometry& cutter,
                            std::span<const sim::ForceSlice> slices, double fz_mm, double kernel_angle_rad) {
  const sim::CutterGeometry sim_cutter{cutter.radius_mm, cutter.flutes, cutter.helix_deg, model.runout_mm};
  std::vector<geometry::Point2> displacement;
  for (int k = 1; k <= cutter.flutes; ++k) displacement.push_back({k * fz_mm, 0.0});
  sim::CutterState state;
  state.spindle_angle_rad = kernel_angle_rad - kPi / 2;
  state.displacement_since_tooth_mm = displacement;
  return sim::milling_force(sim_cutter, sim_coefficients(model), state, slices);
}

TEST(MechanisticSimulator, RegressorColumnsAreTheSimulatorsForceOfEachCoefficient) {
  // Column i of the regressors is the force of a material whose only coefficient is K_i = 1.
  const CutterGeometry cutter{5.0, 4, 30.0};
  const ImmersionArc arc{kPi - std::acos(1 - 3.0 / 5.0), kPi};
  const std::vector<ImmersionArc> arcs{arc};
  const std::vector<EngagedSection> sections{{0.0, 8.0, arcs}};
  std::vector<std::vector<geometry::EngagedInterval>> intervals;
  const std::vector<sim::ForceSlice> slices = simulator_slices(sections, 0.002, intervals);
  for (const std::vector<double>& runout : {std::vector<double>{}, std::vector<double>{0.008, 0.0, 0.0, 0.0}}) {
    MechanisticModel shape;
    shape.runout_mm = runout;
    for (double angle : {0.3, 1.1, 2.0, 2.9, 4.4}) {
      const ForceRegressors r = regressors(shape, sections, cutter, 0.1, angle);
      for (int i = 0; i < 6; ++i) {
        MechanisticModel unit = shape;
        double* k[] = {&unit.ktc_n_per_mm2, &unit.krc_n_per_mm2, &unit.kac_n_per_mm2,
                       &unit.kte_n_per_mm,  &unit.kre_n_per_mm,  &unit.kae_n_per_mm};
        *k[i] = 1.0;
        const sim::Force3 f = simulator_force(unit, cutter, slices, 0.1, angle);
        // Thin slices: the simulator's midpoint rule is within a slice's share of the cut.
        const double tolerance = 2e-3 * std::max(1.0, std::hypot(f.fx_n, f.fy_n)) * (i < 3 ? 0.1 : 1.0);
        EXPECT_NEAR(r.rows[0][i], f.fx_n, tolerance) << "coefficient " << i << " angle " << angle << " runout " << runout.size();
        EXPECT_NEAR(r.rows[1][i], f.fy_n, tolerance) << "coefficient " << i << " angle " << angle << " runout " << runout.size();
        EXPECT_NEAR(r.rows[2][i], f.fz_n, tolerance) << "coefficient " << i << " angle " << angle << " runout " << runout.size();
      }
    }
  }
}

TEST(MechanisticSimulator, PeakOnLayersWithDifferentArcsMatchesTheSimulatorsForce) {
  // A trochoid-like front on three layers (the upper ones cut back by an earlier pass), one arc reaching
  // behind the tool's left side (φ < 0, where only a tooth with runout cuts), with and without size
  // effect and runout, right- and left-hand helical and straight flutes: the kernel's peak against the largest of the
  // simulator's force sampled every 0.1° of a revolution on 0.01 mm slices.
  const std::vector<ImmersionArc> low{{-0.3, 0.4}, {1.2, 2.9}}, middle{{1.5, 2.9}}, high{{2.0, 2.6}};
  const std::vector<EngagedSection> sections{{0.0, 3.0, low}, {3.0, 6.5, middle}, {6.5, 9.0, high}};
  std::vector<std::vector<geometry::EngagedInterval>> intervals;
  const std::vector<sim::ForceSlice> slices = simulator_slices(sections, 0.01, intervals);
  double worst = 0.0;
  for (double helix : {30.0, 0.0, -30.0}) {
    for (int variant = 0; variant < 3; ++variant) {
      MechanisticModel model = al7075();
      if (variant >= 1) model.runout_mm = {0.008, 0.0, -0.004, 0.0};
      if (variant >= 2) model.size_exponent = 0.25;
      const CutterGeometry cutter{5.0, 4, helix};
      const double kernel = predicted_peak_force_n(model, sections, cutter, 0.06);
      double simulated = 0.0;
      for (int i = 0; i < 3600; ++i) {
        const sim::Force3 f = simulator_force(model, cutter, slices, 0.06, 2 * kPi * i / 3600);
        simulated = std::max(simulated, std::hypot(f.fx_n, f.fy_n));
      }
      worst = std::max(worst, std::abs(kernel - simulated) / simulated);
      EXPECT_NEAR(kernel, simulated, 0.005 * simulated) << "helix " << helix << " variant " << variant;
    }
  }
  std::printf("three layers: worst peak difference to the simulator's force %.3f %%\n", 100 * worst);
}

// The simulator's steady per-revolution peak of a straight cutting test: the median of the true-force
// peaks of the revolutions wholly inside the stretch where the tool is fully in the cut at full feed.
double simulated_steady_peak_n(const MechanisticModel& model, const CutterGeometry& cutter, double ae_mm, double ap_mm,
                               double fz_mm, sim::MillingMode mode) {
  const geometry::Tool tool{"D10 Z4", 2 * cutter.radius_mm, cutter.flutes, cutter.helix_deg};
  sim::CuttingTest test;
  test.radial_depth_mm = ae_mm;
  test.axial_depth_mm = ap_mm;
  test.spindle_rpm = 3000;
  test.feed_mm_per_min = fz_mm * cutter.flutes * test.spindle_rpm;
  test.cut_length_mm = 2 * tool.diameter_mm + 4;
  test.mode = mode;
  const sim::CuttingTestSetup setup = sim::make_cutting_test(test, tool);
  sim::SimulationRequest request;
  request.program = setup.program;
  request.stock = setup.stock;
  request.tool = tool;
  request.coefficients = sim_coefficients(model);
  request.machine.max_accel_mm_per_s2 = 5000;
  request.options.runout_mm = model.runout_mm;
  request.options.angle_step_deg = 0.25;
  request.options.layer_thickness_mm = 0.05;
  request.options.log_rate_hz = 2000;  // the log is only read for the tool's x; the peaks use every step
  const sim::SimulationResult result = sim::simulate(request);
  // The tool is fully in the cut while its centre is in [r + 1, L − r − 1] (entry and exit arcs aside).
  double t_lo = 1e300, t_hi = 0.0;
  for (const auto& row : result.log.rows) {
    if (row.x_mm >= cutter.radius_mm + 1 && row.x_mm <= test.cut_length_mm - cutter.radius_mm - 1 &&
        std::abs(row.feed_mm_per_min - test.feed_mm_per_min) < 1e-6 * test.feed_mm_per_min) {
      t_lo = std::min(t_lo, row.t_s);
      t_hi = std::max(t_hi, row.t_s);
    }
  }
  std::vector<double> peaks;
  for (const auto& rev : result.revolutions) {
    if (rev.t_start_s >= t_lo && rev.t_end_s <= t_hi) peaks.push_back(rev.peak_xy_n);
  }
  EXPECT_GE(peaks.size(), 3u);
  if (peaks.empty()) return 0.0;
  std::sort(peaks.begin(), peaks.end());
  return peaks[peaks.size() / 2];
}

TEST(MechanisticSimulator, PeakPerRevolutionOfStraightCuttingTests) {
  // D10 Z4, helix 30°, Al7075 (the kernel's coefficients are the simulator's), without and with runout
  // and the size effect.
  const CutterGeometry cutter{5.0, 4, 30.0};
  struct Case {
    double ae_mm;
    double ap_mm;
    double fz_mm;
    sim::MillingMode mode;
  };
  const Case cases[] = {{1.5, 10.0, 0.1, sim::MillingMode::kDown},
                        {5.0, 4.0, 0.05, sim::MillingMode::kDown},
                        {10.0, 6.0, 0.08, sim::MillingMode::kDown},
                        {3.0, 8.0, 0.1, sim::MillingMode::kUp}};
  for (int variant = 0; variant < 3; ++variant) {
    MechanisticModel model = al7075();
    if (variant >= 1) model.runout_mm = {0.008, 0.0, 0.0, 0.0};
    if (variant == 2) model.size_exponent = 0.2;
    for (const Case& c : cases) {
      if (variant == 2 && c.mode == sim::MillingMode::kUp) continue;
      const double alpha = std::acos(1 - std::min(c.ae_mm, 10.0) / 5.0);
      const bool down = c.mode == sim::MillingMode::kDown;
      const std::vector<ImmersionArc> arcs{{down ? kPi - alpha : 0.0, down ? kPi : alpha}};
      const std::vector<EngagedSection> sections{{0.0, c.ap_mm, arcs}};
      const double kernel = predicted_peak_force_n(model, sections, cutter, c.fz_mm);
      const double simulated = simulated_steady_peak_n(model, cutter, c.ae_mm, c.ap_mm, c.fz_mm, c.mode);
      const char* physics[] = {"no runout", "runout 8 µm", "runout 8 µm, size effect 0.2"};
      std::printf("a_e %4.1f a_p %4.1f f_z %.2f %s %s: kernel %.2f N, simulator %.2f N (%+.3f %%)\n", c.ae_mm, c.ap_mm,
                  c.fz_mm, down ? "down" : "up  ", physics[variant], kernel, simulated, 100 * (kernel - simulated) / simulated);
      EXPECT_NEAR(kernel, simulated, 0.02 * simulated) << "a_e " << c.ae_mm << " a_p " << c.ap_mm;
    }
  }
}

}  // namespace
}  // namespace feedplan::model
