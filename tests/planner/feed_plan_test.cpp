// The feed planner against truths it does not compute itself: the closed-form feed on a straight wall
// (docs/method.md §5.1, §5.3), the virtual machine's own controller model (sim::plan_motion, a separate
// implementation of look-ahead under the acceleration limit) for the predicted cycle time and the
// feed actually run, and the statuses for targets the model cannot meet.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "feedplan/core/angle.hpp"
#include "feedplan/core/input_error.hpp"
#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/model/model_prediction.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/speed_profile.hpp"
#include "feedplan/sim/motion_profile.hpp"
#include "test_models.hpp"

namespace feedplan::planner {
namespace {

constexpr double kPi = 3.14159265358979323846;

PlanSettings settings_for(const cycles::CycleSpec& spec, const model::ResponseSurfaceModel& model) {
  PlanSettings settings;
  settings.model = model;
  settings.target_force_n = spec.target_force_n;
  settings.spindle_rpm = spec.spindle_rpm;
  settings.machine = spec.machine;
  return settings;
}

PlanGeometry geometry_for(const cycles::CycleSpec& spec, double ds_mm = 0.05) {
  const cycles::Cycle cycle = cycles::generate(spec);
  return analyse(cycle.path, cycle.stock, spec.tool, ds_mm);
}

geometry::MachineLimits sim_limits(const geometry::MachineLimits& machine) {
  geometry::MachineLimits limits = sim::kVirtualMachineLimits;
  limits.max_accel_mm_per_s2 = machine.max_accel_mm_per_s2;
  limits.rapid_feed_mm_per_min = machine.rapid_feed_mm_per_min;
  limits.max_feed_mm_per_min = machine.max_feed_mm_per_min;
  limits.junction_deviation_mm = 0.0;  // the planner's controller model stops at corners
  limits.limit_centripetal = true;
  return limits;
}

// --- Speed profile ---------------------------------------------------------------------------------

TEST(GreatestSpeeds, StopInTheMiddleGivesTheBrakingParabola) {
  // Caps 100 mm/s everywhere but a stop at s = 5: v(s) = min(100, √(2 a |s − 5|)).
  const double a = 2000.0;
  std::vector<double> s;
  std::vector<double> cap;
  for (int i = 0; i <= 1000; ++i) {
    s.push_back(0.01 * i);
    cap.push_back(i == 500 ? 0.0 : 100.0);
  }
  const std::vector<double> v = greatest_speeds(s, cap, a);
  for (std::size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(v[i], std::min(100.0, std::sqrt(2.0 * a * std::abs(s[i] - 5.0))), 1e-9) << "s = " << s[i];
  }
}

TEST(IntervalTime, TriangleAndTrapezoidMatchKinematics) {
  // From rest to rest over 1 mm at 1000 mm/s²: triangle, t = 2 √(L / a).
  EXPECT_NEAR(interval_time(1.0, 0.0, 0.0, 1e9, 1000.0), 2.0 * std::sqrt(1.0 / 1000.0), 1e-12);
  // Same with a cap of 10 mm/s: 0.01 s up, 0.01 s down (0.05 mm each), 0.9 mm at 10 mm/s.
  EXPECT_NEAR(interval_time(1.0, 0.0, 0.0, 10.0, 1000.0), 0.01 + 0.01 + 0.09, 1e-12);
  // Cruise: L / v.
  EXPECT_NEAR(interval_time(2.0, 10.0, 10.0, 10.0, 1000.0), 0.2, 1e-12);
}

// F of the blocks that run along a straight wall at engagement `alpha`: at least 100 samples at α
// (±1e-6 rad); the stretch entering the stock and the first samples of the arc's rise may belong to them.
std::vector<double> steady_wall_feeds(const PlanResult& result, double alpha) {
  std::vector<double> feeds;
  for (const PlannedBlock& block : result.blocks) {
    int at_alpha = 0;
    for (int i = block.first_sample; i <= block.last_sample; ++i) {
      const PlannedSample& sample = result.samples[static_cast<std::size_t>(i)];
      if (sample.engaged && std::abs(sample.engagement_rad - alpha) < 1e-6) ++at_alpha;
    }
    if (at_alpha >= 100 && block.feed_mm_per_min > 0.0) feeds.push_back(block.feed_mm_per_min);
  }
  return feeds;
}

// --- Closed-form feed on a straight wall -----------------------------------------------------------

TEST(FeedPlan, StraightWallFeedEqualsClosedForm) {
  // Corner rounding, walls at R_d = 1.5 mm with a D10 tool: α_en = acos(1 − R_d/r), t_m = f sin α_en.
  // A linear model F̂ = β0 + β1 (t_m − c1)/s1 gives f = (c1 + s1 (F − β0)/β1) / sin α_en, and F = f Z n.
  const cycles::CycleSpec spec = testing::corner_spec();
  const auto model = testing::s50c_like_model(/*linear=*/true);
  const PlanGeometry geometry = geometry_for(spec);
  const PlanSettings settings = settings_for(spec, model);
  const PlanResult result = plan(geometry, settings);
  ASSERT_EQ(result.status, PlanStatus::kOk) << ::testing::PrintToString(result.messages);

  const double alpha = std::acos(1.0 - 1.5 / 5.0);
  const double t_m = model.chip_center_mm + model.chip_scale_mm * (settings.target_force_n - model.beta[0]) / model.beta[1];
  const double feed_closed_form = t_m / std::sin(alpha) * 4 * 2800.0;
  const std::vector<double> feeds = steady_wall_feeds(result, alpha);
  ASSERT_EQ(feeds.size(), 2u);  // both walls
  // Rounded down to 1 mm/min; where the wall's block ends at the first samples of the slow-down for
  // the arc, their (lower) limit sets F: at most 2 % below (the arc's entry, where the engaged arc
  // grows at the front, is limited through its chip load — feed_limit.hpp — and slows down earlier).
  for (double feed : feeds) {
    EXPECT_LE(feed, feed_closed_form);
    EXPECT_GE(feed, std::floor(feed_closed_form * 0.98));
  }
  EXPECT_EQ(*std::max_element(feeds.begin(), feeds.end()), std::floor(feed_closed_form));
}

// --- Prediction against the virtual machine's controller ------------------------------------------

class PlanAgainstMachine : public ::testing::TestWithParam<const char*> {};

TEST_P(PlanAgainstMachine, CycleTimeAndForceMatchTheVirtualMachinesMotion) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + GetParam());
  const auto model = testing::s50c_like_model();
  const PlanGeometry geometry = geometry_for(spec);
  PlanSettings settings = settings_for(spec, model);
  const PlanResult result = plan(geometry, settings);
  ASSERT_NE(result.status, PlanStatus::kTargetNotMet) << ::testing::PrintToString(result.messages);

