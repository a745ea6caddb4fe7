// The safety check (planner/safety_check.hpp) and the plans it guards, against truths it does not
// compute: a helix's first turn below the stock top is in solid material by construction (the bore is
// cut from solid); a plunge's allowed feed is the closed form f_z,plunge · Z · n; a rapid moved into
// the stock meets material; and every program the planner writes for the samples passes the check.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "feedplan/cycles/cycle.hpp"
#include "feedplan/cycles/spec_reader.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/safety_check.hpp"
#include "feedplan/planner/sample_force_model.hpp"
#include "test_models.hpp"

namespace feedplan::planner {
namespace {

struct Planned {
  cycles::CycleSpec spec;
  PlanGeometry geometry;
  PlanSettings settings;
  PlanResult result;
};

Planned plan_sample(const std::string& name) {
  Planned p;
  p.spec = cycles::load_cycle_spec(std::string(FEEDPLAN_SAMPLES_DIR) + "/" + name);
  const cycles::Cycle cycle = cycles::generate(p.spec);
  p.geometry = analyse(cycle.path, cycle.stock, p.spec.tool, 0.05);
  p.settings.model = testing::s50c_like_model();
  p.settings.target_force_n = p.spec.target_force_n;
  p.settings.spindle_rpm = p.spec.spindle_rpm;
  p.settings.machine = p.spec.machine;
  p.result = plan(p.geometry, p.settings);
  return p;
}

SafetyCheck check(const Planned& p, const geometry::Program& program) {
  SafetyCheckInput input;
  input.stock = &p.geometry.stock;
  input.tool = &p.geometry.tool;
  input.settings = &p.settings;
  return check_safety(program, input);
}

// The check may take the planner's chip-load ratios where its own engagement is the planner's: then its
// allowed feeds are those it computes itself, and a planner engagement that differs anywhere (here by
// 1e-6 rad on every engaged set) is never trusted, however wrong the ratios it comes with.
TEST(SafetyCheck, ThePlannersChipLoadIsTakenOnlyWhereTheEngagementIsTheSame) {
  const Planned p = plan_sample("trochoid.yaml");
  const SafetyCheck own = check(p, p.result.program);
  const SampleForceModel forces(p.settings.model, nullptr, p.geometry.engagement, p.geometry.tool);
  std::vector<double> ratios;
  for (const auto& sample : p.geometry.engagement.samples) ratios.push_back(forces.load_ratio(sample));
  auto check_with = [&](const geometry::EngagementProfile& planned, const std::vector<double>& planned_ratios) {
    SafetyCheckInput input;
    input.stock = &p.geometry.stock;
    input.tool = &p.geometry.tool;
    input.settings = &p.settings;
    input.planned_engagement = &planned;
    input.planned_load_ratio = &planned_ratios;
    return check_safety(p.result.program, input);
  };
  auto expect_same_allowed = [&](const SafetyCheck& found, const char* what) {
    ASSERT_EQ(found.allowed.size(), own.allowed.size()) << what;
    for (std::size_t k = 0; k < own.allowed.size(); ++k) {
      const double a = own.allowed[k].mm_per_min, b = found.allowed[k].mm_per_min;
      if (std::isinf(a) && std::isinf(b)) continue;
      ASSERT_NEAR(b, a, 1e-9 * std::max(1.0, a)) << what << " at s " << own.allowed[k].s_mm;
    }
  };
  expect_same_allowed(check_with(p.geometry.engagement, ratios), "the planner's own ratios");

  std::vector<double> wrong = ratios;
  for (double& r : wrong) r *= 3.0;
  int differing = 0;
  const SafetyCheck trusted = check_with(p.geometry.engagement, wrong);
  for (std::size_t k = 0; k < own.allowed.size(); ++k) {
    differing += std::isfinite(own.allowed[k].mm_per_min) &&
                 trusted.allowed[k].mm_per_min < own.allowed[k].mm_per_min * 0.99;
  }
  EXPECT_GT(differing, 1000) << "the check does take the planner's ratios where the engagement agrees";

  geometry::EngagementProfile shifted = p.geometry.engagement;
  for (auto& interval : shifted.intervals) interval.entry_rad += 1e-6;
  expect_same_allowed(check_with(shifted, wrong), "an engagement 1e-6 rad off");
}

TEST(SafetyCheck, TheSamplesPlansPassIt) {
  for (const char* name : {"corner.yaml", "trochoid.yaml", "spiral.yaml", "helical_boring.yaml"}) {
    const Planned p = plan_sample(name);
    EXPECT_NE(p.result.status, PlanStatus::kUnsafe) << name << ": " << ::testing::PrintToString(p.result.messages);
    EXPECT_TRUE(check(p, p.result.program).violations.empty()) << name;
  }
}

// The helix's first turn (tip from the stock top down one pitch) cuts solid steel on the layer the tip
// enters: never at the air feed, on any block of it.
TEST(SafetyCheck, TheFirstHelixTurnIsCutNotFlownThrough) {
  const Planned p = plan_sample("helical_boring.yaml");
  const auto& bore = std::get<cycles::HelicalBoringSpec>(p.spec.geometry);
  const double top_mm = p.geometry.stock.z_top_mm;
  const double air_feed = p.settings.machine.max_feed_mm_per_min;
  int first_turn_blocks = 0;
  for (std::size_t b = 0; b < p.result.program.path.moves.size(); ++b) {
    const geometry::Move& move = p.result.program.path.moves[b];
    if (move.kind != geometry::MoveKind::kArc) continue;
    const double z_mm = std::min(move.start.z_mm, move.end.z_mm);
    if (!(z_mm < top_mm - 1e-6 && std::max(move.start.z_mm, move.end.z_mm) > top_mm - bore.pitch_mm)) continue;
    ++first_turn_blocks;
    EXPECT_LT(p.result.program.blocks[b].feed_mm_per_min, 0.5 * air_feed) << "block " << b << " at z " << z_mm;
  }
  EXPECT_GE(first_turn_blocks, 1);
}

// The same program with every feed move at the air feed: the check names the first helix turn.
TEST(SafetyCheck, AProgramAtTheAirFeedIsRefusedWhereItEntersTheMaterial) {
  const Planned p = plan_sample("helical_boring.yaml");
  geometry::Program program = p.result.program;
  for (std::size_t b = 0; b < program.blocks.size(); ++b) {
    if (program.path.moves[b].kind != geometry::MoveKind::kRapid) {
      program.blocks[b].feed_mm_per_min = p.settings.machine.max_feed_mm_per_min;
    }
  }
  const SafetyCheck found = check(p, program);
  ASSERT_FALSE(found.violations.empty());
  const SafetyViolation& first = found.violations.front();
  EXPECT_EQ(first.problem, SafetyProblem::kAboveForceLimit);
  EXPECT_LE(first.position.z_mm, p.geometry.stock.z_top_mm);
  EXPECT_GT(first.position.z_mm, p.geometry.stock.z_top_mm - std::get<cycles::HelicalBoringSpec>(p.spec.geometry).pitch_mm);
  EXPECT_GT(first.material_height_mm, 0.0);
  EXPECT_NE(describe(first).find("above the force limit"), std::string::npos) << describe(first);
}

// A rapid into the stock: "rapid through material", with no feed allowed there.
TEST(SafetyCheck, ARapidIntoTheStockIsNamed) {
  const Planned p = plan_sample("corner.yaml");
  geometry::Program program = p.result.program;
  // The first block whose F the force sets (one program move per block).
  const auto& blocks = p.result.blocks;
  const auto held = std::find_if(blocks.begin(), blocks.end(), [&](const PlannedBlock& b) {
    return p.result.samples[static_cast<std::size_t>(b.first_sample)].limit_reason == FeedLimitReason::kForce;
  });
  ASSERT_NE(held, blocks.end());
  const auto index = static_cast<std::size_t>(held - blocks.begin());
  program.path.moves[index].kind = geometry::MoveKind::kRapid;
  program.blocks[index].feed_mm_per_min = 0.0;
  const SafetyCheck found = check(p, program);
  const auto rapid = std::find_if(found.violations.begin(), found.violations.end(), [](const SafetyViolation& v) {
    return v.problem == SafetyProblem::kRapidInMaterial;
  });
  ASSERT_NE(rapid, found.violations.end());
  EXPECT_EQ(rapid->move_index, static_cast<int>(index));
  EXPECT_NE(describe(*rapid).find("rapid through material"), std::string::npos);
}

// A straight plunge into solid stock at the tool's centre: allowed f_z,plunge · Z · n · L / (Δz + u)
// (closed form; the default plunge feed per tooth is 0.0025 · D; u = 0.001 mm, the written program's
// resolution, which can steepen a descent by that much), whatever the force model says.
TEST(SafetyCheck, AStraightPlungeIsHeldToThePlungeFeedPerTooth) {
  Planned p = plan_sample("helical_boring.yaml");
  geometry::Program program;
  geometry::Move down;
  down.kind = geometry::MoveKind::kLine;
  down.start = {0.0, 0.0, 2.0};
  down.end = {0.0, 0.0, -3.0};
  down.cutting = true;
  down.axial_depth_mm = 3.0;
  program.path.moves.push_back(down);
  program.path.part_names = {"plunge"};
  geometry::BlockCommand command;
  command.feed_mm_per_min = 2000.0;
  command.spindle_rpm = p.settings.spindle_rpm;
  command.spindle = geometry::SpindleDirection::kClockwise;
  program.blocks.push_back(command);
  const SafetyCheck found = check(p, program);
  ASSERT_EQ(found.violations.size(), 1u);
  const SafetyViolation& v = found.violations.front();
  const double allowed =
      0.0025 * p.spec.tool.diameter_mm * p.spec.tool.flutes * p.settings.spindle_rpm * 5.0 / (5.0 + 0.001);
  EXPECT_EQ(v.problem, SafetyProblem::kAbovePlungeLimit);
  EXPECT_NEAR(v.allowed_mm_per_min, allowed, 1e-9 * allowed);
  EXPECT_LT(v.position.z_mm, p.geometry.stock.z_top_mm);
  program.blocks[0].feed_mm_per_min = allowed;
  for (const SafetyViolation& left : check(p, program).violations) {
    EXPECT_NE(left.problem, SafetyProblem::kAbovePlungeLimit) << describe(left);
  }
}

}  // namespace
}  // namespace feedplan::planner
