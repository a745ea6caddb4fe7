// align_log on logs of the virtual machine: a short corner-rounding cycle (samples/corner.yaml with
// shorter walls) planned with a hand-made model and run on the virtual machine. The oracle for s is the
// machine's own motion (sim::plan_motion(program).state_at_time(t).s_mm): the simulated program is the
// plan's, so its s is the plan's s.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <variant>

#include "../planner/test_models.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "feedplan/sim/motion_profile.hpp"

namespace feedplan::learning {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The virtual machine's drives with the spec's feed, acceleration and rapid limits.
geometry::MachineLimits motion_limits(const geometry::MachineLimits& machine) {
  geometry::MachineLimits limits = sim::kVirtualMachineLimits;
  limits.max_accel_mm_per_s2 = machine.max_accel_mm_per_s2;
  limits.rapid_feed_mm_per_min = machine.rapid_feed_mm_per_min;
  limits.max_feed_mm_per_min = machine.max_feed_mm_per_min;
  return limits;
}

// The corner sample with 8 mm walls, 6 mm deep (a_p / a_p,model = 0.6), planned at 350 N.
struct PlannedCorner {
  cycles::CycleSpec spec;
  cycles::Cycle cycle;
  planner::PlanResult plan;
};

PlannedCorner planned_corner(double corner_angle_deg) {
  PlannedCorner c;
  c.spec = cycles::load_cycle_spec(FEEDPLAN_SAMPLES_DIR "/corner.yaml");
  c.spec.axial_depth_mm = 6.0;
  auto& corner = std::get<cycles::CornerSpec>(c.spec.geometry);
  corner.wall_length_mm = 8.0;
  corner.corner_angle_deg = corner_angle_deg;
  c.cycle = cycles::generate(c.spec);
  const planner::PlanGeometry geometry = planner::analyse(c.cycle.path, c.cycle.stock, c.cycle.tool, 0.05);
  planner::PlanSettings settings;
  settings.model = planner::testing::s50c_like_model();
  settings.target_force_n = c.spec.target_force_n;
  settings.spindle_rpm = c.spec.spindle_rpm;
  settings.machine = c.spec.machine;
  c.plan = planner::plan(geometry, settings);
  return c;
}

struct Run {
  PlannedCorner corner;
  sim::SimulationResult result;
  sim::MotionProfile motion;
};

const Run& run() {
  static const Run r = [] {
    PlannedCorner corner = planned_corner(90.0);
    const sim::MaterialLibrary materials = sim::load_materials(FEEDPLAN_SAMPLES_DIR "/../data/materials.yaml");
    sim::SimulationRequest request;
    request.program = corner.plan.program;
    request.tool = corner.spec.tool;
    request.coefficients = materials.get(corner.spec.material).coefficients;
    request.stock = corner.cycle.stock;
    request.machine = motion_limits(corner.spec.machine);
    request.options.default_spindle_rpm = corner.spec.spindle_rpm;
    request.options.layer_thickness_mm = 1.0;
    request.sensors.dynamometer.noise_n = 2.0;
    sim::SimulationResult result = sim::simulate(request);
    sim::MotionProfile motion = sim::plan_motion(request.program, request.machine);
    return Run{std::move(corner), std::move(result), std::move(motion)};
  }();
  return r;
}

// Uniform noise of standard deviation `sigma` from the standardised mt19937 sequence.
class Noise {
 public:
  explicit Noise(std::uint32_t seed) : engine_(seed) {}
  double next(double sigma) {
    const double u = static_cast<double>(engine_()) / 4294967296.0;  // [0, 1)
    return (2.0 * u - 1.0) * sigma * std::sqrt(3.0);
  }