  const sim::MotionProfile motion = sim::plan_motion(result.program, sim_limits(spec.machine));
  EXPECT_NEAR(result.summary.cycle_time_s, motion.duration_s(), 2e-3 * motion.duration_s());

  // The force at the speed the virtual machine's controller runs, from the model directly: never
  // above the target (default mode).
  double worst_n = 0.0;
  for (const auto& sample : geometry.engagement.samples) {
    if (!sample.cutting || sample.engagement_rad <= 0.0) continue;
    const double feed_mm_per_min = motion.speed_cap_at(sample.s_mm) * 60.0;
    const double chip = sample.chip_factor * sample.xy_speed_ratio * feed_mm_per_min / (spec.tool.flutes * spec.spindle_rpm);
    double force = model::predict(model, chip, std::max(sample.contact_length_mm, model.range.contact_length_min_mm)).force_n;
    if (model.axial_depth_mm > 0 && sample.axial_depth_mm > 0) force *= sample.axial_depth_mm / model.axial_depth_mm;
    worst_n = std::max(worst_n, force);
  }
  EXPECT_LE(worst_n, settings.target_force_n * (1.0 + 1e-9));
  // …and the plan is not timid: somewhere the force comes within 3 % of the target.
  EXPECT_GE(worst_n, 0.97 * settings.target_force_n);
  // The baseline runs one feed and is slower.
  EXPECT_GT(result.summary.baseline.cycle_time_s, result.summary.cycle_time_s);
}

