// The virtual machine end to end: cutting tests against the closed-form mean forces (docs/method.md
// §6.1, closed_form_forces.hpp), steady per-revolution peaks on straight cuts and internal arcs,
// a helix cutting layer by layer, determinism, the feed override loop and bad requests.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "closed_form_forces.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/sim/cutting_test.hpp"
#include "feedplan/sim/milling_simulation.hpp"

namespace feedplan::sim {
namespace {

constexpr double kPi = std::numbers::pi;

SimulationRequest cutting_test_request(double ae_mm, MillingMode mode, double fz_mm, double rpm) {
  const geometry::Tool tool{"D10 Z4", 10.0, 4, 30.0};
  CuttingTest test;
  test.radial_depth_mm = ae_mm;
  test.axial_depth_mm = 10.0;
  test.spindle_rpm = rpm;
  test.feed_mm_per_min = fz_mm * tool.flutes * rpm;
  test.cut_length_mm = 40.0;
  test.mode = mode;
  CuttingTestSetup setup = make_cutting_test(test, tool);
  SimulationRequest request;
  request.program = setup.program;
  request.stock = setup.stock;
  request.tool = tool;
  request.coefficients = al7075();
  request.machine.max_accel_mm_per_s2 = 2000;
  return request;
}

// Mean of the logged dynamometer force over whole tooth periods while the tool is fully in the cut
// at full speed (x of the centre in [r + 2, L − r − 2]).
MeanForce steady_mean(const SimulationResult& result, double feed_mm_per_min, double tooth_period_s, double x_lo,
                      double x_hi) {
  double t0 = -1.0, t1 = -1.0;
  for (const auto& row : result.log.rows) {
    if (row.x_mm >= x_lo && row.x_mm <= x_hi && std::abs(row.feed_mm_per_min - feed_mm_per_min) < 1e-6 * feed_mm_per_min) {
      if (t0 < 0) t0 = row.t_s;
      t1 = row.t_s;
    }
  }
  EXPECT_GT(t1 - t0, 20 * tooth_period_s);
  const double periods = std::floor((t1 - t0) / tooth_period_s);
  t1 = t0 + periods * tooth_period_s;
  MeanForce mean;
  int count = 0;
  for (const auto& row : result.log.rows) {
    if (row.t_s < t0 || row.t_s >= t1) continue;
    mean.fx_n += row.fx_n;
    mean.fy_n += row.fy_n;
    ++count;
  }
  mean.fx_n /= count;
  mean.fy_n /= count;
  return mean;
}

TEST(MillingSimulation, CuttingTestsMatchTheClosedFormMeanForces) {
  struct Case {
    const char* name;
    double ae_mm;
    MillingMode mode;
  };
  const Case cases[] = {{"down a_e 1.5 (Al7075 check of docs/method.md §6.1)", 1.5, MillingMode::kDown},
                        {"up a_e 1.5", 1.5, MillingMode::kUp},
                        {"down a_e 4", 4.0, MillingMode::kDown},
                        {"up a_e 3", 3.0, MillingMode::kUp},
                        {"full slot", 10.0, MillingMode::kDown}};
  const double rpm = 2800;
  const double fz = 0.1;
  for (const auto& c : cases) {
    const SimulationRequest request = cutting_test_request(c.ae_mm, c.mode, fz, rpm);
    const SimulationResult result = simulate(request);
    const double alpha = std::acos(1 - std::min(c.ae_mm, 10.0) / 5.0);
    const bool down = c.mode == MillingMode::kDown;
    const double st = c.ae_mm >= 10 ? 0.0 : (down ? kPi - alpha : 0.0);
    const double ex = c.ae_mm >= 10 ? kPi : (down ? kPi : alpha);
    const MeanForce truth = closed_form_mean(4, 10, fz, st, ex, al7075());
    const MeanForce sim = steady_mean(result, fz * 4 * rpm, 60.0 / (4 * rpm), 7.0, 33.0);
    std::printf("%-36s simulated Fx %8.2f Fy %8.2f N | closed form %8.2f %8.2f N | deviation %.3f%% %.3f%%\n", c.name,
                sim.fx_n, sim.fy_n, truth.fx_n, truth.fy_n, 100 * (sim.fx_n - truth.fx_n) / std::abs(truth.fx_n),
                100 * (sim.fy_n - truth.fy_n) / std::abs(truth.fy_n));
    EXPECT_NEAR(sim.fx_n, truth.fx_n, 0.01 * std::abs(truth.fx_n)) << c.name;
    EXPECT_NEAR(sim.fy_n, truth.fy_n, 0.01 * std::abs(truth.fy_n)) << c.name;
  }
}

TEST(MillingSimulation, SpindlePowerMatchesTheClosedFormMeanTorque) {
  // The spindle's cutting power on a straight down cut (a_e 1.5 mm of a D10 Z4 at 2800 rev/min, S50C-like
  // with edge forces) against the mean torque of dF_t = (K_tc h + K_te) dz over a revolution:
  // M̄ = N a r / (2π) [K_tc c (cos φ_st − cos φ_ex) + K_te (φ_ex − φ_st)], P̄ = M̄ ω. The readings come through
  // the override loop's input, every step (the power is not in the force log).
  const double rpm = 2800.0, c = 1000.0 / (4 * 2800);
  SimulationRequest request = cutting_test_request(1.5, MillingMode::kDown, c, rpm);
  request.coefficients = CuttingCoefficients{};
  request.coefficients.ktc_n_per_mm2 = 2000;
  request.coefficients.krc_n_per_mm2 = 600;
  request.coefficients.kte_n_per_mm = 20;
  request.sensors.spindle_power.enabled = true;
  std::vector<std::pair<double, double>> power;  // t, W
  request.override_loop.period_s = 1e-9;        // every step
  request.override_loop.controller = [&power](const ControlInput& in) {
    power.emplace_back(in.t_s, in.reading.spindle_power_w);
    return 1.0;
  };
  const SimulationResult result = simulate(request);
  double t0 = -1.0, t1 = -1.0;
  for (const auto& row : result.log.rows) {
    if (row.x_mm >= 7.0 && row.x_mm <= 33.0 && std::abs(row.feed_mm_per_min - 1000.0) < 1e-6) {
      if (t0 < 0) t0 = row.t_s;
      t1 = row.t_s;
    }
  }
  const double revolution_s = 60.0 / rpm;
  t1 = t0 + std::floor((t1 - t0) / revolution_s) * revolution_s;
  ASSERT_GT(t1 - t0, 10 * revolution_s);
  double sum = 0.0;
  int count = 0;
  for (const auto& [t, w] : power) {
    if (t < t0 || t >= t1) continue;
    sum += w;
    ++count;
  }
  const double st = kPi - std::acos(0.7), ex = kPi, a_mm = 10.0, r_mm = 5.0;
  const double torque_nmm = 4 * a_mm * r_mm / (2 * kPi) *
                            (2000.0 * c * (std::cos(st) - std::cos(ex)) + 20.0 * (ex - st));
  const double truth_w = torque_nmm * 1e-3 * rpm * 2 * kPi / 60.0;
  std::printf("spindle power: simulated mean %.1f W, closed form %.1f W\n", sum / count, truth_w);
  EXPECT_NEAR(sum / count, truth_w, 0.01 * truth_w);
}

// Largest relative spread (max − min) / mean of the per-revolution peaks of the revolutions that
// lie wholly inside [t_lo, t_hi].
double peak_spread(const SimulationResult& result, double t_lo, double t_hi, int& count) {
  double lo = 1e300, hi = 0.0, sum = 0.0;
  count = 0;
  for (const auto& rev : result.revolutions) {
    if (rev.t_start_s < t_lo || rev.t_end_s > t_hi) continue;
    lo = std::min(lo, rev.peak_xy_n);
    hi = std::max(hi, rev.peak_xy_n);
    sum += rev.peak_xy_n;
    ++count;
  }
  return count > 0 ? (hi - lo) / (sum / count) : 1.0;
}

TEST(MillingSimulation, DesignMagnitudeCheckForSteel) {
  // docs/method.md §6.2: S50C-like Ktc 2000, Krc 0.3 Ktc (no edge forces), D10 Z4, 2800 rpm, a_p 10, a_e 1.5,
  // 1000 mm/min → mean |F| ≈ 350 N, peak ≈ 480–490 N, the magnitude seed 003 reports.
  SimulationRequest request = cutting_test_request(1.5, MillingMode::kDown, 1000.0 / (4 * 2800), 2800);
  request.coefficients = CuttingCoefficients{};
  request.coefficients.ktc_n_per_mm2 = 2000;
  request.coefficients.krc_n_per_mm2 = 600;
  const SimulationResult result = simulate(request);
  const double c = 1000.0 / (4 * 2800);
  const MeanForce truth = closed_form_mean(4, 10, c, kPi - std::acos(0.7), kPi, request.coefficients);
  const MeanForce sim = steady_mean(result, 1000, 60.0 / (4 * 2800), 7.0, 33.0);
  std::printf("S50C-like check: |mean F| %.1f N (closed form %.1f N), max per-revolution peak %.1f N\n",
              std::hypot(sim.fx_n, sim.fy_n), std::hypot(truth.fx_n, truth.fy_n), result.summary.max_revolution_peak_n);
  EXPECT_NEAR(std::hypot(sim.fx_n, sim.fy_n), std::hypot(truth.fx_n, truth.fy_n), 0.01 * std::hypot(truth.fx_n, truth.fy_n));
  EXPECT_NEAR(std::hypot(truth.fx_n, truth.fy_n), 350, 5);
  EXPECT_GT(result.summary.max_revolution_peak_n, 470);
  EXPECT_LT(result.summary.max_revolution_peak_n, 500);
  EXPECT_EQ(result.summary.engagement_bands, 1);  // a 2.5D cut: one engagement computation for all layers
}

TEST(MillingSimulation, PeaksAreSteadyOnAStraightCut) {
  const SimulationRequest request = cutting_test_request(1.5, MillingMode::kDown, 0.1, 2800);
  const SimulationResult result = simulate(request);
  // Centre x in [7, 33] mm at 1120 mm/min after the acceleration.
  double t_lo = 1e300, t_hi = 0.0;
  for (const auto& row : result.log.rows) {
    if (row.x_mm >= 7 && row.x_mm <= 33 && std::abs(row.feed_mm_per_min - 1120) < 1e-6) {
      t_lo = std::min(t_lo, row.t_s);
      t_hi = std::max(t_hi, row.t_s);
    }
  }
  int count = 0;
  const double spread = peak_spread(result, t_lo, t_hi, count);
  std::printf("straight cut: %d steady revolutions, peak spread %.4f%%, peak %.1f N\n", count, 100 * spread,
              result.summary.max_revolution_peak_n);
  EXPECT_GT(count, 20);
  EXPECT_LT(spread, 0.005);
}

geometry::Move line_move(geometry::MoveKind kind, geometry::Point3 a, geometry::Point3 b, bool cutting) {
  geometry::Move m;
  m.kind = kind;
  m.start = a;
  m.end = b;
  m.cutting = cutting;
  m.axial_depth_mm = cutting ? 10 : 0;
  return m;
}

void add_block(geometry::Program& program, double feed, double rpm) {
  geometry::BlockCommand block;
  block.feed_mm_per_min = program.path.moves.back().kind == geometry::MoveKind::kRapid ? 0.0 : feed;
  block.spindle_rpm = rpm;
  block.spindle = geometry::SpindleDirection::kClockwise;
  program.blocks.push_back(block);
}

TEST(MillingSimulation, PeaksAreSteadyOnAnInternalArc) {
  // Finishing a bore from radius 18.5 to 20 mm (a_e 1.5) with the tool centre on radius 15 mm,
  // counter-clockwise (climb milling for M3), entered radially from the bore's centre.
  const double rpm = 3000;
  const double feed = 600;
  SimulationRequest request;
  request.tool = {"D10 Z4", 10.0, 4, 30.0};
  request.coefficients = al7075();
  request.stock.regions.push_back({geometry::Contour::rectangle({-40, -40}, {40, 40}), {geometry::Contour::circle({0, 0}, 18.5)}});
  request.stock.z_top_mm = 0;
  request.stock.z_bottom_mm = -20;
  auto& path = request.program.path;
  path.part_names = {"arc"};
  path.moves.push_back(line_move(geometry::MoveKind::kRapid, {0, 0, 5}, {0, 0, -10}, false));
  add_block(request.program, feed, rpm);
  path.moves.push_back(line_move(geometry::MoveKind::kLine, {0, 0, -10}, {15, 0, -10}, true));
  add_block(request.program, feed, rpm);
  geometry::Move arc;
  arc.kind = geometry::MoveKind::kArc;
  arc.start = {15, 0, -10};
  arc.end = {15, 0, -10};
  arc.center = {0, 0};
  arc.ccw = true;
  arc.sweep_rad = 2 * kPi;
  arc.cutting = true;
  arc.axial_depth_mm = 10;
  path.moves.push_back(arc);
  add_block(request.program, feed, rpm);
  path.moves.push_back(line_move(geometry::MoveKind::kLine, {15, 0, -10}, {0, 0, -10}, false));
  add_block(request.program, feed, rpm);
  request.machine.max_accel_mm_per_s2 = 2000;
  const SimulationResult result = simulate(request);
  // The arc from 60° to 300° is steady (the entry and the tool's own start are behind).
  double t_lo = 1e300, t_hi = 0.0;
  for (const auto& row : result.log.rows) {
    const double angle = std::atan2(row.y_mm, row.x_mm);
    const double a = angle < 0 ? angle + 2 * kPi : angle;
    if (std::hypot(row.x_mm, row.y_mm) > 14.99 && a > kPi / 3 && a < 5 * kPi / 3) {
      t_lo = std::min(t_lo, row.t_s);
      t_hi = std::max(t_hi, row.t_s);
    }
  }
  int count = 0;
  const double spread = peak_spread(result, t_lo, t_hi, count);
  std::printf("internal arc R 20 a_e 1.5: %d steady revolutions, peak spread %.4f%%, peak %.1f N\n", count,
              100 * spread, result.summary.max_revolution_peak_n);
  EXPECT_GT(count, 30);
  EXPECT_LT(spread, 0.005);
  EXPECT_GT(result.summary.max_revolution_peak_n, 100.0);
}

TEST(MillingSimulation, AHelixCutsLayerByLayer) {
  // Helical boring into solid: tool centre on radius 4 mm (hole 18 mm), pitch 1 mm, 5 turns.
  const double rpm = 3000;
  SimulationRequest request;
  request.tool = {"D10 Z4", 10.0, 4, 30.0};
  request.coefficients = al7075();
  request.stock.regions.push_back({geometry::Contour::rectangle({-30, -30}, {30, 30}), {}});
  request.stock.z_top_mm = 0;
  request.stock.z_bottom_mm = -20;
  request.options.layer_thickness_mm = 0.25;  // the helix rule makes it pitch / 20
  auto& path = request.program.path;
  path.part_names = {"helix"};
  path.moves.push_back(line_move(geometry::MoveKind::kRapid, {4, 0, 5}, {4, 0, 0.5}, false));
  add_block(request.program, 300, rpm);
  path.moves.push_back(line_move(geometry::MoveKind::kLine, {4, 0, 0.5}, {4, 0, 0}, false));
  add_block(request.program, 300, rpm);
  geometry::Move helix;
  helix.kind = geometry::MoveKind::kArc;
  helix.start = {4, 0, 0};
  helix.end = {4, 0, -5};
  helix.center = {0, 0};
  helix.ccw = true;
  helix.sweep_rad = 5 * 2 * kPi;
  helix.cutting = true;
  helix.axial_depth_mm = 1;
  path.moves.push_back(helix);
  add_block(request.program, 300, rpm);
  request.machine.max_accel_mm_per_s2 = 2000;
  const SimulationResult result = simulate(request);
  EXPECT_DOUBLE_EQ(result.summary.layer_thickness_mm, 0.05);
  EXPECT_EQ(result.summary.engagement_bands, 100);  // each layer of the helix is its own computation
  // Once the helix is two turns deep the cut is steady: the same layers meet the same material.
  double t_lo = 1e300, t_hi = 0.0;
  for (const auto& row : result.log.rows) {
    if (row.z_mm < -2.2 && row.z_mm > -4.8) {
      t_lo = std::min(t_lo, row.t_s);
      t_hi = std::max(t_hi, row.t_s);
    }
  }
  int count = 0;
  const double spread = peak_spread(result, t_lo, t_hi, count);
  std::printf("helix into solid: %d stock layers, %d engagement bands, steady-turn peak spread %.2f%% over %d revs\n",
              result.summary.stock_layers, result.summary.engagement_bands, 100 * spread, count);
  EXPECT_GT(count, 10);
  EXPECT_LT(spread, 0.04);  // the layer quadrature ripple, ~3 % at 20 layers per pitch
  EXPECT_GT(result.summary.max_force_z_n, 1.0);  // axial force from the flutes in the cut
}

TEST(MillingSimulation, NoiseIsReproducibleFromTheSeed) {
  SimulationRequest request = cutting_test_request(1.5, MillingMode::kDown, 0.05, 6000);
  request.options.log_rate_hz = 2000;
  request.sensors.dynamometer.noise_n = 5.0;
  request.sensors.seed = 7;
  const SimulationResult a = simulate(request);
  const SimulationResult b = simulate(request);
  request.sensors.seed = 8;
  const SimulationResult c = simulate(request);
  ASSERT_EQ(a.log.rows.size(), b.log.rows.size());
  bool differs = false;
  for (std::size_t i = 0; i < a.log.rows.size(); ++i) {
    ASSERT_EQ(a.log.rows[i].fx_n, b.log.rows[i].fx_n);
    differs = differs || a.log.rows[i].fx_n != c.log.rows[i].fx_n;
  }
  EXPECT_TRUE(differs);
}

TEST(MillingSimulation, AFeedOverrideSlowsTheMachineThroughItsLag) {
  SimulationRequest request = cutting_test_request(1.5, MillingMode::kDown, 0.1, 2800);
  const double planned = simulate(request).summary.cycle_time_s;
  request.override_loop.period_s = 0.01;
  request.override_loop.controller = [](const ControlInput&) { return 0.5; };
  const SimulationResult slowed = simulate(request);
  std::printf("override 50 %%: cycle %.3f s instead of %.3f s\n", slowed.summary.cycle_time_s, planned);
  EXPECT_GT(slowed.summary.cycle_time_s, 1.8 * planned);
  // After the dead time and a few time constants the logged feed is half the programmed one.
  bool seen_half = false;
  for (const auto& row : slowed.log.rows) {
    if (row.t_s > 1.0 && row.x_mm > 5 && row.x_mm < 30) {
      EXPECT_NEAR(row.feed_mm_per_min, 560, 1.0);
      seen_half = true;
    }
  }
  EXPECT_TRUE(seen_half);
}

TEST(MillingSimulation, BadRequestsNameTheField) {
  SimulationRequest request = cutting_test_request(1.5, MillingMode::kDown, 0.1, 2800);
  request.tool.flutes = 0;
  request.coefficients.ktc_n_per_mm2 = -5;
  request.options.angle_step_deg = 0;
  request.options.runout_mm = {0.01};
  request.program.blocks[1].spindle = geometry::SpindleDirection::kOff;
  try {
    simulate(request);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string text = e.what();
    for (const char* field : {"tool.flutes", "material.ktc_n_per_mm2", "options.angle_step_deg", "options.runout_mm",
                              "move 1"}) {
      EXPECT_NE(text.find(field), std::string::npos) << field << " missing from:\n" << text;
    }
  }
}

}  // namespace
}  // namespace feedplan::sim