 private:
  std::mt19937 engine_;
};

double true_s(double t_s) { return run().motion.state_at_time(t_s).s_mm; }

struct InCut {
  double first_mm = 0.0, last_mm = 0.0, length_mm = 0.0;
};

// The in-cut stretch as the plan's engaged samples give it.
InCut in_cut(const planner::PlanResult& plan) {
  InCut cut;
  bool any = false;
  for (std::size_t k = 0; k + 1 < plan.samples.size(); ++k) {
    if (!plan.samples[k].engaged && !plan.samples[k + 1].engaged) continue;
    if (!any) cut.first_mm = plan.samples[k].s_mm;
    any = true;
    cut.last_mm = plan.samples[k + 1].s_mm;
    cut.length_mm += plan.samples[k + 1].s_mm - plan.samples[k].s_mm;
  }
  return cut;
}

TEST(LogAlignment, NoisyPositionsGiveTheMachinesArcLength) {
  force_log::ForceLog log = run().result.log;
  Noise noise(20240601);
  for (auto& row : log.rows) {
    row.x_mm += noise.next(0.01);
    row.y_mm += noise.next(0.01);
    row.z_mm += noise.next(0.01);
  }
  // The acquisition started 50 ms before the program, with the machine parked elsewhere.
  force_log::ForceLog early = log;
  early.rows.clear();
  for (int i = 500; i >= 1; --i) {
    force_log::ForceLogRow row;
    row.t_s = -1e-4 * i;
    row.x_mm = -120.0;
    row.y_mm = 80.0;
    row.z_mm = 100.0;
    row.feed_mm_per_min = 0.0;
    row.spindle_rpm = 2800.0;
    early.rows.push_back(row);
  }
  early.rows.insert(early.rows.end(), log.rows.begin(), log.rows.end());

  const Alignment a = align_log(early, run().corner.plan);
  ASSERT_EQ(a.status, AlignmentStatus::kOk) << a.message;
  EXPECT_EQ(a.method, AlignmentMethod::kPositions);
  EXPECT_EQ(a.rows, static_cast<int>(early.rows.size()));
  EXPECT_NEAR(a.covered_fraction, 1.0, 1e-9);
  EXPECT_EQ(a.rows_with_nan, 0);
  EXPECT_EQ(a.gaps, 0);
  EXPECT_NE(a.message.find("500 rows before the path starts"), std::string::npos) << a.message;
  for (int i = 0; i < 500; ++i) EXPECT_TRUE(std::isnan(a.s_mm[static_cast<std::size_t>(i)]));
  double worst = 0.0;
  int aligned = 0;
  for (std::size_t i = 500; i < early.rows.size(); ++i) {
    if (!std::isfinite(a.s_mm[i])) continue;
    ++aligned;
    worst = std::max(worst, std::abs(a.s_mm[i] - true_s(early.rows[i].t_s)));
  }
  EXPECT_EQ(aligned, static_cast<int>(log.rows.size()));
  EXPECT_LT(worst, 0.05);
  // The dynamometer (3 kHz) lags by a fraction of a millisecond; the estimate is late by the force's
  // rise at the slow entry (log_alignment.hpp; the tool enters at 11 mm/s here).
  EXPECT_NEAR(a.delay_s, 0.0, 0.005) << a.message;
}

// A noisy dynamometer (20 N per axis and row) on the same run, whose forces do not lag (the virtual machine's
// dynamometer lags by a fraction of a millisecond): the noise's envelope in the air exceeds 3 % of the cut's
// peak, so air read as contact throughout and no delay could be estimated (50 ms were taken for none). The
// contact threshold stands above the noise read where the plan has the tool in the air; the entry's force
// passes it later than 3 % of the peak, so the estimate comes out late by a few milliseconds (3.3 and 56.0 ms).
TEST(LogAlignment, TheNoiseReadInTheAirDoesNotPassForContact) {
  for (const std::size_t shift : {std::size_t{0}, std::size_t{500}}) {  // rows at 10 kHz
    force_log::ForceLog log = run().result.log;
    for (std::size_t i = log.rows.size(); i-- > 0;) {
      const bool before = i < shift;
      log.rows[i].fx_n = before ? 0.0 : log.rows[i - shift].fx_n;
      log.rows[i].fy_n = before ? 0.0 : log.rows[i - shift].fy_n;
    }
    Noise noise(20261128);
    for (auto& row : log.rows) {
      row.fx_n += noise.next(20.0);
      row.fy_n += noise.next(20.0);
    }
    const Alignment a = align_log(log, run().corner.plan);
    ASSERT_EQ(a.status, AlignmentStatus::kOk) << a.message;
    EXPECT_NEAR(a.delay_s, 1e-4 * static_cast<double>(shift), 0.007) << a.message;
  }
}

TEST(LogAlignment, ForcesLaggingBy50msAreEstimated) {
  force_log::ForceLog log = run().result.log;
  const std::size_t shift = 500;  // 50 ms at 10 kHz
  for (std::size_t i = log.rows.size(); i-- > 0;) {
    const bool before = i < shift;
    log.rows[i].fx_n = before ? 0.0 : log.rows[i - shift].fx_n;
    log.rows[i].fy_n = before ? 0.0 : log.rows[i - shift].fy_n;
    log.rows[i].fz_n = before ? 0.0 : log.rows[i - shift].fz_n;
  }
  const Alignment a = align_log(log, run().corner.plan);
  ASSERT_EQ(a.status, AlignmentStatus::kOk) << a.message;
  EXPECT_NEAR(a.delay_s, 0.050, 0.005) << a.message;
  EXPECT_GT(a.delay_correlation, 0.5);

  AlignmentOptions no_delay;
  no_delay.estimate_delay = false;
  EXPECT_EQ(align_log(log, run().corner.plan, no_delay).delay_s, 0.0);
}

// Forces whose contact has nothing to do with the plan's (bursts of 300 N every 0.6 s, in the air as in the
// cut): the air reads as much force as the cut, no delay is estimated, and the forces stay where the positions
// put them.
TEST(LogAlignment, ForcesAsLargeInTheAirAsInTheCutGiveNoDelay) {
  force_log::ForceLog log = run().result.log;
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    const bool burst = (i / 3000) % 2 == 0;
    log.rows[i].fx_n = burst ? 300.0 : 0.0;
    log.rows[i].fy_n = 0.0;
  }
  const Alignment a = align_log(log, run().corner.plan);
  ASSERT_EQ(a.status, AlignmentStatus::kOk) << a.message;
  EXPECT_EQ(a.delay_s, 0.0) << a.message;
  EXPECT_NE(a.message.find("force delay not estimated (the log reads forces up to 375 N where the plan has the "
                           "tool in the air"),
            std::string::npos)
      << a.message;
}