INSTANTIATE_TEST_SUITE_P(Samples, PlanAgainstMachine,
                         ::testing::Values("corner.yaml", "trochoid.yaml", "spiral.yaml"));

TEST(FeedPlan, SlowsDownBeforeTheArcNotInIt) {
  // Seed 003 Fig. 6: with feedback the force spikes where the straight wall meets the arc; planned
  // ahead, the machine is already at the arc's feed when the engagement rises.
  const cycles::CycleSpec spec = testing::corner_spec();
  const PlanGeometry geometry = geometry_for(spec);
  const PlanResult result = plan(geometry, settings_for(spec, testing::s50c_like_model()));
  double first_arc_limit = 0.0;
  double feed_there = 0.0;
  for (const PlannedSample& sample : result.samples) {
    const auto& move = geometry.path.moves[static_cast<std::size_t>(sample.move_index)];
    if (move.kind == geometry::MoveKind::kArc && sample.engaged) {
      first_arc_limit = sample.feed_limit_mm_per_min;
      feed_there = sample.feed_mm_per_min;
      break;
    }
  }
  ASSERT_GT(first_arc_limit, 0.0);
  EXPECT_LE(feed_there, first_arc_limit);
}

// --- Statuses and bad settings ---------------------------------------------------------------------

TEST(FeedPlan, TargetBelowForceAtMinimumFeedIsReportedNotClamped) {
  const cycles::CycleSpec spec = testing::corner_spec();
  PlanSettings settings = settings_for(spec, testing::s50c_like_model());
  settings.target_force_n = 40.0;  // F̂ at t_m → 0 is ≈ 60–100 N on the walls
  const PlanResult result = plan(geometry_for(spec), settings);
  EXPECT_EQ(result.status, PlanStatus::kTargetNotMet);
  ASSERT_FALSE(result.messages.empty());
  EXPECT_THAT(result.messages.front(), ::testing::HasSubstr("target 40 N not met"));
  EXPECT_GT(result.summary.over_target_samples, 0);
  for (const PlannedBlock& block : result.blocks) {
    if (block.feed_mm_per_min > 0.0) {
      EXPECT_GE(block.feed_mm_per_min, spec.machine.min_feed_mm_per_min);
    }
  }
}

TEST(FeedPlan, MachineMinimumFeedAboveTheNeededFeedIsReported) {
  const cycles::CycleSpec spec = testing::corner_spec();
  PlanSettings settings = settings_for(spec, testing::s50c_like_model());
  settings.machine.min_feed_mm_per_min = 5000.0;  // the target needs ≈ 1400 mm/min on the walls
  const PlanResult result = plan(geometry_for(spec), settings);
  EXPECT_EQ(result.status, PlanStatus::kTargetNotMet);
  EXPECT_THAT(result.messages.front(), ::testing::HasSubstr("minimum feed 5000 mm/min"));
}

TEST(FeedPlan, ModelExtrapolationIsAStatus) {
  const cycles::CycleSpec spec = testing::corner_spec();
  auto model = testing::s50c_like_model();
  model.range.contact_length_max_mm = 2.0;  // the walls have L = 4 mm
  const PlanResult result = plan(geometry_for(spec), settings_for(spec, model));
  EXPECT_EQ(result.status, PlanStatus::kExtrapolated);
  EXPECT_GT(result.summary.extrapolated_samples, 0);
  EXPECT_THAT(::testing::PrintToString(result.messages), ::testing::HasSubstr("extrapolates"));
}

