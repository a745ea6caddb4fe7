// measured_revolutions on a log of the virtual machine (a short corner-rounding cycle, samples/corner.yaml
// with 8 mm walls and 6 mm axial depth, planned with a hand-made model). Oracles: the simulator's own
// per-revolution true peaks (SimulationResult::revolutions: unfiltered, noise-free, every internal step),
// its motion (sim::plan_motion) for where and how fast the tool was, and the analytic straight-cut
// engagement of docs/method.md §5.1 (cos α = 1 − R_d / r, t_m = f sin α, L = r α) on the first wall.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

#include "../planner/test_models.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/core/angle.hpp"
#include "feedplan/learning/measured_revolutions.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/peak_comparison.hpp"
#include "feedplan/sim/material.hpp"
#include "feedplan/sim/milling_simulation.hpp"
#include "feedplan/sim/motion_profile.hpp"

namespace feedplan::learning {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kFlutes = 4;
constexpr double kRpm = 2800.0;
constexpr double kToolRadiusMm = 5.0;
constexpr double kRadialDepthMm = 1.5;
constexpr double kAxialDepthMm = 6.0;
constexpr double kLogRateHz = 50000.0;

struct CornerRun {
  cycles::CycleSpec spec;
  planner::PlanResult plan;
  model::ResponseSurfaceModel model;
  sim::SimulationResult result;
  sim::MotionProfile motion;
  Alignment alignment;
};

// The corner cycle planned, cut on the virtual machine (tooth j cutting at r + runout_mm[j] when given)
// and its log aligned.
CornerRun simulate_corner(const std::vector<double>& runout_mm) {
  cycles::CycleSpec spec = cycles::load_cycle_spec(FEEDPLAN_SAMPLES_DIR "/corner.yaml");
  spec.axial_depth_mm = kAxialDepthMm;
  std::get<cycles::CornerSpec>(spec.geometry).wall_length_mm = 8.0;
  const cycles::Cycle cycle = cycles::generate(spec);
  planner::PlanSettings settings;
  settings.model = planner::testing::s50c_like_model();
  settings.target_force_n = spec.target_force_n;
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  planner::PlanResult plan = planner::plan(planner::analyse(cycle.path, cycle.stock, cycle.tool, 0.05), settings);

  const sim::MaterialLibrary materials = sim::load_materials(FEEDPLAN_SAMPLES_DIR "/../data/materials.yaml");
  sim::SimulationRequest request;
  request.program = plan.program;
  request.tool = spec.tool;
  request.coefficients = materials.get(spec.material).coefficients;
  request.stock = cycle.stock;
  request.machine = spec.machine;
  request.options.default_spindle_rpm = spec.spindle_rpm;
  request.options.layer_thickness_mm = 1.0;
  request.options.runout_mm = runout_mm;
  request.sensors.dynamometer.noise_n = 2.0;
  // A near-ideal dynamometer, so its peaks are the true ones: a tooth entering the material at full
  // chip (down milling) is a force step, which a 3 kHz sensor rounds off by up to 14 % in the short
  // pulses of a small engagement and a flat (ζ = 1/√2) one overshoots by 4 %; critically damped at
  // 20 kHz, logged at 50 kHz, the peaks stay within a few per cent of the true ones.
  request.sensors.dynamometer.bandwidth_hz = 20000.0;
  request.sensors.dynamometer.damping_ratio = 1.0;
  request.options.log_rate_hz = kLogRateHz;
  sim::SimulationResult result = sim::simulate(request);
  sim::MotionProfile motion = sim::plan_motion(request.program, request.machine);
  Alignment alignment = align_log(result.log, plan);
  return CornerRun{spec, std::move(plan), settings.model, std::move(result), std::move(motion), std::move(alignment)};
}

const CornerRun& run() {
  static const CornerRun r = simulate_corner({});
  return r;
}

// The simulator's true peak of the revolution starting at t_start_s (its revolutions start on its
// internal steps, at most one step after t0 + k T).
const force_log::RevolutionPeak* true_revolution(double t_start_s) {
  for (const auto& rev : run().result.revolutions) {
    if (std::abs(rev.t_start_s - t_start_s) < 1e-4) return &rev;
  }
  return nullptr;
}

// The machine's largest speed over [t0_s, t0_s + span_s], mm/s.
double fastest_mm_per_s(double t0_s, double span_s) {
  double fastest = 0.0;
  for (int k = 0; k <= 20; ++k) fastest = std::max(fastest, run().motion.state_at_time(t0_s + span_s * k / 20).speed_mm_per_s);
  return fastest;
}

// The analytic straight cut on the walls (docs/method.md §5.1).
double wall_engagement_rad() { return std::acos(1.0 - kRadialDepthMm / kToolRadiusMm); }

// True when the plan has the straight-wall engagement all over [s0, s1].
bool on_steady_wall(double s0_mm, double s1_mm) {
  bool any = false;
  for (const auto& sample : run().plan.samples) {
    if (sample.s_mm < s0_mm - 0.1 || sample.s_mm > s1_mm + 0.1) continue;
    if (std::abs(sample.engagement_rad - wall_engagement_rad()) > 1e-4) return false;
    any = true;
  }
  return any;
}

TEST(MeasuredRevolutions, PeaksAreTheSimulatorsAndInputsTheAnalyticStraightCut) {
  ASSERT_EQ(run().alignment.status, AlignmentStatus::kOk) << run().alignment.message;
  MeasuredRevolutionOptions raw;  // the measured peaks as they are (the transfer: next tests)
  raw.transfer_to_model = false;
  const MeasuredRevolutions m =
      measured_revolutions(run().result.log, run().alignment, run().plan, run().model, kFlutes, kRpm, raw);
  ASSERT_GT(m.samples.size(), 20u) << m.message;
  ASSERT_EQ(m.samples.size(), m.sample_t_start_s.size());
  EXPECT_EQ(m.skipped_nan, 0);
  const double period_s = 60.0 / kRpm;
  int steady = 0;
  std::vector<double> errors;
  for (std::size_t k = 0; k < m.samples.size(); ++k) {
    const LearningSample& sample = m.samples[k];
    const double t0 = m.sample_t_start_s[k];
    const force_log::RevolutionPeak* truth = true_revolution(t0);
    ASSERT_NE(truth, nullptr) << "t " << t0;
    // The dynamometer (2 N noise) against the true force at every internal step: within 6 % where the
    // force changes inside the window (the tool entering or leaving; the simulator's window starts up to
    // one internal step later), the median within 1 % (below).
    const double error = sample.force_n / truth->peak_xy_n - 1.0;
    EXPECT_NEAR(error, 0.0, 0.06) << "t " << t0;
    errors.push_back(std::abs(error));
    // The middle of the path the machine covered in the revolution (the estimated force delay — the true
    // one is a fraction of a millisecond — moves it by |delay| times the speed there).
    const double s0 = run().motion.state_at_time(t0).s_mm;
    const double s1 = run().motion.state_at_time(t0 + period_s).s_mm;
    EXPECT_NEAR(sample.s_mm, 0.5 * (s0 + s1), 0.05 + std::abs(run().alignment.delay_s) * fastest_mm_per_s(t0, period_s))
        << "t " << t0;
    if (!on_steady_wall(s0, s1)) continue;
    ++steady;
    const double feed_mm_per_min = run().motion.state_at_time(t0 + 0.5 * period_s).speed_mm_per_s * 60.0;
    const double f_z_mm = feed_mm_per_min / (kFlutes * kRpm);
    EXPECT_NEAR(sample.chip_mm, f_z_mm * std::sin(wall_engagement_rad()), 0.005 * sample.chip_mm) << "t " << t0;
    EXPECT_NEAR(sample.contact_length_mm, kToolRadiusMm * wall_engagement_rad(), 1e-3);
    // The plan predicted the same feed there.
    const auto& planned = *std::min_element(
        run().plan.samples.begin(), run().plan.samples.end(),
        [&](const auto& a, const auto& b) { return std::abs(a.s_mm - sample.s_mm) < std::abs(b.s_mm - sample.s_mm); });
    EXPECT_NEAR(sample.chip_mm, planned.chip_thickness_mm, 0.01 * planned.chip_thickness_mm);
  }
  EXPECT_GE(steady, 10);
  std::nth_element(errors.begin(), errors.begin() + static_cast<long>(errors.size() / 2), errors.end());
  EXPECT_LT(errors[errors.size() / 2], 0.01);  // median |error|
}

TEST(MeasuredRevolutions, EveryAlignedRevolutionIsThereForThePeakComparison) {
  const MeasuredRevolutions m =
      measured_revolutions(run().result.log, run().alignment, run().plan, run().model, kFlutes, kRpm);
  const double period_s = 60.0 / kRpm;
  const double duration_s = run().result.log.rows.back().t_s - run().result.log.rows.front().t_s;
  // Complete windows of force_log::revolution_peaks' rule; all aligned (the log starts and ends on the path)
  // but the first, which the estimated force delay may move before the log's start.
  const int complete = static_cast<int>(std::floor(duration_s / period_s + 1e-6));
  EXPECT_NEAR(static_cast<double>(m.revolutions.size()), complete, 1.0);
  EXPECT_LE(m.skipped_not_aligned, 1);
  EXPECT_EQ(static_cast<int>(m.revolutions.size()), static_cast<int>(m.samples.size()) + m.skipped_not_engaged);
  for (const auto& rev : m.revolutions) EXPECT_LE(rev.s_start_mm, rev.s_end_mm);
  const planner::PeakComparison c = planner::compare_peaks(run().plan, run().spec.target_force_n, m.revolutions);
  EXPECT_GE(c.in_cut, static_cast<int>(m.samples.size()));
}

TEST(MeasuredRevolutions, ForceDelayIsUndoneWhenPlacingRevolutions) {
  force_log::ForceLog log = run().result.log;
  const std::size_t shift = static_cast<std::size_t>(std::lround(0.05 * kLogRateHz));  // forces lag by 50 ms
  for (std::size_t i = log.rows.size(); i-- > 0;) {
    log.rows[i].fx_n = i < shift ? 0.0 : log.rows[i - shift].fx_n;
    log.rows[i].fy_n = i < shift ? 0.0 : log.rows[i - shift].fy_n;
  }
  const Alignment alignment = align_log(log, run().plan);
  ASSERT_NEAR(alignment.delay_s, 0.05, 0.005) << alignment.message;
  const MeasuredRevolutions m = measured_revolutions(log, alignment, run().plan, run().model, kFlutes, kRpm);
  ASSERT_GT(m.samples.size(), 20u);
  const double period_s = 60.0 / kRpm;
  auto true_middle_mm = [&](double t_start_s) {  // where the machine was when the force was made
    return 0.5 * (run().motion.state_at_time(t_start_s - 0.05).s_mm +
                  run().motion.state_at_time(t_start_s - 0.05 + period_s).s_mm);
  };
  for (std::size_t k = 0; k < m.samples.size(); ++k) {
    const double t0 = m.sample_t_start_s[k] - 0.05;
    EXPECT_NEAR(m.samples[k].s_mm, true_middle_mm(m.sample_t_start_s[k]),
                0.05 + std::abs(alignment.delay_s - 0.05) * fastest_mm_per_s(t0, period_s));
  }
  // Without the shift the places would be 50 ms of travel (over a millimetre) late.
  Alignment unshifted = alignment;
  unshifted.delay_s = 0.0;
  const MeasuredRevolutions late = measured_revolutions(log, unshifted, run().plan, run().model, kFlutes, kRpm);
  double largest_miss = 0.0;
  for (std::size_t k = 0; k < late.samples.size(); ++k) {
    largest_miss = std::max(largest_miss, std::abs(late.samples[k].s_mm - true_middle_mm(late.sample_t_start_s[k])));
  }
  EXPECT_GT(largest_miss, 1.0);
}

TEST(MeasuredRevolutions, FeedFromTheAlignmentWhenTheLogHasNone) {
  force_log::ForceLog log = run().result.log;
  for (auto& row : log.rows) row.feed_mm_per_min = kNaN;
  const MeasuredRevolutions with =
      measured_revolutions(run().result.log, run().alignment, run().plan, run().model, kFlutes, kRpm);
  const MeasuredRevolutions without =
      measured_revolutions(log, run().alignment, run().plan, run().model, kFlutes, kRpm);
  ASSERT_EQ(with.samples.size(), without.samples.size());
  int steady = 0;
  for (std::size_t k = 0; k < with.samples.size(); ++k) {
    const double period_s = 60.0 / kRpm;
    const double t0 = with.sample_t_start_s[k];
    if (!on_steady_wall(run().motion.state_at_time(t0).s_mm, run().motion.state_at_time(t0 + period_s).s_mm)) continue;
    ++steady;
    EXPECT_NEAR(without.samples[k].chip_mm, with.samples[k].chip_mm, 0.01 * with.samples[k].chip_mm);
  }
  EXPECT_GE(steady, 10);
}

TEST(MeasuredRevolutions, ForcesTransferToTheModelsStraightCutUnlessAskedNot) {
  // On the steady 6 mm wall the planner puts the chip-load transfer on the 10 mm model (feed_limit.hpp):
  // the 10 mm cut's 30° flute spans 66° of immersion, more than the wall's α = 45.6°, the 6 mm cut's
  // w = 6 tan β / r = 39.7°, so the peak chip held at once is (cos(π − α) − cos(π − α + w)) / (1 − cos α)
  // of the 10 mm cut's (the closed form of FeedPlan.AxialDepthScalesTheForceByTheChipLoad), not 6/10.
  MeasuredRevolutionOptions raw;
  raw.transfer_to_model = false;
  const MeasuredRevolutions scaled =
      measured_revolutions(run().result.log, run().alignment, run().plan, run().model, kFlutes, kRpm);
  const MeasuredRevolutions unscaled =
      measured_revolutions(run().result.log, run().alignment, run().plan, run().model, kFlutes, kRpm, raw);
  ASSERT_EQ(scaled.samples.size(), unscaled.samples.size());
  const double alpha = wall_engagement_rad();
  const double w = kAxialDepthMm * std::tan(30.0 * kPi / 180.0) / kToolRadiusMm;
  const double ratio = (std::cos(kPi - alpha) - std::cos(kPi - alpha + w)) / (1.0 - std::cos(alpha));
  ASSERT_GT(ratio, kAxialDepthMm / 10.0);
  int steady = 0;
  for (std::size_t k = 0; k < scaled.samples.size(); ++k) {
    EXPECT_GT(scaled.samples[k].force_n, 0.0);
    const double t0 = scaled.sample_t_start_s[k];
    if (!on_steady_wall(run().motion.state_at_time(t0).s_mm, run().motion.state_at_time(t0 + 60.0 / kRpm).s_mm)) continue;
    ++steady;
    // The peak over the spindle angle is sampled (geometry::kChipLoadSteps per tooth period): within 0.5 %.
    EXPECT_NEAR(scaled.samples[k].force_n * ratio, unscaled.samples[k].force_n, 0.005 * unscaled.samples[k].force_n);
  }
  EXPECT_GE(steady, 10);
}

TEST(MeasuredRevolutions, ARevolutionWithANanForceIsSkipped) {
  const MeasuredRevolutions all =
      measured_revolutions(run().result.log, run().alignment, run().plan, run().model, kFlutes, kRpm);
  force_log::ForceLog log = run().result.log;
  // A row in the middle of the sixth sample's revolution.
  const double t = all.sample_t_start_s[5] + 0.5 * 60.0 / kRpm;
  for (auto& row : log.rows) {
    if (std::abs(row.t_s - t) < 0.5 / kLogRateHz) row.fx_n = kNaN;
  }
  const MeasuredRevolutions m =
      measured_revolutions(log, align_log(log, run().plan), run().plan, run().model, kFlutes, kRpm);
  EXPECT_EQ(m.skipped_nan, 1);
  EXPECT_EQ(m.samples.size() + 1, all.samples.size());
  for (double t0 : m.sample_t_start_s) EXPECT_NE(t0, all.sample_t_start_s[5]);
}

TEST(MeasuredRevolutions, AnUnusableAlignmentGivesNoSamples) {
  Alignment alignment = run().alignment;
  alignment.status = AlignmentStatus::kNotThisProgram;
  const MeasuredRevolutions m =
      measured_revolutions(run().result.log, alignment, run().plan, run().model, kFlutes, kRpm);
  EXPECT_TRUE(m.samples.empty());
  EXPECT_TRUE(m.revolutions.empty());
  EXPECT_NE(m.message.find("not usable"), std::string::npos);
}

TEST(MeasuredRevolutions, BadArgumentsAreInputErrors) {
  const auto& r = run();
  EXPECT_THROW(measured_revolutions(r.result.log, r.alignment, r.plan, r.model, 0, kRpm), InputError);
  EXPECT_THROW(measured_revolutions(r.result.log, r.alignment, r.plan, r.model, kFlutes, 0.0), InputError);
  force_log::ForceLog currents_only = r.result.log;
  currents_only.has_forces = false;
  EXPECT_THROW(measured_revolutions(currents_only, r.alignment, r.plan, r.model, kFlutes, kRpm), InputError);
}

// The engaged revolution sample of `m` whose revolution holds the time t_s, or nullptr.
const LearningSample* revolution_at(const MeasuredRevolutions& m, double t_s) {
  for (std::size_t i = 0; i < m.samples.size(); ++i) {
    if (m.sample_t_start_s[i] <= t_s && t_s < m.sample_t_start_s[i] + 60.0 / kRpm) return &m.samples[i];
  }
  return nullptr;
}

TEST(MeasuredRevolutions, ToothPeriodsDivideEachRevolutionIntoZ) {
  MeasuredRevolutionOptions raw;  // measured peaks (the transfer factor differs between places)
  raw.transfer_to_model = false;
  const MeasuredRevolutions m =
      measured_revolutions(run().result.log, run().alignment, run().plan, run().model, kFlutes, kRpm, raw);
  ASSERT_GT(m.tooth_periods.size(), kFlutes * m.samples.size() / 2) << m.message;
  for (std::size_t k = 0; k < m.tooth_periods.size(); ++k) {
    const ToothPeriodPeak& p = m.tooth_periods[k];
    EXPECT_LE(p.s_start_mm, p.s_peak_mm + 1e-9);
    EXPECT_LE(p.s_peak_mm, p.s_end_mm + 1e-9);
    if (k > 0 && p.window == m.tooth_periods[k - 1].window + 1) {
      EXPECT_NEAR(p.s_start_mm, m.tooth_periods[k - 1].s_end_mm, 1e-9);  // one path, no gaps
    }
  }
  // Every tooth period's peak is at most its revolution's (the largest force over a whole turn), and
  // within the sensor noise of it on the steady wall, where all flutes cut alike.
  int compared = 0;
  for (const auto& p : m.tooth_periods) {
    const LearningSample* revolution = revolution_at(m, p.t_peak_s);
    if (revolution == nullptr) continue;
    EXPECT_LE(p.sample.force_n, revolution->force_n * (1.0 + 1e-12)) << "window " << p.window;
    if (!on_steady_wall(revolution->s_mm - 0.3, revolution->s_mm + 0.3)) continue;
    EXPECT_NEAR(p.sample.force_n, revolution->force_n, 0.02 * revolution->force_n) << "window " << p.window;
    ++compared;
  }
  EXPECT_GT(compared, 40);
  // Without runout every flute cuts alike: factors of 1 up to the sensor noise (2 N on ~1 kN peaks).
  for (const auto& p : m.tooth_periods) {
    EXPECT_GE(p.runout_factor, 1.0);
    EXPECT_LT(p.runout_factor, 1.02) << "window " << p.window;
  }
}

TEST(MeasuredRevolutions, RunoutFactorTurnsEachToothPeriodIntoItsRevolutionsPeak) {
  // Tooth 0 cuts 8 µm outside the others (chips of ±16 % at f_z ≈ 0.05 mm on the wall).
  const CornerRun with = simulate_corner({0.008, 0.0, 0.0, 0.0});
  ASSERT_EQ(with.alignment.status, AlignmentStatus::kOk) << with.alignment.message;
  const MeasuredRevolutions m = measured_revolutions(with.result.log, with.alignment, with.plan, with.model, kFlutes, kRpm);
  double largest_factor = 0.0;
  for (const auto& p : m.tooth_periods) largest_factor = std::max(largest_factor, p.runout_factor);
  EXPECT_GT(largest_factor, 1.1);
  // On the steady wall every tooth period × its factor stands for the peak of its revolution.
  int checked = 0, short_of_it = 0;
  for (const auto& p : m.tooth_periods) {
    const LearningSample* revolution = revolution_at(m, p.t_peak_s);
    if (revolution == nullptr || !on_steady_wall(revolution->s_mm - 0.3, revolution->s_mm + 0.3)) continue;
    const double stands_for = p.sample.force_n * p.runout_factor;
    EXPECT_NEAR(stands_for, revolution->force_n, 0.03 * revolution->force_n) << "window " << p.window;
    if (p.sample.force_n < 0.95 * revolution->force_n) ++short_of_it;
    ++checked;
  }
  EXPECT_GT(checked, 40);
  EXPECT_GT(short_of_it, checked / 3);  // the factor matters: most flutes' own peaks are 8–19 % short
}

}  // namespace
}  // namespace feedplan::learning
