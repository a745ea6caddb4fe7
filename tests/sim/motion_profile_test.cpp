// The virtual machine's feed drive against closed forms (trapezoid and triangle times, grbl's
// junction-deviation speed, the centripetal speed √(aR)), and a seeded random property test against
// a grid oracle (forward/backward pass on v² over grid points on every move). Reproduce the random
// test with FEEDPLAN_TEST_SEED and FEEDPLAN_TEST_COUNT.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "feedplan/core/angle.hpp"
#include "feedplan/geometry/tool_path.hpp"
#include "feedplan/sim/motion_profile.hpp"

namespace feedplan::sim {
namespace {

using geometry::BlockCommand;
using geometry::Move;
using geometry::MoveKind;
using geometry::Point2;
using geometry::Point3;
using geometry::Program;

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Builds programs move by move, each starting where the previous one ends.
struct ProgramBuilder {
  Program program;
  Point3 at;

  explicit ProgramBuilder(Point3 start = {}) : at(start) {}

  BlockCommand& add(Move move, double feed_mm_per_min) {
    move.start = at;
    at = move.end;
    program.path.moves.push_back(move);
    BlockCommand block;
    block.feed_mm_per_min = move.kind == MoveKind::kRapid ? 0.0 : feed_mm_per_min;
    program.blocks.push_back(block);
    return program.blocks.back();
  }
  BlockCommand& line(Point3 end, double feed_mm_per_min, bool cutting = true) {
    Move move;
    move.kind = MoveKind::kLine;
    move.end = end;
    move.cutting = cutting;
    return add(move, feed_mm_per_min);
  }
  BlockCommand& rapid(Point3 end) {
    Move move;
    move.kind = MoveKind::kRapid;
    move.end = end;
    return add(move, 0.0);
  }
  // Arc about `center` by `sweep_rad`, z changing by `dz_mm` (a helix when non-zero).
  BlockCommand& arc(Point2 center, double sweep_rad, bool ccw, double feed_mm_per_min, double dz_mm = 0.0) {
    Move move;
    move.kind = MoveKind::kArc;
    move.center = center;
    move.sweep_rad = sweep_rad;
    move.ccw = ccw;
    move.cutting = true;
    move.start = at;
    move.end = at;  // point_at needs only start, center, sweep and ccw
    Point3 end = geometry::point_at(move, 1.0);
    end.z_mm = at.z_mm + dz_mm;
    move.end = end;
    return add(move, feed_mm_per_min);
  }
};

// Rest-to-rest time over length L with cap v and acceleration a: a trapezoid L/v + v/a when the cap
// is reached (L ≥ v²/a), else a triangle 2√(L/a).
double rest_to_rest_s(double length_mm, double cap_mm_per_s, double accel) {
  if (length_mm >= cap_mm_per_s * cap_mm_per_s / accel) return length_mm / cap_mm_per_s + cap_mm_per_s / accel;
  return 2.0 * std::sqrt(length_mm / accel);
}

// grbl's junction speed (planner.c): cos θ = −(t1 · t2), sin(θ/2) = √((1 − cos θ)/2),
// v² = a δ sin(θ/2)/(1 − sin(θ/2)). Evaluated without cancellation for unit tangents:
// sin(θ/2) = |t1 + t2|/2 and 1 − sin(θ/2) = (|t1 − t2|/2)²/(1 + sin(θ/2)). As the header specifies,
// junctions deflecting by at most kTangentJunctionToleranceRad are unlimited, and those within it of
// a reversal stop.
double grbl_junction_speed(double t1x, double t1y, double t1z, double t2x, double t2y, double t2z, double accel,
                           double deviation_mm) {
  const double sin_theta_d2 = 0.5 * std::hypot(t1x + t2x, t1y + t2y, t1z + t2z);
  const double half_difference = 0.5 * std::hypot(t1x - t2x, t1y - t2y, t1z - t2z);
  const double deflection_rad = 2.0 * std::atan2(half_difference, sin_theta_d2);
  if (deflection_rad <= kTangentJunctionToleranceRad) return kInfinity;
  if (deflection_rad >= kPi - kTangentJunctionToleranceRad) return 0.0;
  const double one_minus_sin = half_difference * half_difference / (1.0 + sin_theta_d2);
  return std::sqrt(accel * deviation_mm * sin_theta_d2 / one_minus_sin);
}

// Largest path speed and |dv/dt| seen by sampling state_at_time densely (finite differences).
struct Sampled {
  double max_speed = 0.0;
  double max_abs_accel = 0.0;
  double max_s_jump = 0.0;
  bool monotone = true;
};
Sampled sample(const MotionProfile& profile, int count) {
  Sampled out;
  MotionState previous = profile.state_at_time(0.0);
  const double dt = profile.duration_s() / count;
  for (int k = 1; k <= count; ++k) {
    const MotionState state = profile.state_at_time(k * dt);
    out.max_speed = std::max(out.max_speed, state.speed_mm_per_s);
    out.max_abs_accel = std::max(out.max_abs_accel, std::abs(state.speed_mm_per_s - previous.speed_mm_per_s) / dt);
    out.max_s_jump = std::max(out.max_s_jump, state.s_mm - previous.s_mm);
    if (state.s_mm < previous.s_mm) out.monotone = false;
    previous = state;
  }
  return out;
}

TEST(MotionProfile, LongLineFromRestToRestIsATrapezoid) {
  ProgramBuilder b;
  b.line({100, 0, 0}, 6000);  // 100 mm/s; reaches F after v²/2a = 2.5 mm
  const geometry::MachineLimits limits = kVirtualMachineLimits;
  const MotionProfile profile = plan_motion(b.program, limits);
  const double v = 100.0, a = 2000.0, length = 100.0;
  EXPECT_NEAR(profile.duration_s(), length / v + v / a, 1e-12);
  EXPECT_NEAR(profile.length_mm(), length, 1e-12);
  const MotionState at_cruise = profile.state_at_time(v / a);
  EXPECT_NEAR(at_cruise.s_mm, v * v / (2 * a), 1e-12);
  EXPECT_NEAR(at_cruise.speed_mm_per_s, v, 1e-12);
  const MotionState half_way = profile.state_at_time(0.5 * profile.duration_s());
  EXPECT_NEAR(half_way.s_mm, 50.0, 1e-9);
  EXPECT_NEAR(half_way.position.x_mm, 50.0, 1e-9);
  EXPECT_NEAR(half_way.fraction, 0.5, 1e-11);
  EXPECT_EQ(half_way.accel_mm_per_s2, 0.0);
  const MotionState early = profile.state_at_time(0.01);  // accelerating: s = a t²/2
  EXPECT_NEAR(early.s_mm, 0.5 * a * 0.01 * 0.01, 1e-12);
  EXPECT_NEAR(early.accel_mm_per_s2, a, 0.0);
  EXPECT_NEAR(profile.time_in_cut_s(), profile.duration_s(), 1e-12);
  EXPECT_EQ(profile.time_in_air_s(), 0.0);
}

TEST(MotionProfile, ShortLineThatCannotReachItsFeedIsATriangle) {
  ProgramBuilder b;
  b.line({0.6, 0.8, 0}, 6000);  // L = 1 mm < v²/a = 5 mm
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  const double a = 2000.0;
  EXPECT_NEAR(profile.duration_s(), 2.0 * std::sqrt(1.0 / a), 1e-12);
  const MotionState peak = profile.state_at_time(std::sqrt(1.0 / a));
  EXPECT_NEAR(peak.speed_mm_per_s, std::sqrt(a * 1.0), 1e-9);  // v_peak² = 2a (L/2)
  EXPECT_NEAR(peak.s_mm, 0.5, 1e-12);
  EXPECT_NEAR(profile.speed_cap_at(0.5), std::sqrt(a * 1.0), 1e-9);
  EXPECT_NEAR(profile.speed_cap_at(0.25), std::sqrt(2 * a * 0.25), 1e-9);
}

TEST(MotionProfile, SlowerCollinearBlockIsEnteredAtExactlyItsFeed) {
  ProgramBuilder b;
  b.line({50, 0, 0}, 6000);   // 100 mm/s
  b.line({100, 0, 0}, 1200);  // 20 mm/s
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  const double a = 2000.0;
  // Move 1: 0 → 100 (2.5 mm), cruise, 100 → 20 (2.4 mm). Move 2: cruise at 20, 20 → 0 (0.1 mm).
  const double move1_s = 100.0 / a + (50.0 - 2.5 - 2.4) / 100.0 + 80.0 / a;
  const double move2_s = (50.0 - 0.1) / 20.0 + 20.0 / a;
  EXPECT_NEAR(profile.duration_s(), move1_s + move2_s, 1e-12);
  EXPECT_NEAR(profile.moves()[1].entry_speed_mm_per_s, 20.0, 1e-12);
  EXPECT_NEAR(profile.speed_cap_at(50.0), 20.0, 1e-9);
  EXPECT_NEAR(profile.speed_cap_at(50.0 - 2.4), 100.0, 1e-9);  // deceleration starts 2.4 mm before
  for (double s = 50.0; s <= 100.0; s += 0.5) EXPECT_LE(profile.speed_cap_at(s), 20.0 + 1e-9) << "s = " << s;
}

TEST(MotionProfile, CornerJunctionSpeedFollowsJunctionDeviation) {
  const double a = 2000.0, delta = 0.01;
  ProgramBuilder b;
  b.line({50, 0, 0}, 6000);
  b.line({50, 50, 0}, 6000);  // 90° corner
  const double cos60 = std::cos(deg_to_rad(120.0)), sin60 = std::sin(deg_to_rad(120.0));
  b.line({50 + 30 * cos60, 50 + 30 * sin60, 0}, 6000);  // turns 30° further left: a 30° deflection
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  const double v90 = grbl_junction_speed(1, 0, 0, 0, 1, 0, a, delta);
  // With θ = 90° interior angle: sin 45° / (1 − sin 45°) = 1 + √2.
  EXPECT_NEAR(v90, std::sqrt(a * delta * (1 + std::sqrt(2.0))), 1e-12);
  EXPECT_NEAR(profile.moves()[1].entry_speed_mm_per_s, v90, 1e-9);
  EXPECT_NEAR(profile.speed_cap_at(50.0), v90, 1e-9);
  const double v30 = grbl_junction_speed(0, 1, 0, cos60, sin60, 0, a, delta);
  EXPECT_NEAR(profile.moves()[2].entry_speed_mm_per_s, v30, 1e-9);
  // Time: three trapezoids between the junction speeds 0, v90, v30, 0 (all moves reach 100 mm/s).
  auto leg_s = [&](double length, double v_in, double v_out) {
    const double v = 100.0;
    const double s_ramps = (v * v - v_in * v_in) / (2 * a) + (v * v - v_out * v_out) / (2 * a);
    return (v - v_in) / a + (length - s_ramps) / v + (v - v_out) / a;
  };
  EXPECT_NEAR(profile.duration_s(), leg_s(50, 0, v90) + leg_s(50, v90, v30) + leg_s(30, v30, 0), 1e-12);

  geometry::MachineLimits exact_stop = kVirtualMachineLimits;
  exact_stop.junction_deviation_mm = 0.0;
  const MotionProfile stopping = plan_motion(b.program, exact_stop);
  EXPECT_EQ(stopping.moves()[1].entry_speed_mm_per_s, 0.0);
  EXPECT_EQ(stopping.moves()[2].entry_speed_mm_per_s, 0.0);
  EXPECT_NEAR(stopping.duration_s(), rest_to_rest_s(50, 100, a) * 2 + rest_to_rest_s(30, 100, a), 1e-12);
}

TEST(MotionProfile, FullReversalStops) {
  ProgramBuilder b;
  b.line({20, 0, 0}, 3000);
  b.line({5, 0, 0}, 3000);
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  EXPECT_EQ(profile.moves()[1].entry_speed_mm_per_s, 0.0);
  EXPECT_NEAR(profile.duration_s(), rest_to_rest_s(20, 50, 2000) + rest_to_rest_s(15, 50, 2000), 1e-12);
}

TEST(MotionProfile, TangentContinuousTrochoidDoesNotStopAtJunctions) {
  // Loops of radius 5 about c_k = (k, 0), each starting at b_k = c_k − (0, 5) where the ccw circle runs
  // along +x, joined by straight +x steps: every junction is tangent-continuous.
  ProgramBuilder b({0, -5, 0});
  const int loops = 6;
  for (int k = 0; k < loops; ++k) {
    b.arc({static_cast<double>(k), 0}, kTwoPi, true, 3000);  // 50 mm/s < √(aR) = 100 mm/s
    if (k + 1 < loops) b.line({k + 1.0, -5, 0}, 3000);
  }
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  const double length = loops * kTwoPi * 5 + (loops - 1);
  EXPECT_NEAR(profile.length_mm(), length, 1e-9);
  for (std::size_t i = 1; i < profile.moves().size(); ++i) {
    EXPECT_NEAR(profile.moves()[i].entry_speed_mm_per_s, 50.0, 1e-9) << "junction before move " << i;
  }
  EXPECT_NEAR(profile.duration_s(), length / 50.0 + 50.0 / 2000.0, 1e-9);
}

TEST(MotionProfile, ArcSpeedIsCappedByCentripetalAcceleration) {
  const double a = 2000.0, radius = 2.0;
  ProgramBuilder b({radius, 0, 0});
  b.arc({0, 0}, kTwoPi, true, 6000);  // F = 100 mm/s > √(aR) = 63.2 mm/s
  const double v_cap = std::sqrt(a * radius);
  const double length = kTwoPi * radius;
  const MotionProfile capped = plan_motion(b.program, kVirtualMachineLimits);
  EXPECT_NEAR(capped.moves()[0].cap_mm_per_s, v_cap, 1e-12);
  EXPECT_NEAR(capped.speed_cap_at(0.5 * length), v_cap, 1e-9);
  EXPECT_NEAR(capped.duration_s(), length / v_cap + v_cap / a, 1e-12);
  EXPECT_LE(sample(capped, 2000).max_speed, v_cap * (1 + 1e-12));

  geometry::MachineLimits no_centripetal = kVirtualMachineLimits;
  no_centripetal.limit_centripetal = false;
  const MotionProfile free = plan_motion(b.program, no_centripetal);
  EXPECT_NEAR(free.duration_s(), length / 100.0 + 100.0 / a, 1e-12);

  // A helix runs F along its length in space; R is still the XY radius.
  ProgramBuilder h({10, 0, 0});
  h.arc({0, 0}, 2 * kTwoPi, false, 1200, -4.0);
  const double helix_length = std::hypot(2 * kTwoPi * 10, 4.0);
  EXPECT_NEAR(plan_motion(h.program).duration_s(), helix_length / 20.0 + 20.0 / a, 1e-12);
}

TEST(MotionProfile, FeedAboveMachineMaximumIsClamped) {
  ProgramBuilder b;
  b.line({500, 0, 0}, 30000);
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  const double v = 20000.0 / 60.0;
  EXPECT_NEAR(profile.duration_s(), 500.0 / v + v / 2000.0, 1e-12);
}

TEST(MotionProfile, PlungeRunsAtItsFeedAlongZ) {
  ProgramBuilder b({0, 0, 5});
  b.line({0, 0, -3}, 600, false);  // 10 mm/s over 8 mm
  b.line({40, 0, -3}, 600);        // 90° corner from −z to +x
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  const double a = 2000.0;
  const double v_corner = grbl_junction_speed(0, 0, -1, 1, 0, 0, a, 0.01);
  ASSERT_LT(v_corner, 10.0);
  EXPECT_NEAR(profile.moves()[1].entry_speed_mm_per_s, v_corner, 1e-9);
  auto leg_s = [&](double length, double v_in, double v_out) {
    const double v = 10.0;
    const double s_ramps = (v * v - v_in * v_in) / (2 * a) + (v * v - v_out * v_out) / (2 * a);
    return (v - v_in) / a + (length - s_ramps) / v + (v - v_out) / a;
  };
  EXPECT_NEAR(profile.duration_s(), leg_s(8, 0, v_corner) + leg_s(40, v_corner, 0), 1e-12);
  EXPECT_NEAR(profile.time_in_air_s(), profile.moves()[0].end_time_s, 1e-12);
  EXPECT_NEAR(profile.time_in_cut_s(), profile.duration_s() - profile.moves()[0].end_time_s, 1e-12);
  // At 0.1 s: 0.005 s of acceleration to 10 mm/s (0.025 mm), then 0.095 s at 10 mm/s: 0.975 mm down.
  const MotionState plunging = profile.state_at_time(0.1);
  EXPECT_NEAR(plunging.position.z_mm, 5.0 - 0.975, 1e-12);
}

TEST(MotionProfile, RapidsRunAtTheRapidRateWithExactStopsAtFeedSwitches) {
  const double a = 2000.0, rapid = 15000.0 / 60.0;
  ProgramBuilder alone;
  alone.rapid({100, 0, 0});
  EXPECT_NEAR(plan_motion(alone.program).duration_s(), 100.0 / rapid + rapid / a, 1e-12);

  ProgramBuilder b;
  b.rapid({100, 0, 0});
  b.line({150, 0, 0}, 3000);  // collinear, but a rapid → feed switch
  b.rapid({250, 0, 0});
  b.rapid({350, 0, 0});  // rapid → rapid, collinear: no stop
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  EXPECT_EQ(profile.moves()[1].entry_speed_mm_per_s, 0.0);
  EXPECT_EQ(profile.moves()[2].entry_speed_mm_per_s, 0.0);
  EXPECT_NEAR(profile.moves()[3].entry_speed_mm_per_s, rapid, 1e-9);
  EXPECT_NEAR(profile.duration_s(),
              rest_to_rest_s(100, rapid, a) + rest_to_rest_s(50, 50, a) + rest_to_rest_s(200, rapid, a), 1e-12);
  EXPECT_NEAR(profile.time_in_cut_s(), rest_to_rest_s(50, 50, a), 1e-12);
  EXPECT_NEAR(profile.time_in_air_s(), rest_to_rest_s(100, rapid, a) + rest_to_rest_s(200, rapid, a), 1e-12);
}

TEST(MotionProfile, DwellAddsExactlyItsTimeAtRest) {
  const double a = 2000.0;
  ProgramBuilder b;
  b.line({30, 0, 0}, 3000);
  b.line({60, 0, 0}, 3000).dwell_before_s = 0.7;  // collinear: only the dwell stops it
  b.program.dwell_at_end_s = 0.25;
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  const double leg_s = rest_to_rest_s(30, 50, a);
  EXPECT_NEAR(profile.duration_s(), 2 * leg_s + 0.7 + 0.25, 1e-12);
  EXPECT_NEAR(profile.time_dwelling_s(), 0.95, 1e-15);
  EXPECT_NEAR(profile.moves()[1].start_time_s, leg_s + 0.7, 1e-12);
  const MotionState dwelling = profile.state_at_time(leg_s + 0.35);
  EXPECT_TRUE(dwelling.dwelling);
  EXPECT_EQ(dwelling.speed_mm_per_s, 0.0);
  EXPECT_EQ(dwelling.move_index, 1u);
  EXPECT_NEAR(dwelling.s_mm, 30.0, 1e-9);
  const MotionState end_dwell = profile.state_at_time(profile.duration_s() - 0.1);
  EXPECT_TRUE(end_dwell.dwelling);
  EXPECT_NEAR(end_dwell.s_mm, 60.0, 1e-9);
  EXPECT_NEAR(end_dwell.fraction, 1.0, 1e-12);
  const MotionState done = profile.state_at_time(profile.duration_s() + 5);
  EXPECT_FALSE(done.dwelling);
  EXPECT_EQ(done.s_mm, 60.0);
  EXPECT_EQ(done.speed_mm_per_s, 0.0);
}

TEST(MotionProfile, ZeroLengthMovesTakeNoTimeAndFormNoJunction) {
  ProgramBuilder b;
  b.line({50, 0, 0}, 3000);
  b.line({50, 0, 0}, 3000);  // zero length: the neighbours meet directly (collinear, no stop)
  b.line({100, 0, 0}, 3000);
  const MotionProfile profile = plan_motion(b.program, kVirtualMachineLimits);
  EXPECT_NEAR(profile.duration_s(), rest_to_rest_s(100, 50, 2000), 1e-12);
  EXPECT_NEAR(profile.moves()[1].entry_speed_mm_per_s, 50.0, 1e-12);
  EXPECT_EQ(profile.moves()[1].start_time_s, profile.moves()[1].end_time_s);
}

TEST(MotionProfile, StateIsContinuousAndWithinLimitsOnAMixedProgram) {
  ProgramBuilder b({0, 0, 10});
  b.rapid({0, 0, 2});
  b.line({0, 0, -2}, 300, false);
  b.line({20, 0, -2}, 1500);
  b.arc({20, 5}, kPi, true, 1500);
  b.line({0, 10, -2}, 900).dwell_before_s = 0.1;
  b.arc({0, 12}, 1.5 * kPi, false, 4000, -1.0);
  b.rapid({0, 12, 10});
  const geometry::MachineLimits limits = kVirtualMachineLimits;
  const MotionProfile profile = plan_motion(b.program, limits);
  const int count = 200000;
  const Sampled s = sample(profile, count);
  EXPECT_TRUE(s.monotone);
  EXPECT_LE(s.max_abs_accel, limits.max_accel_mm_per_s2 * (1 + 1e-6));
  EXPECT_LE(s.max_s_jump, limits.rapid_feed_mm_per_min / 60.0 * profile.duration_s() / count * (1 + 1e-9));
  // Position continuity: consecutive samples are no further apart in space than along the path.
  const double dt = profile.duration_s() / count;
  Point3 previous = profile.state_at_time(0).position;
  for (int k = 1; k <= count; ++k) {
    const MotionState state = profile.state_at_time(k * dt);
    const double gap = std::hypot(state.position.x_mm - previous.x_mm, state.position.y_mm - previous.y_mm,
                                  state.position.z_mm - previous.z_mm);
    ASSERT_LE(gap, s.max_s_jump + 1e-9) << "t = " << k * dt;
    previous = state.position;
  }
  EXPECT_NEAR(previous.x_mm, 0.0, 1e-9);
  EXPECT_NEAR(previous.z_mm, 10.0, 1e-9);
}

TEST(MotionProfile, InvalidLimitsAndProgramsAreRejected) {
  geometry::MachineLimits bad = kVirtualMachineLimits;
  bad.max_accel_mm_per_s2 = -1;
  bad.rapid_feed_mm_per_min = std::nan("");
  bad.max_feed_mm_per_min = 0;
  bad.junction_deviation_mm = -0.01;
  const auto problems = validate(bad);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0].field, "machine.max_accel_mm_per_s2");
  EXPECT_EQ(problems[1].field, "machine.rapid_feed_mm_per_min");
  EXPECT_EQ(problems[2].field, "machine.max_feed_mm_per_min");
  EXPECT_EQ(problems[3].field, "machine.junction_deviation_mm");
  EXPECT_TRUE(validate(kVirtualMachineLimits).empty());