TEST(FeedPlan, AxialDepthScalesTheForceByTheChipLoad) {
  // The same cycle at half the axial depth. Linear scaling would say half the force (the feed for twice
  // the target); but the 10 mm cut the model was fitted at wraps its 30° flute over 66° of immersion,
  // more than the wall's α = 45.6°, while a 5 mm cut wraps 33°: the peak uncut chip held at once is
  // ∫ sin φ dφ / (tan β / r) over the immersions the flute spans inside [π − α, π] (Altintas' flute lag),
  // i.e. (cos(π − α) − cos(π − α + w)) / (1 − cos α) of the 10 mm cut's, w = 5 tan β / r — the force
  // scales by that ratio (feed_limit.hpp, the chip-load transfer), not by 0.5.
  cycles::CycleSpec spec = testing::corner_spec();
  const auto model = testing::s50c_like_model(/*linear=*/true);
  spec.axial_depth_mm = 5.0;
  const PlanResult half = plan(geometry_for(spec), settings_for(spec, model));
  const double alpha = std::acos(1.0 - 1.5 / 5.0);
  const double w = 5.0 * std::tan(deg_to_rad(30.0)) / 5.0;
  const double ratio = (std::cos(kPi - alpha) - std::cos(kPi - alpha + w)) / (1.0 - std::cos(alpha));
  ASSERT_GT(ratio, 0.5);
  const double t_m =
      model.chip_center_mm + model.chip_scale_mm * (spec.target_force_n / ratio - model.beta[0]) / model.beta[1];
  const double expected = t_m / std::sin(alpha) * 4 * 2800.0;
  const std::vector<double> feeds = steady_wall_feeds(half, alpha);
  ASSERT_EQ(feeds.size(), 2u);
  // The peak over the spindle angle is sampled (kChipLoadSteps per tooth period): within 0.5 %.
  EXPECT_NEAR(*std::max_element(feeds.begin(), feeds.end()), expected, 0.005 * expected);
}

TEST(FeedPlan, NonsenseSettingsAreInputErrorsNamingTheField) {
  const cycles::CycleSpec spec = testing::corner_spec();
  const PlanGeometry geometry = geometry_for(spec, 0.2);
  auto expect_field = [&](PlanSettings settings, const std::string& field) {
    try {
      plan(geometry, settings);
      ADD_FAILURE() << "no InputError for " << field;
    } catch (const InputError& error) {
      EXPECT_THAT(error.what(), ::testing::HasSubstr(field));
    }
  };
  PlanSettings base = settings_for(spec, testing::s50c_like_model());
  PlanSettings s = base;
  s.machine.min_feed_mm_per_min = 20000.0;
  expect_field(s, "machine.min_feed_mm_per_min");
  s = base;
  s.machine.max_accel_mm_per_s2 = -1.0;
  expect_field(s, "machine.max_accel_mm_per_s2");
  s = base;
  s.target_force_n = std::nan("");
  expect_field(s, "target_force_n");
  s = base;
  s.spindle_rpm = 0.0;
  expect_field(s, "spindle_rpm");
  s = base;
  s.options.merge_tolerance = 3.0;
  expect_field(s, "options.merge_tolerance");
  s = base;
  s.options.air_feed_mm_per_min = 1e6;
  expect_field(s, "options.air_feed_mm_per_min");
  s = base;
  s.model.chip_scale_mm = 0.0;
  expect_field(s, "model.");
}

TEST(FeedPlan, RegulateModeTracksCloserWithBoundedOvershoot) {
  const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/trochoid.yaml");
  const PlanGeometry geometry = geometry_for(spec);
  PlanSettings settings = settings_for(spec, testing::s50c_like_model());
  const PlanResult safe = plan(geometry, settings);
  settings.options.mode = PlanMode::kRegulate;
  const PlanResult regulate = plan(geometry, settings);
  EXPECT_LE(regulate.summary.cycle_time_s, safe.summary.cycle_time_s);
  EXPECT_LE(regulate.summary.max_predicted_force_n, settings.target_force_n * 1.03);
}