// Forces whose contact has nothing to do with the plan's, on a log that starts and ends near the stock (no
// air to tell the noise by): no lag explains them, the best correlation is weak, and it is said but not applied.
TEST(LogAlignment, AWeakDelayIsSaidButNotApplied) {
  const Alignment positions = align_log(run().result.log, run().corner.plan);
  double first_engaged_mm = 1e9, last_engaged_mm = -1e9;
  for (const auto& sample : run().corner.plan.samples) {
    if (!sample.engaged) continue;
    first_engaged_mm = std::min(first_engaged_mm, sample.s_mm);
    last_engaged_mm = std::max(last_engaged_mm, sample.s_mm);
  }
  force_log::ForceLog log = run().result.log;
  log.rows.clear();
  for (std::size_t i = 0; i < run().result.log.rows.size(); ++i) {
    const double s_mm = positions.s_mm[i];
    if (!(s_mm > first_engaged_mm - 1.0 && s_mm < last_engaged_mm + 1.0)) continue;
    force_log::ForceLogRow row = run().result.log.rows[i];
    row.fx_n = (i / 3000) % 2 == 0 ? 300.0 : 0.0;
    row.fy_n = 0.0;
    log.rows.push_back(row);
  }
  const Alignment a = align_log(log, run().corner.plan);
  ASSERT_EQ(a.status, AlignmentStatus::kOk) << a.message;
  EXPECT_EQ(a.delay_s, 0.0) << a.message;
  EXPECT_NE(a.message.find("weak: not applied"), std::string::npos) << a.message;
}

TEST(LogAlignment, ALogOfAnotherProgramIsNotThisProgram) {
  // The same corner, but 60° instead of 90°: the same first wall, then another way.
  const PlannedCorner other = planned_corner(60.0);
  const sim::MotionProfile motion = sim::plan_motion(other.plan.program, motion_limits(other.spec.machine));
  force_log::ForceLog log;
  for (double t = 0.0; t <= motion.duration_s(); t += 1e-3) {
    const sim::MotionState state = motion.state_at_time(t);
    force_log::ForceLogRow row;
    row.t_s = t;
    row.x_mm = state.position.x_mm;
    row.y_mm = state.position.y_mm;
    row.z_mm = state.position.z_mm;
    log.rows.push_back(row);
  }
  const Alignment a = align_log(log, run().corner.plan);
  EXPECT_EQ(a.status, AlignmentStatus::kNotThisProgram) << a.message;
  EXPECT_NE(a.message.find("mm from it"), std::string::npos) << a.message;
  EXPECT_NE(a.message.find("row "), std::string::npos) << a.message;
  EXPECT_EQ(a.rows_aligned, 0);

  // Far away altogether: the first row and its distance are named.
  force_log::ForceLog moved = run().result.log;
  for (auto& row : moved.rows) row.x_mm += 200.0;
  const Alignment b = align_log(moved, run().corner.plan);
  EXPECT_EQ(b.status, AlignmentStatus::kNotThisProgram);
  EXPECT_NE(b.message.find("row 1 (t = 0.0000 s) is"), std::string::npos) << b.message;
}

