#pragma once
// Why a block of a plan has the F it has, in words a machinist reads ("force 300 N at 58 deg engagement",
// "plunge limit 0.05 mm/tooth", "acceleration"): what `feedplan plan --explain` and `feedplan optimize
// --explain` write as a comment beside every F word.
//
// The block's F comes from the sample inside it (its first to its last sample, both ends included) with
// the smallest feed limit of step 1 (feed_plan.hpp) — PlannedBlock::min_limit_mm_per_min — unless the
// machine's ramp holds it lower: the command profile of step 2 is below the limit there (the machine is
// still slowing down for, or speeding up from, another place), or the pass that makes every F change
// feasible lowered it. F below the limit by more than its rounding (down to the feed resolution and, with
// controller-friendly blocks, onto the F levels) is the ramp's: reason "acceleration". Otherwise the
// sample's FeedLimitReason, with its numbers:
//   kForce        "force <target> N at <α_en> deg engagement" (α_en of that sample, whole degrees);
//   kModelRange   "model range, chip <t_m> mm" (t_m the sample's chip at its limit feed);
//   kPlunge       "plunge limit <f_z,plunge> mm/tooth" (the tool's plunge feed per tooth);
//   kMaxFeed      "machine max feed";  kMinFeed "machine min feed";  kAirFeed "air";
//   kCentripetal  "arc R <R> mm, acceleration" (v² ≤ a·R on the block's arc).
// A limit the planner carried over from a sample after the block (the mechanistic kind holds each force
// limit over one tooth's travel before its place) is explained by that sample.

#include <cstddef>
#include <string>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! What sets one block's F.
struct BlockFeedReason {
  bool rapid = false;          //!< a rapid block: it has no F and no reason
  bool acceleration = false;   //!< the machine's ramp holds F below the limit (the reason is then "acceleration")
  FeedLimitReason limit = FeedLimitReason::kAirFeed;  //!< the reason of the deciding sample's limit
  int sample = -1;             //!< index of the deciding sample in PlanResult::samples (−1 on rapids)
  double limit_mm_per_min = 0.0;  //!< its feed limit, mm/min
  double target_force_n = 0.0;    //!< the target the force limit holds, N (kForce)
  double engagement_deg = 0.0;    //!< α_en at the deciding sample, deg (kForce)
  double chip_thickness_mm = 0.0; //!< t_m at the deciding sample at its limit feed, mm (kModelRange)
  double plunge_feed_per_tooth_mm = 0.0;  //!< the tool's plunge feed per tooth, mm (kPlunge)
  double arc_radius_mm = 0.0;     //!< radius of the block's arc, mm (kCentripetal; 0 on lines)
};

//! The reason of block `block` of `result`, planned by plan(geometry, settings) (the rule at the top of this
//! file). `block` must be an index into result.blocks, and result.samples must be geometry's engagement
//! samples, planned (assert).
BlockFeedReason block_feed_reason(const PlanGeometry& geometry, const PlanSettings& settings, const PlanResult& result,
                                  std::size_t block);

//! The reason in words, without "F:" ("force 300 N at 58 deg engagement"); "" for a rapid block.
std::string to_text(const BlockFeedReason& reason);

//! to_text(block_feed_reason(…)) of every block of `result`, in block order ("" on rapids): one per move of
//! result.program, as gcode::WriterOptions::feed_comments takes them.
std::vector<std::string> block_feed_reason_texts(const PlanGeometry& geometry, const PlanSettings& settings,
                                                 const PlanResult& result);

}  // namespace feedplan::planner