// Controller-friendly blocks on the three samples: every F at most the smallest feed limit of step 1 in its
// block, on the grid of levels below the machine's largest feed (to the F resolution), every block that
// is not a whole move lasting at least the shortest duration at its F; far fewer blocks than the plan
// with every ramp written out, the safety check satisfied. The time it costs: measured 5.3 % on the corner
// (its plunge beside the stock, below the stock's top, runs at the plunge feed: a block of its own) and 1.8 %
// on the spiral; 11 % on the trochoid, whose limits change within a millimetre at the loops'
// entries and exits, where 20 ms blocks cannot follow them (2 ms blocks can).
TEST(FeedPlan, ControllerFriendlyBlocksAreFewLongAndNeverAboveTheLimits) {
  for (const auto& [sample, time_ratio] : {std::pair<const char*, double>{"corner.yaml", 1.06}, {"trochoid.yaml", 1.15},
                                           {"spiral.yaml", 1.02}}) {
    SCOPED_TRACE(sample);
    const cycles::CycleSpec spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + sample);
    const PlanGeometry geometry = geometry_for(spec);
    PlanSettings settings = settings_for(spec, testing::s50c_like_model());
    const PlanResult ramps = plan(geometry, settings);
    settings.options.feed_step = 0.02;
    settings.options.min_block_duration_s = 0.02;
    const PlanResult friendly = plan(geometry, settings);
    ASSERT_NE(friendly.status, PlanStatus::kUnsafe) << friendly.messages.front();
    const double step = settings.options.feed_resolution_mm_per_min;
    const double top = settings.machine.max_feed_mm_per_min;
    std::vector<int> blocks_of_move(geometry.path.moves.size(), 0);
    for (const PlannedBlock& b : friendly.blocks) ++blocks_of_move[static_cast<std::size_t>(b.move_index)];
    for (const PlannedBlock& b : friendly.blocks) {
      if (!(b.feed_mm_per_min > 0.0)) continue;
      double smallest = 1e300;
      for (int i = b.first_sample; i <= b.last_sample; ++i) {
        smallest = std::min(smallest, friendly.samples[static_cast<std::size_t>(i)].feed_limit_mm_per_min);
      }
      EXPECT_LE(b.feed_mm_per_min, std::max(smallest, settings.machine.min_feed_mm_per_min) * (1 + 1e-9));
      if (b.feed_mm_per_min > settings.machine.min_feed_mm_per_min) {
        const double k = std::log(top / b.feed_mm_per_min) / std::log1p(0.02);
        const double level = top * std::pow(1.02, -std::floor(k + 1e-9));
        EXPECT_LT(level - b.feed_mm_per_min, step + 1e-9) << "F " << b.feed_mm_per_min << " is not a level";
      }
      if (blocks_of_move[static_cast<std::size_t>(b.move_index)] > 1) {
        EXPECT_GE(b.length_mm / (b.feed_mm_per_min / 60.0), 0.02 * (1 - 1e-9)) << "a block shorter than 0.02 s";
      }
    }
    EXPECT_LT(friendly.blocks.size(), ramps.blocks.size() * 2 / 3);
    EXPECT_LE(friendly.summary.cycle_time_s, time_ratio * ramps.summary.cycle_time_s);
    EXPECT_LE(friendly.summary.max_predicted_force_n, settings.target_force_n * (1.0 + 1e-9));
    std::printf("%s: %zu blocks, %.2f s with every ramp written out; %zu blocks, %.2f s controller-friendly\n", sample,
                ramps.blocks.size(), ramps.summary.cycle_time_s, friendly.blocks.size(), friendly.summary.cycle_time_s);
  }
}

TEST(FeedPlan, JerkLimitOnlySlowsDown) {
  const cycles::CycleSpec spec = testing::corner_spec();
  const PlanGeometry geometry = geometry_for(spec);
  PlanSettings settings = settings_for(spec, testing::s50c_like_model());
  const PlanResult plain = plan(geometry, settings);
  settings.options.jerk_limit_mm_per_s3 = 50000.0;
  const PlanResult jerk = plan(geometry, settings);
  EXPECT_LT(jerk.summary.accel_used_mm_per_s2, settings.machine.max_accel_mm_per_s2);
  EXPECT_GE(jerk.summary.cycle_time_s, plain.summary.cycle_time_s);
  EXPECT_LE(jerk.summary.max_predicted_force_n, settings.target_force_n * (1.0 + 1e-9));
}

}  // namespace
}  // namespace feedplan::planner

