#pragma once
// How close measured (or simulated) per-revolution peak forces come to the plan's target: the figure a
// process engineer checks before trusting a plan on the machine (seed 003 Figs. 6, 10, 13).
//
// Each revolution is placed on the path by the path length it spans. A revolution counts as
//   - in cut when some planned sample inside its span is engaged;
//   - force-limited when every engaged planned sample inside its span is force-limited
//     (FeedLimitReason::kForce) and inside the model's fitted range at the feed run
//     (PlannedSample::within_model_range), and the machine's predicted speed reaches that limit somewhere
//     in the span within kHeldFeedShortfall: a faster plan could run the place faster;
//   - held when it is force-limited and the speed is within kHeldFeedShortfall of the limit at every engaged
//     sample of the span: there the plan promises the target over the whole revolution, on the model's own
//     ground, so |peak − target| / target is the error. A revolution's largest force comes from whichever
//     tooth pass (with runout: whichever pass of its largest tooth) lands where the force is highest, and
//     where the plan runs part of the span under its limit that is a matter of the spindle's angle: at a
//     loop's exit, where the feed cannot rise as fast as the engagement falls, the same plan reads up to 6 %
//     under the target from one revolution to the next. Elsewhere — the machine's maximum feed, an arc's
//     centripetal limit or the axes' acceleration (the feed cannot rise to the limit in time, so the plan
//     itself predicts less) binds, or the tool enters or leaves the material, where the engagement leaves
//     the straight-cut data the model was fitted on — the comparison reports the overshoot (peak above the
//     target), which says how far the model is off there, and the time lost under the target shows in the
//     cycle time;
//   - steady when it is held and the engagement angle varies by at most kSteadyEngagementSpreadRad over
//     its span: a straight cut or a steady arc, the geometry of the cutting tests a model is fitted on.
//     Entering and leaving the material (where the engaged arc does not end at the exit side, so t_m and
//     L pair differently than in any straight cut) is held but not steady.

#include <string>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::planner {

//! How far below its force limit the speed of a held revolution may stay, as a fraction of the limit: a
//! block's F lies up to the merge tolerance (PlanOptions, 2 %) below the limits it spans and is rounded
//! down to the F words' step. Further below, the plan itself does not bring the force to the target there.
inline constexpr double kHeldFeedShortfall = 0.025;

//! Largest spread of the engagement angle over a revolution that still counts as steady, rad (0.5°).
inline constexpr double kSteadyEngagementSpreadRad = 0.5 * 3.14159265358979323846 / 180.0;

//! One revolution as measured.
struct MeasuredRevolution {
  double s_start_mm = 0.0;  //!< path length where the revolution starts, mm
  double s_end_mm = 0.0;    //!< path length where it ends, mm (≥ s_start_mm)
  double peak_n = 0.0;      //!< peak XY force over the revolution, N
};

//! One revolution compared with the plan.
struct RevolutionComparison {
  MeasuredRevolution revolution;      //!< as given
  bool in_cut = false;                //!< some engaged planned sample inside
  bool force_limited = false;         //!< every engaged sample inside force-limited, in range, at the limit somewhere
  bool held = false;                  //!< force-limited and run at the limit at every engaged sample inside
  bool steady = false;                //!< held, with a constant engagement angle (straight cut, steady arc)
  double planned_force_n = 0.0;       //!< largest predicted force inside, N
  double error_percent = 0.0;         //!< (peak − target) / target × 100
  geometry::Point3 position;          //!< tool position at the middle of the span (planned sample), mm
};

//! The comparison over a whole run.
struct PeakComparison {
  std::vector<RevolutionComparison> revolutions;  //!< one per measured revolution
  int in_cut = 0;                         //!< revolutions in cut
  int held = 0;                           //!< revolutions where the plan holds the target
  int steady = 0;                         //!< held revolutions at constant engagement
  double max_abs_error_percent = 0.0;     //!< largest |error| over held revolutions, %
  double rms_error_percent = 0.0;         //!< RMS error over held revolutions, %
  double steady_max_abs_error_percent = 0.0;  //!< largest |error| over steady revolutions, %
  double steady_rms_error_percent = 0.0;      //!< RMS error over steady revolutions, %
  double max_overshoot_percent = 0.0;     //!< largest (peak − target)/target over all in-cut revolutions, % (≤ 0: never above)
  int worst_held = -1;                    //!< index of the held revolution with the largest |error| (−1: none)
  int worst_steady = -1;                  //!< index of the steady revolution with the largest |error| (−1: none)
  int worst_overshoot = -1;               //!< index of the in-cut revolution with the largest overshoot (−1: none)
  //! Index of the revolution with the largest peak of all, in the plan's cut or not (−1: none): the
  //! figure that says whether the program is safe, wherever the force came from.
  int largest_peak = -1;
};

//! Compares `revolutions` (in path order or not) with the plan `result` at target `target_force_n` (> 0),
//! by the rule at the top of this file. Linear in samples + revolutions when revolutions are in path order.
PeakComparison compare_peaks(const PlanResult& result, double target_force_n,
                             const std::vector<MeasuredRevolution>& revolutions);

//! A few lines for people, led by the largest per-revolution peak anywhere (N, against the target, and
//! where: s, x, y, z, in the plan's cut or not); then counts, max and RMS error over steady and over held
//! revolutions with where the worst is, and the largest overshoot over the in-cut revolutions.
std::string describe(const PeakComparison& comparison, double target_force_n);

//! "<peak> N at s = <mid> mm, x <x> y <y> z <z>" for one revolution.
std::string where_text(const RevolutionComparison& revolution);

}  // namespace feedplan::planner