  ProgramBuilder b;
  b.line({10, 0, 0}, 1000);
  EXPECT_THROW(plan_motion(b.program, bad), InputError);

  ProgramBuilder no_feed;
  no_feed.line({10, 0, 0}, 0.0).source_line = 7;
  no_feed.line({20, 0, 0}, 100).dwell_before_s = -1;
  try {
    plan_motion(no_feed.program);
    FAIL() << "F0 was accepted";
  } catch (const InputError& error) {
    ASSERT_EQ(error.problems().size(), 2u);
    EXPECT_EQ(error.problems()[0].field, "line 7 F");
    EXPECT_EQ(error.problems()[1].field, "move 1 dwell");
  }
  EXPECT_THROW(plan_motion(Program{}), InputError);
}

// ---- Seeded random property test -------------------------------------------------------------

unsigned env_or(const char* name, unsigned fallback) {
  const char* text = std::getenv(name);
  return text ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : fallback;
}

struct Tangent {
  double x, y, z;
};

// Unit tangent in space at `fraction` (0 or 1) of a move, from its geometry.
Tangent tangent_of(const Move& move, double fraction) {
  const double length = geometry::length_mm(move);
  const double dz = (move.end.z_mm - move.start.z_mm) / length;
  if (move.kind != MoveKind::kArc) {
    return {(move.end.x_mm - move.start.x_mm) / length, (move.end.y_mm - move.start.y_mm) / length, dz};
  }
  const Point3 p = geometry::point_at(move, fraction);
  const double rx = p.x_mm - move.center.x_mm, ry = p.y_mm - move.center.y_mm;
  const double r = std::hypot(rx, ry);
  const double sign = move.ccw ? 1.0 : -1.0;
  const double xy = geometry::xy_length_mm(move) / length;
  return {-sign * ry / r * xy, sign * rx / r * xy, dz};
}

