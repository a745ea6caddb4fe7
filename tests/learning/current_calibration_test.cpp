// fit_current_calibration and forces_from_currents on a log of the virtual machine with servo currents
// on: a corner-rounding cycle (samples/corner.yaml, 20 mm walls, 6 mm deep) at a constant feed. The
// oracle is the sensor model's own characteristic (sim/sensors.hpp defaults = seed 002 Eqs. 12–14:
// x 4.12 + 0.00362 F, y 7.24 + 0.00450 F, z 18.5 + 0.00289 F), which the fit never sees.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <variant>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/geometry/program.hpp"
#include "feedplan/learning/current_calibration.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "feedplan/force_log/revolution_peaks.hpp"

namespace feedplan::learning {
namespace {

constexpr double kRpm = 2800.0;

// The cycle's path as a program: every feed move at 1200 mm/min, rapids as rapids, M3 at 2800 rpm.
geometry::Program constant_feed_program(const geometry::ToolPath& path) {
  geometry::Program program;
  program.path = path;
  for (const auto& move : path.moves) {
    geometry::BlockCommand block;
    block.feed_mm_per_min = move.kind == geometry::MoveKind::kRapid ? 0.0 : 1200.0;
    block.spindle_rpm = kRpm;
    block.spindle = geometry::SpindleDirection::kClockwise;
    program.blocks.push_back(block);
  }
  return program;
}

const sim::SimulationResult& run() {
  static const sim::SimulationResult result = [] {
    cycles::CycleSpec spec = cycles::load_cycle_spec(FEEDPLAN_SAMPLES_DIR "/corner.yaml");
    spec.axial_depth_mm = 6.0;
    std::get<cycles::CornerSpec>(spec.geometry).wall_length_mm = 20.0;
    const cycles::Cycle cycle = cycles::generate(spec);
    const sim::MaterialLibrary materials = sim::load_materials(FEEDPLAN_SAMPLES_DIR "/../data/materials.yaml");
    sim::SimulationRequest request;
    request.program = constant_feed_program(cycle.path);
    request.tool = spec.tool;
    request.coefficients = materials.get(spec.material).coefficients;
    request.stock = cycle.stock;
    request.machine.max_accel_mm_per_s2 = spec.machine.max_accel_mm_per_s2;
    request.machine.rapid_feed_mm_per_min = spec.machine.rapid_feed_mm_per_min;
    request.options.layer_thickness_mm = 1.0;
    request.options.log_rate_hz = 5000.0;
    request.sensors.dynamometer.noise_n = 2.0;
    request.sensors.servo_current.enabled = true;  // seed 002's a, b and 62 Hz: the defaults
    request.sensors.servo_current.noise_amp = 0.005;
    return sim::simulate(request);
  }();
  return result;
}

TEST(CurrentCalibration, RecoversTheSensorModelsSeed002Characteristic) {
  const sim::ServoCurrentOptions truth;  // the simulator's defaults
  ASSERT_TRUE(run().log.has_currents);
  const CurrentCalibration c = fit_current_calibration(run().log);
  EXPECT_NEAR(c.x.a_a, truth.x.a_amp, 0.01 * truth.x.a_amp);
  EXPECT_NEAR(c.x.b_a_per_n, truth.x.b_amp_per_n, 0.02 * truth.x.b_amp_per_n);
  EXPECT_NEAR(c.y.a_a, truth.y.a_amp, 0.01 * truth.y.a_amp);
  EXPECT_NEAR(c.y.b_a_per_n, truth.y.b_amp_per_n, 0.02 * truth.y.b_amp_per_n);
  EXPECT_GT(c.x.r_squared, 0.95);
  EXPECT_GT(c.y.r_squared, 0.95);
  EXPECT_GT(c.x.windows, 20);
  // z: the helix pulls along z while cutting, so it is fitted too.
  ASSERT_GT(c.z.windows, 0);
  EXPECT_NEAR(c.z.a_a, truth.z.a_amp, 0.01 * truth.z.a_amp);
  EXPECT_NEAR(c.z.b_a_per_n, truth.z.b_amp_per_n, 0.03 * truth.z.b_amp_per_n);
}

// Mean of |F| per axis over complete revolutions in steady cutting.
struct Means {
  double x = 0.0, y = 0.0;
  double peak_xy = 0.0;
};

Means steady_means(const force_log::ForceLog& log, double t0_s, double t1_s) {
  Means m;
  double sx = 0.0, sy = 0.0;
  int n = 0;
  std::vector<double> t, fx, fy;
  for (const auto& row : log.rows) {
    if (row.t_s < t0_s || row.t_s >= t1_s) continue;
    sx += row.fx_n;
    sy += row.fy_n;
    ++n;
    t.push_back(row.t_s);
    fx.push_back(row.fx_n);
    fy.push_back(row.fy_n);
  }
  m.x = std::abs(sx / n);
  m.y = std::abs(sy / n);
  for (const auto& p : force_log::revolution_peaks(t, fx, fy, kRpm)) m.peak_xy = std::max(m.peak_xy, p.peak_xy_n);
  return m;
}

TEST(CurrentCalibration, ForcesFromCurrentsAreTheMeanForcesNotThePeaks) {
  const CurrentCalibration c = fit_current_calibration(run().log);
  force_log::ForceLog currents_only = run().log;
  currents_only.has_forces = false;
  for (auto& row : currents_only.rows) row.fx_n = row.fy_n = row.fz_n = std::numeric_limits<double>::quiet_NaN();
  const force_log::ForceLog derived = forces_from_currents(currents_only, c);
  EXPECT_TRUE(derived.has_forces);
  EXPECT_TRUE(derived.has_currents);
  EXPECT_NE(derived.metadata_value("forces").find("mean forces"), std::string::npos);
  // The steady stretch of the first wall: whole revolutions where the dynamometer's mean force is flat.
  const double period_s = 60.0 / kRpm;
  double t_first_contact = 0.0;
  for (const auto& row : run().log.rows) {
    if (std::hypot(row.fx_n, row.fy_n) > 50.0) {
      t_first_contact = row.t_s;
      break;
    }
  }
  const double t0 = t_first_contact + 0.3, t1 = t0 + 10 * period_s;  // 6 mm in at 20 mm/s: straight wall
  const Means measured = steady_means(run().log, t0, t1);
  const Means from_currents = steady_means(derived, t0, t1);
  EXPECT_NEAR(from_currents.x, measured.x, 0.03 * measured.x + 2.0);
  EXPECT_NEAR(from_currents.y, measured.y, 0.03 * measured.y + 2.0);
  // The 62 Hz current loop does not pass the 187 Hz tooth peaks.
  EXPECT_LT(from_currents.peak_xy, 0.8 * measured.peak_xy);
}

TEST(CurrentCalibration, ALogWithoutForcesOrCurrentsOrVariationCannotCalibrate) {
  force_log::ForceLog no_currents = run().log;
  no_currents.has_currents = false;
  EXPECT_THROW(fit_current_calibration(no_currents), InputError);
  force_log::ForceLog no_forces = run().log;
  no_forces.has_forces = false;
  EXPECT_THROW(fit_current_calibration(no_forces), InputError);
  // Only the approach through air: no force to fit a slope on.
  force_log::ForceLog air = run().log;
  std::size_t keep = 0;
  while (keep < air.rows.size() && std::hypot(air.rows[keep].fx_n, air.rows[keep].fy_n) < 20.0) ++keep;
  ASSERT_GT(keep, 500u);
  air.rows.resize(keep);
  try {
    fit_current_calibration(air);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("force varies by"), std::string::npos) << e.what();
  }
}

TEST(CurrentCalibration, ForcesFromCurrentsNeedCurrentsAndAPositiveSlope) {
  CurrentCalibration c;
  c.x = {4.12, 0.00362, 1.0, 10};
  c.y = {7.24, 0.0, 1.0, 10};
  EXPECT_THROW(forces_from_currents(run().log, c), InputError);
  c.y.b_a_per_n = 0.0045;
  force_log::ForceLog no_currents = run().log;
  no_currents.has_currents = false;
  EXPECT_THROW(forces_from_currents(no_currents, c), InputError);
  // Hand check of the map on one row: |F| = (I − a) / b.
  force_log::ForceLog one = run().log;
  one.rows.resize(1);
  one.rows[0].ix_a = 4.12 + 0.00362 * 250.0;
  one.rows[0].iy_a = 7.24 + 0.0045 * 100.0;
  const force_log::ForceLog f = forces_from_currents(one, c);
  EXPECT_NEAR(f.rows[0].fx_n, 250.0, 1e-9);
  EXPECT_NEAR(f.rows[0].fy_n, 100.0, 1e-9);
  EXPECT_TRUE(std::isnan(f.rows[0].fz_n));  // no z calibration
}

}  // namespace
}  // namespace feedplan::learning