TEST(LogAlignment, PositionsInInchesAreRecognised) {
  force_log::ForceLog log = run().result.log;
  for (auto& row : log.rows) {
    row.x_mm /= 25.4;
    row.y_mm /= 25.4;
    row.z_mm /= 25.4;
  }
  const Alignment a = align_log(log, run().corner.plan);
  EXPECT_EQ(a.status, AlignmentStatus::kUnitsLookWrong) << a.message;
  EXPECT_NE(a.message.find("inches"), std::string::npos);
  EXPECT_EQ(a.rows_aligned, 0);
}

TEST(LogAlignment, ALogEndingInTheMiddleOfTheCutIsTruncated) {
  const InCut cut = in_cut(run().corner.plan);
  ASSERT_GT(cut.length_mm, 20.0);
  const double s_end = cut.first_mm + 0.4 * (cut.last_mm - cut.first_mm);
  force_log::ForceLog log = run().result.log;
  std::size_t keep = 0;
  while (keep < log.rows.size() && true_s(log.rows[keep].t_s) <= s_end) ++keep;
  log.rows.resize(keep);
  const Alignment a = align_log(log, run().corner.plan);
  EXPECT_EQ(a.status, AlignmentStatus::kTruncated) << a.message;
  // The in-cut path is continuous here, so the covered share is the stretch up to s_end.
  EXPECT_NEAR(a.covered_fraction, (s_end - cut.first_mm) / cut.length_mm, 0.01);
  EXPECT_NE(a.message.find("ends before the cut does"), std::string::npos) << a.message;
}

TEST(LogAlignment, ALogStartingInTheMiddleOfTheCutIsAlignedFromThere) {
  const InCut cut = in_cut(run().corner.plan);
  const double s_start = cut.first_mm + 0.5 * (cut.last_mm - cut.first_mm);
  force_log::ForceLog log = run().result.log;
  std::size_t drop = 0;
  while (drop < log.rows.size() && true_s(log.rows[drop].t_s) < s_start) ++drop;
  log.rows.erase(log.rows.begin(), log.rows.begin() + static_cast<long>(drop));
  const Alignment a = align_log(log, run().corner.plan);
  EXPECT_EQ(a.status, AlignmentStatus::kTruncated) << a.message;
  EXPECT_NE(a.message.find("starts after the cut has begun"), std::string::npos) << a.message;
  EXPECT_NEAR(a.covered_fraction, (cut.last_mm - s_start) / cut.length_mm, 0.01);
  EXPECT_EQ(a.rows_aligned, a.rows);
  for (std::size_t i = 0; i < log.rows.size(); ++i)
    EXPECT_NEAR(a.s_mm[i], true_s(log.rows[i].t_s), 0.05) << "row " << i;
}

TEST(LogAlignment, TrochoidLoopsThatCrossEachOtherAreFollowedInOrder) {
  // samples/trochoid.yaml: 1 mm pitch, so each loop passes within 0.5 mm of its neighbours many times.
  const cycles::CycleSpec spec = cycles::load_cycle_spec(FEEDPLAN_SAMPLES_DIR "/trochoid.yaml");
  const cycles::Cycle cycle = cycles::generate(spec);
  planner::PlanSettings settings;
  settings.model = planner::testing::s50c_like_model();
  settings.target_force_n = spec.target_force_n;
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  const planner::PlanResult plan = planner::plan(planner::analyse(cycle.path, cycle.stock, cycle.tool, 0.05), settings);
  ASSERT_GT(plan.samples.back().s_mm, 200.0);  // nine loops of 31 mm
  const sim::MotionProfile motion = sim::plan_motion(plan.program, motion_limits(spec.machine));
  force_log::ForceLog log;
  log.has_forces = false;
  Noise noise(7);
  for (double t = 0.0; t <= motion.duration_s(); t += 5e-4) {
    const sim::MotionState state = motion.state_at_time(t);
    force_log::ForceLogRow row;
    row.t_s = t;
    row.x_mm = state.position.x_mm + noise.next(0.01);
    row.y_mm = state.position.y_mm + noise.next(0.01);
    row.z_mm = state.position.z_mm + noise.next(0.01);
    log.rows.push_back(row);
  }
  const Alignment a = align_log(log, plan);
  ASSERT_EQ(a.status, AlignmentStatus::kOk) << a.message;
  EXPECT_EQ(a.rows_aligned, a.rows);
  EXPECT_NE(a.message.find("the log has no forces"), std::string::npos) << a.message;
  double worst = 0.0;
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    worst = std::max(worst, std::abs(a.s_mm[i] - motion.state_at_time(log.rows[i].t_s).s_mm));
  }
  EXPECT_LT(worst, 0.05);
}

