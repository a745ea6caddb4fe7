#pragma once
// What a feed override can express: a ratio of the programmed feed between a minimum (0 unless a floor
// is set) and a maximum, either continuous or in fixed steps. Seed 001 (Ulsoy & Koren, NSF report UM-MEAM-82-7) describes both on its
// lab machines: the NC lathe's override electronics move the feed "in discrete steps of 15 % of the full
// programmed feedrate from 0 % to 150 %", the CNC mill's "continuously … in the range 0 % to 150 %".
// Seed 002 (Kim & Kim) sends 0–255 % as an 8-bit number.
//
// The floor is not the papers': it is the bound a caller keeps the override above (feedplan's 10 % when a
// controller runs alone, so that a force no feed can bring down does not stop the machine; 70 % when it
// trims a plan). A controller that knows it clamps its own state there too (anti-windup): held at the floor
// while the force stays above the target, it does not integrate further down, and moves up at the first
// sample the force falls below the target.

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"

namespace feedplan::control {

//! The range and resolution of the override a controller commands.
struct OverrideRange {
  double max_ratio = 1.5;   //!< largest ratio, > 0 (1.5 = 150 %, seed 001's machines)
  double step_ratio = 0.0;  //!< resolution, ≥ 0 and ≤ max_ratio; 0: continuous, 0.15: seed 001's lathe
  double min_ratio = 0.0;   //!< smallest ratio, ≥ 0 and ≤ max_ratio (0.1 = 10 %; 0: the papers' 0 %)
};

//! Seed 001's NC lathe: 0–150 % in steps of 15 %.
inline constexpr OverrideRange kLatheOverrideSteps{1.5, 0.15};

//! Every problem with the range, each named "<field_prefix><field>" with its value and the rule
//! ("override.step_ratio = -0.1: must be finite and ≥ 0"). Empty when the range is usable.
std::vector<InputProblem> validate(const OverrideRange& range, const std::string& field_prefix = "override.");

//! The problems of a controller's override settings that share one rule: the range itself (named
//! "<field_prefix>override_range.<field>") and the feed before the first sample, which must be finite, ≥ 0 and
//! within the range's top, max_ratio × programmed feed ("<field_prefix>initial_feed_mm_per_min"). Empty
//! when usable. The programmed feed is checked by the caller.
std::vector<InputProblem> validate_override_start(const OverrideRange& range, double programmed_feed_mm_per_min,
                                                  double initial_feed_mm_per_min, const std::string& field_prefix);

//! The override the machine applies for the wish `ratio`: clamped to [min_ratio, max_ratio], then, with
//! steps, rounded to the nearest multiple of step_ratio that lies in [min_ratio, max_ratio] (when none
//! does — a floor and a ceiling within one step — the ceiling's multiple). Needs a range that passes
//! validate() and a ratio that is not NaN (asserted).
double applied_override(const OverrideRange& range, double ratio);

}  // namespace feedplan::control