Program random_program(std::mt19937_64& rng, geometry::MachineLimits& limits) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  limits.max_accel_mm_per_s2 = uniform(200, 5000);
  limits.rapid_feed_mm_per_min = uniform(3000, 20000);
  limits.max_feed_mm_per_min = uniform(2000, 15000);
  limits.junction_deviation_mm = unit(rng) < 0.1 ? 0.0 : uniform(0.001, 0.1);
  limits.limit_centripetal = unit(rng) < 0.8;
  ProgramBuilder b({uniform(-20, 20), uniform(-20, 20), uniform(-5, 5)});
  const int count = 1 + static_cast<int>(unit(rng) * 30);
  double heading = uniform(0, kTwoPi);
  for (int i = 0; i < count; ++i) {
    const double feed = std::exp(uniform(std::log(20.0), std::log(20000.0)));
    const double pick = unit(rng);
    BlockCommand* block = nullptr;
    const bool tangent = unit(rng) < 0.3;  // continue along the current heading
    if (!tangent) heading = uniform(0, kTwoPi);
    if (pick < 0.1) {
      const double length = std::exp(uniform(std::log(0.01), std::log(200.0)));
      block = &b.rapid({b.at.x_mm + length * std::cos(heading), b.at.y_mm + length * std::sin(heading),
                        b.at.z_mm + uniform(-2, 2)});
    } else if (pick < 0.15) {
      block = &b.line({b.at.x_mm, b.at.y_mm, b.at.z_mm + uniform(-10, 10)}, feed);  // plunge or retract
    } else if (pick < 0.18) {
      block = &b.line(b.at, feed);  // zero length
    } else if (pick < 0.6) {
      const double length = std::exp(uniform(std::log(0.001), std::log(100.0)));
      const double dz = unit(rng) < 0.2 ? uniform(-1, 1) : 0.0;
      block = &b.line({b.at.x_mm + length * std::cos(heading), b.at.y_mm + length * std::sin(heading),
                       b.at.z_mm + dz}, feed);
    } else {
      const double radius = std::exp(uniform(std::log(0.05), std::log(50.0)));
      const bool ccw = unit(rng) < 0.5;
      const double side = ccw ? 0.5 * kPi : -0.5 * kPi;  // centre on the left of the heading for ccw
      const Point2 center = {b.at.x_mm + radius * std::cos(heading + side), b.at.y_mm + radius * std::sin(heading + side)};
      const double sweep = uniform(0.01, 2.5 * kTwoPi);
      const double dz = unit(rng) < 0.3 ? uniform(-3, 3) : 0.0;
      block = &b.arc(center, sweep, ccw, feed, dz);
      heading += (ccw ? 1.0 : -1.0) * sweep;
    }
    if (unit(rng) < 0.05) block->dwell_before_s = uniform(0.0, 0.5);
  }
  if (unit(rng) < 0.1) b.program.dwell_at_end_s = uniform(0.0, 1.0);
  return b.program;
}