TEST(LogAlignment, ALogOfTheApproachOnlyHasNoCut) {
  const InCut cut = in_cut(run().corner.plan);
  force_log::ForceLog log = run().result.log;
  std::size_t keep = 0;
  while (keep < log.rows.size() && true_s(log.rows[keep].t_s) < cut.first_mm - 1.0) ++keep;
  ASSERT_GT(keep, 100u);
  log.rows.resize(keep);
  const Alignment a = align_log(log, run().corner.plan);
  EXPECT_EQ(a.status, AlignmentStatus::kNoCut) << a.message;
  EXPECT_EQ(a.covered_fraction, 0.0);
  EXPECT_GT(a.rows_aligned, 100);
}

TEST(LogAlignment, NanRowsAreCountedAndSkippedAndGapsCounted) {
  force_log::ForceLog log = run().result.log;
  const std::size_t n = log.rows.size();
  for (std::size_t i : {n / 3, n / 3 + 1, n / 2}) log.rows[i].x_mm = kNaN;
  for (std::size_t i : {n / 4, 2 * n / 3}) log.rows[i].fy_n = kNaN;
  // A 20 ms hole in the data.
  log.rows.erase(log.rows.begin() + static_cast<long>(n / 5), log.rows.begin() + static_cast<long>(n / 5 + 200));
  const Alignment a = align_log(log, run().corner.plan);
  EXPECT_EQ(a.rows_with_nan, 5);
  EXPECT_EQ(a.gaps, 1);
  EXPECT_TRUE(usable(a.status)) << a.message;
  EXPECT_EQ(a.rows_aligned, a.rows - 3);
  for (std::size_t i = 0; i < log.rows.size(); ++i) {
    EXPECT_EQ(std::isnan(log.rows[i].x_mm), std::isnan(a.s_mm[i])) << "row " << i;
  }
}

TEST(LogAlignment, AKistlerExportIsAlignedByThePlansTimeProfile) {
  // As a DynoWare export: no positions, no feed, the acquisition's own clock, started 0.3 s early.
  const force_log::ForceLog& simulated = run().result.log;
  force_log::ForceLog log;
  log.has_positions = false;
  const double clock_offset_s = 12.5;
  for (int i = 3000; i >= 1; --i) {
    force_log::ForceLogRow row;
    row.t_s = clock_offset_s - 1e-4 * i;
    row.x_mm = row.y_mm = row.z_mm = row.feed_mm_per_min = row.spindle_rpm = kNaN;
    row.fx_n = row.fy_n = row.fz_n = 0.0;
    log.rows.push_back(row);
  }
  for (const auto& source : simulated.rows) {
    force_log::ForceLogRow row = source;
    row.t_s += clock_offset_s;
    row.x_mm = row.y_mm = row.z_mm = row.feed_mm_per_min = row.spindle_rpm = kNaN;
    log.rows.push_back(row);
  }
  const Alignment a = align_log(log, run().corner.plan);
  EXPECT_EQ(a.method, AlignmentMethod::kTimeProfile);
  EXPECT_NE(a.message.find("time profile"), std::string::npos);
  ASSERT_EQ(a.status, AlignmentStatus::kOk) << a.message;
  const InCut cut = in_cut(run().corner.plan);
  double worst = 0.0;
  int in_cut_rows = 0;
  for (std::size_t i = 3000; i < log.rows.size(); ++i) {
    const double s = true_s(log.rows[i].t_s - clock_offset_s);
    if (s < cut.first_mm || s > cut.last_mm) continue;
    ++in_cut_rows;
    ASSERT_TRUE(std::isfinite(a.s_mm[i])) << "row " << i;
    worst = std::max(worst, std::abs(a.s_mm[i] - s));
  }
  EXPECT_GT(in_cut_rows, 1000);
  EXPECT_LT(worst, 3.0);
}

TEST(LogAlignment, BadOptionsAndTimeGoingBackAreInputErrors) {
  const force_log::ForceLog& log = run().result.log;
  AlignmentOptions options;
  options.max_distance_mm = 0.0;
  EXPECT_THROW(align_log(log, run().corner.plan, options), InputError);
  force_log::ForceLog backwards = log;
  backwards.rows[10].t_s = backwards.rows[9].t_s;
  try {
    align_log(backwards, run().corner.plan);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("row 11"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace feedplan::learning