namespace feedplan::planner {
namespace {

TEST(CautiousPlan, HoldsTheUpperBoundAtTheTargetAndTightensWithTheCovariance) {
  const cycles::CycleSpec spec = testing::corner_spec();
  const PlanGeometry geometry = geometry_for(spec);
  PlanSettings settings = settings_for(spec, testing::s50c_like_model());
  const PlanResult plain = plan(geometry, settings);
  ForceUncertainty uncertainty;
  for (std::size_t j = 0; j < 6; ++j) uncertainty.covariance(j, j) = std::pow(0.1 * settings.model.beta[j], 2);
  uncertainty.relative = 0.1;
  settings.uncertainty = uncertainty;
  const PlanResult cautious = plan(geometry, settings);
  for (double& c : settings.uncertainty->covariance.entries()) c *= 0.25;
  settings.uncertainty->relative = 0.05;
  const PlanResult tighter = plan(geometry, settings);
  EXPECT_GT(cautious.summary.cycle_time_s, tighter.summary.cycle_time_s);
  EXPECT_GT(tighter.summary.cycle_time_s, plain.summary.cycle_time_s);
  // Independently of the planner: F̂ + 2σ, σ² = ψᵀCψ + (0.1 F̂)² with C = diag((0.1 β)²), at every engaged
  // sample at the feed the plan runs, never above the target, and close to it somewhere.
  const auto& model = settings.model;
  double worst = 0.0;
  for (std::size_t i = 0; i < cautious.samples.size(); ++i) {
    const PlannedSample& p = cautious.samples[i];
    if (!p.engaged) continue;
    const double length = std::max(p.contact_length_mm, model.range.contact_length_min_mm);
    const auto psi = model::regressors(model, p.chip_thickness_mm, length);
    double variance = 0.0;
    for (int j = 0; j < 6; ++j) variance += std::pow(0.1 * model.beta[j] * psi[j], 2);
    const double force = model::predict(model, p.chip_thickness_mm, length).force_n;
    variance += std::pow(0.1 * force, 2);
    worst = std::max(worst, force + 2.0 * std::sqrt(variance));
  }
  EXPECT_LE(worst, settings.target_force_n * (1.0 + 1e-6));
  EXPECT_GE(worst, settings.target_force_n * 0.97);
}

TEST(CautiousPlan, OffStraightCutMultipliesTheBoundByTheChipAreaRatio) {
  const cycles::CycleSpec spec = testing::corner_spec();
  const PlanGeometry geometry = geometry_for(spec);
  PlanSettings settings = settings_for(spec, testing::s50c_like_model());
  settings.uncertainty = ForceUncertainty{};
  settings.uncertainty->relative = 0.1;
  const PlanResult straight = plan(geometry, settings);
  settings.uncertainty->off_straight_cut = true;
  const PlanResult entries = plan(geometry, settings);
  // The corner's wall entry is off the straight cuts; the walls and the arc are not.
  int off = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < entries.samples.size(); ++i) {
    const PlannedSample& p = entries.samples[i];
    if (!p.engaged) continue;
    const double rho = geometry.engagement.samples[i].chip_area_ratio;
    if (rho > 1.05) ++off;
    // Independently: ρ · (F̂ + 2 · 0.1 F̂) at the feed the plan runs never exceeds the target.
    const double length = std::max(p.contact_length_mm, settings.model.range.contact_length_min_mm);
    const double force = model::predict(settings.model, p.chip_thickness_mm, length).force_n;
    worst = std::max(worst, rho * 1.2 * force);
  }
  EXPECT_GT(off, 10);
  EXPECT_LE(worst, settings.target_force_n * (1.0 + 1e-6));
  EXPECT_GT(entries.summary.cycle_time_s, straight.summary.cycle_time_s);
  EXPECT_LT(entries.summary.cycle_time_s, 1.2 * straight.summary.cycle_time_s);  // only the entries slow down
}

TEST(CautiousPlan, BadUncertaintyIsAnInputError) {
  const cycles::CycleSpec spec = testing::corner_spec();
  PlanSettings settings = settings_for(spec, testing::s50c_like_model());
  settings.uncertainty = ForceUncertainty{};
  settings.uncertainty->sigmas = -1.0;
  settings.uncertainty->covariance(1, 1) = std::nan("");
  try {
    plan(geometry_for(spec, 0.2), settings);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("uncertainty.sigmas"));
    EXPECT_THAT(error.what(), ::testing::HasSubstr("uncertainty.covariance[7]"));
  }
}

}  // namespace
}  // namespace feedplan::planner
