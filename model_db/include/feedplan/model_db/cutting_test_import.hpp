#pragma once
// Cutting-test import: from the force log of a straight cut at constant conditions (measured on a
// dynamometer, or simulated by the virtual machine) to one model data point — the steady per-revolution
// peak of |F_xy| and the model inputs t_m and L it belongs to (docs/method.md §4, §5.1, §5.3).
//
// Steady-state rule. A straight cut starts and ends with transients (air, the tool entering the block,
// the tool leaving it); only the steady part between them is the cutting test. With P_k the peak of
// |F_xy| in complete spindle revolution k (force_log::revolution_peaks at the given spindle speed):
//   1. Eligible revolutions: when the log records the path feed (a feed_mm_per_min column, else x_mm
//      and y_mm: the distance between a revolution's first and last sample over their time), only those
//      whose feed lies within feed_tolerance of the given feed — rapids, acceleration and override
//      changes drop out. Logs without either (Kistler exports) keep every revolution.
//   2. Trend: T_k = median of P over the trend_window_revolutions revolutions centred on k (fewer at the
//      ends of a stretch of consecutive eligible revolutions), so that one odd revolution neither
//      breaks nor makes a plateau.
//   3. Plateau: level = median of P over the eligible revolutions with T_k ≥ loaded_fraction · max T
//      (the cutting ones, not air). The plateau is the longest run of consecutive eligible revolutions
//      with |T_k − level| ≤ plateau_tolerance · level; level is then re-taken as the median of P over
//      the run and the run found again, until it no longer changes (at most 10 times).
//   4. End trimming: σ = 1.4826 · MAD of P over the plateau (a robust standard deviation). Leading and
//      trailing revolutions with P_k < level − max(trim_sigmas · σ, trim_min_fraction · level) are
//      dropped: entry and exit are ramps up into and down out of the full engagement, so they sit low.
//      Revolutions inside the plateau all count, high or low — runout and process scatter are part of
//      the measurement.
//   5. At least min_steady_revolutions must remain.
// The statistics (mean, sample standard deviation, min, max) are over the P_k that remain.
//
// Consistency with the log. Conditions that contradict the log are bad input: a spindle speed that
// differs from the log's (`# spindle_rpm:` metadata, or the median of the spindle_rpm column over the
// steady part) by more than rpm_tolerance; a feed that differs from the log's (median of the
// feed_mm_per_min column, and separately of the feed from positions, over the steady part) by more
// than feed_tolerance; a log whose `sample_rate_hz` metadata differs from the rate of its time column
// (1 / median step) by more than sample_rate_tolerance. To judge the feed the steady part is first
// found from the forces alone (steps 2–4 with every revolution eligible); step 1 is applied after.

#include <string>
#include <vector>

#include "feedplan/core/input_error.hpp"
#include "feedplan/geometry/tool.hpp"
#include "feedplan/model_db/cutting_test.hpp"
#include "feedplan/force_log/force_log.hpp"

namespace feedplan::model_db {

//! Tolerances and the steady-state rule's parameters (see the file comment).
struct CuttingTestImportOptions {
  //! Names the log in messages and becomes CuttingTestRecord::source; empty: "force log" (the path
  //! overload uses the path).
  std::string source_name;
  double rpm_tolerance = 0.01;          //!< allowed |S_given − S_log| / S_log, fraction
  double feed_tolerance = 0.02;         //!< allowed |F_given − F_log| / F_log, fraction
  double sample_rate_tolerance = 0.01;  //!< allowed |rate_meta − rate_time| / rate_time, fraction
  int min_steady_revolutions = 8;       //!< fewest steady revolutions a test needs, ≥ 1
  int trend_window_revolutions = 5;     //!< running-median window of the trend, revolutions, odd ≥ 1
  double loaded_fraction = 0.5;         //!< trend share of its maximum that counts as cutting, in (0, 1)
  double plateau_tolerance = 0.2;       //!< allowed |trend − level| / level on the plateau, in (0, 1)
  double trim_sigmas = 2.0;             //!< end trimming threshold in robust standard deviations, ≥ 0
  double trim_min_fraction = 0.01;      //!< smallest end trimming threshold, fraction of level, in [0, 1)
};

//! Problems with the conditions and the tool: every number finite, spindle speed, feed, axial depth and
//! tool diameter > 0, flutes ≥ 1, helix in [0, 90) deg, radial depth in (0, D], and slot mode exactly when
//! a_e = D (up to 1e-9 relative). Fields are "conditions.spindle_rpm", "conditions.radial_depth_mm",
//! "conditions.mode", "tool.diameter_mm", … Empty when all is well.
std::vector<InputProblem> validate(const CuttingTestConditions& conditions, const geometry::Tool& tool);

//! Problems with the options (fields "options.feed_tolerance", …); empty when all is well.
std::vector<InputProblem> validate(const CuttingTestImportOptions& options);

//! Imports a cutting test from its force log. Needs a log with forces (has_forces), a tool and
//! conditions that pass validate() and agree with the log (file comment), and at least
//! options.min_steady_revolutions steady revolutions.
//!
//! Returns the record: the conditions; f_z = F / (N · S); α_en from the straight-cut closed form
//! (geometry::straight_engagement_rad, π for a slot); t_m = f_z · sin(min(α_en, π/2)); L = r · α_en
//! (docs/method.md §5.1); the steady peaks with their mean, sample standard deviation (0 for one), min and max;
//! the complete and the steady revolution counts; and notes saying which revolutions were used, how the
//! feed and spindle speed were checked (or why not) and whether the peaks scatter much.
//!
//! Throws feedplan::InputError listing every problem: the validate() problems; then the log's
//! contradictions and its lack of forces (fields name the condition, e.g. "conditions.spindle_rpm", or
//! the log, e.g. "<source> sample_rate_hz"); then too few steady revolutions (field <source>, saying how
//! many were found and needed).
CuttingTestRecord import_cutting_test(const force_log::ForceLog& log, const CuttingTestConditions& conditions,
                                      const geometry::Tool& tool, const CuttingTestImportOptions& options = {});

//! The same for the log file at `log_path` (force_log::load_force_log: our CSV or a Kistler DynoWare export).
//! The reader's InputError (missing file, missing columns, a truncated row, time that does not increase —
//! each naming the file and line) reaches the caller unchanged. Messages and the record's source name
//! the path unless options.source_name is set.
CuttingTestRecord import_cutting_test(const std::string& log_path, const CuttingTestConditions& conditions,
                                      const geometry::Tool& tool, const CuttingTestImportOptions& options = {});

}  // namespace feedplan::model_db