// The oracle: junction caps from grbl's formula as written in its planner, then a forward and a
// backward pass on v² over a grid of points on every move (docs/method.md §5.5), and on each grid interval
// the fastest motion between its end speeds under the move's cap (accelerate, cruise, decelerate).
// Its code shares nothing with the planner's.
struct Oracle {
  std::vector<double> cap_mm_per_s;  // per move
  std::vector<double> junction_cap;  // per move: cap on its entry speed (moves that take time only)
  double duration_s = 0.0;
};

// Fastest time over `ds` from v0 to v1 (reachable from each other) with |dv/dt| ≤ a and v ≤ cap.
double fastest_interval_s(double ds, double v0, double v1, double cap, double a) {
  // Peak speed where the acceleration from v0 meets the deceleration to v1, unless the cap is lower.
  const double v_meet = std::sqrt(std::max({(2 * a * ds + v0 * v0 + v1 * v1) / 2, v0 * v0, v1 * v1}));
  const double v_top = std::min(cap, v_meet);
  const double ramp_ds = (v_top * v_top - v0 * v0) / (2 * a) + (v_top * v_top - v1 * v1) / (2 * a);
  return (v_top - v0) / a + (v_top - v1) / a + std::max(0.0, ds - ramp_ds) / v_top;
}

Oracle grid_oracle(const Program& program, const geometry::MachineLimits& limits, int intervals_per_move) {
  const auto& moves = program.path.moves;
  const double a = limits.max_accel_mm_per_s2;
  Oracle oracle;
  std::vector<std::size_t> real;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const Move& m = moves[i];
    double cap = limits.rapid_feed_mm_per_min / 60.0;
    if (m.kind != MoveKind::kRapid) {
      cap = std::min(program.blocks[i].feed_mm_per_min, limits.max_feed_mm_per_min) / 60.0;
      if (m.kind == MoveKind::kArc && limits.limit_centripetal) {
        cap = std::min(cap, std::sqrt(a * std::hypot(m.start.x_mm - m.center.x_mm, m.start.y_mm - m.center.y_mm)));
      }
    }
    oracle.cap_mm_per_s.push_back(cap);
    if (geometry::length_mm(m) >= 1e-9) real.push_back(i);
    oracle.duration_s += program.blocks[i].dwell_before_s;
  }
  oracle.duration_s += program.dwell_at_end_s;
  oracle.junction_cap.assign(moves.size(), kInfinity);
  std::vector<double> u;        // v² at grid points
  std::vector<double> step_mm;  // grid spacing after each point
  std::vector<double> step_cap;  // cap of the move each spacing lies on
  for (std::size_t j = 0; j < real.size(); ++j) {
    const std::size_t q = real[j];
    double junction = 0.0;
    if (j > 0) {
      const std::size_t p = real[j - 1];
      bool stop = (moves[p].kind == MoveKind::kRapid) != (moves[q].kind == MoveKind::kRapid);
      for (std::size_t k = p + 1; k <= q; ++k) stop = stop || program.blocks[k].dwell_before_s > 0;
      if (!stop) {
        const Tangent t1 = tangent_of(moves[p], 1.0), t2 = tangent_of(moves[q], 0.0);
        junction = std::min({oracle.cap_mm_per_s[p], oracle.cap_mm_per_s[q],
                             grbl_junction_speed(t1.x, t1.y, t1.z, t2.x, t2.y, t2.z, a, limits.junction_deviation_mm)});
      }
    }
    oracle.junction_cap[q] = junction;
    u.push_back(junction * junction);
    const double cap2 = oracle.cap_mm_per_s[q] * oracle.cap_mm_per_s[q];
    const double ds = geometry::length_mm(moves[q]) / intervals_per_move;
    for (int k = 0; k < intervals_per_move; ++k) {
      step_mm.push_back(ds);
      step_cap.push_back(oracle.cap_mm_per_s[q]);
      if (k > 0) u.push_back(cap2);
    }
  }
  u.push_back(0.0);
  for (std::size_t i = 1; i < u.size(); ++i) u[i] = std::min(u[i], u[i - 1] + 2 * a * step_mm[i - 1]);
  for (std::size_t i = u.size() - 1; i-- > 0;) u[i] = std::min(u[i], u[i + 1] + 2 * a * step_mm[i]);
  for (std::size_t i = 0; i + 1 < u.size(); ++i) {
    oracle.duration_s += fastest_interval_s(step_mm[i], std::sqrt(u[i]), std::sqrt(u[i + 1]), step_cap[i], a);
  }
  return oracle;
}

TEST(MotionProfile, RandomProgramsStayWithinEveryLimitAndMatchTheGridOracle) {
  const unsigned seed = env_or("FEEDPLAN_TEST_SEED", 20240611u);
  const unsigned count = env_or("FEEDPLAN_TEST_COUNT", 2000u);
  std::cout << "random motion programs: seed " << seed << ", count " << count << "\n";
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t total_moves = 0, total_segments = 0;
  double worst_oracle_gap = 0.0;
  for (unsigned c = 0; c < count; ++c) {
    geometry::MachineLimits limits = kVirtualMachineLimits;
    const Program program = random_program(rng, limits);
    SCOPED_TRACE("program " + std::to_string(c) + " of seed " + std::to_string(seed));
    const MotionProfile profile = plan_motion(program, limits);
    const double a = limits.max_accel_mm_per_s2;
    const Oracle oracle = grid_oracle(program, limits, 7);
    total_moves += program.path.moves.size();
    total_segments += profile.segments().size();
    const double length = geometry::length_mm(program.path);
    const double v_scale = std::max(limits.rapid_feed_mm_per_min, limits.max_feed_mm_per_min) / 60.0;
    const double v_tol = 1e-9 * v_scale;
    const double s_tol = 1e-9 * std::max(1.0, length);

    // As fast as the oracle: the same time-optimal profile, found another way.
    const double gap = std::abs(oracle.duration_s - profile.duration_s()) / std::max(oracle.duration_s, 1e-3);
    worst_oracle_gap = std::max(worst_oracle_gap, gap);
    EXPECT_LE(gap, 1e-9) << "oracle " << oracle.duration_s << " s, planned " << profile.duration_s() << " s";

    // Segments: contiguous in time, s and v; within |a| ≤ a_max and the caps; cruising only at the cap.
    double t_sum = 0.0, s_prev_end = 0.0, v_prev_end = 0.0;
    for (const MotionSegment& seg : profile.segments()) {
      ASSERT_GT(seg.duration_s, 0.0);
      ASSERT_NEAR(seg.t0_s, t_sum, 1e-12 * std::max(1.0, t_sum));
      t_sum += seg.duration_s;
      ASSERT_NEAR(seg.s0_mm, s_prev_end, s_tol);
      ASSERT_NEAR(seg.v0_mm_per_s, v_prev_end, v_tol);
      ASSERT_LE(std::abs(seg.a_mm_per_s2), a * (1 + 1e-12));
      const double v_end = seg.v0_mm_per_s + seg.a_mm_per_s2 * seg.duration_s;
      ASSERT_GE(v_end, -v_tol);
      const double cap = oracle.cap_mm_per_s[seg.move_index];
      if (seg.dwell) {
        ASSERT_EQ(seg.v0_mm_per_s, 0.0);
      } else {
        ASSERT_LE(std::max(seg.v0_mm_per_s, v_end), cap * (1 + 1e-12)) << "move " << seg.move_index;
        if (seg.a_mm_per_s2 == 0.0) {
          ASSERT_NEAR(seg.v0_mm_per_s, cap, 1e-12 * cap) << "cruise below the cap";
        }
      }
      s_prev_end = seg.s0_mm + seg.duration_s * (seg.v0_mm_per_s + 0.5 * seg.a_mm_per_s2 * seg.duration_s);
      v_prev_end = std::max(0.0, v_end);
    }
    EXPECT_NEAR(t_sum, profile.duration_s(), 1e-12 * std::max(1.0, t_sum));
    EXPECT_NEAR(v_prev_end, 0.0, v_tol);
    EXPECT_NEAR(s_prev_end, length, s_tol);

    // Junction speeds within grbl's rule, the caps and the exact stops.
    for (std::size_t i = 0; i < program.path.moves.size(); ++i) {
      if (geometry::length_mm(program.path.moves[i]) < 1e-9) continue;
      ASSERT_LE(profile.moves()[i].entry_speed_mm_per_s, oracle.junction_cap[i] * (1 + 1e-9)) << "move " << i;
    }

    // Sampled: s monotone, |dv/dt| ≤ a, speed within the current move's cap, at rest at the end.
    std::vector<double> times(300);
    for (double& t : times) t = unit(rng) * profile.duration_s();
    std::sort(times.begin(), times.end());
    MotionState previous = profile.state_at_time(0.0);
    EXPECT_EQ(previous.speed_mm_per_s, 0.0);
    for (double t : times) {
      const MotionState state = profile.state_at_time(t);
      ASSERT_GE(state.s_mm, previous.s_mm - s_tol) << "t = " << t;
      ASSERT_LE(state.speed_mm_per_s, oracle.cap_mm_per_s[state.move_index] * (1 + 1e-12) + v_tol);
      if (state.dwelling) {
        ASSERT_EQ(state.speed_mm_per_s, 0.0);
      }
      const double dt = state.t_s - previous.t_s;
      if (dt > 1e-9) {
        ASSERT_LE(std::abs(state.speed_mm_per_s - previous.speed_mm_per_s), a * dt * (1 + 1e-9) + v_tol);
      }
      previous = state;
    }
    const MotionState end = profile.state_at_time(profile.duration_s());
    EXPECT_NEAR(end.s_mm, length, s_tol);
    EXPECT_EQ(end.speed_mm_per_s, 0.0);
    EXPECT_NEAR(profile.time_in_cut_s() + profile.time_in_air_s() + profile.time_dwelling_s(), profile.duration_s(),
                1e-12 * std::max(1.0, profile.duration_s()));
    if (::testing::Test::HasFatalFailure()) return;
  }
  std::cout << "  " << total_moves << " moves, " << total_segments << " segments; worst |oracle − planned| / oracle time "
            << worst_oracle_gap << "\n";
}

}  // namespace
}  // namespace feedplan::sim
