#pragma once
// Per-revolution peak forces of an aligned log paired with the force model's inputs where and at the feed
// they were measured (docs/method.md §5.3–5.4): the samples the RLS and the batch refit learn from, and the
// revolutions compare_peaks judges a plan by.
//
// Step by step:
//   1. Revolution windows by time at the given spindle speed, counted from the first row: revolution k
//      covers [t0 + k T, t0 + (k + 1) T), T = 60 / rpm — force_log::revolution_peaks, with NaN forces read as 0
//      there. Only complete windows; a window with a NaN force or with fewer than half the rows it should
//      hold (a gap) is skipped (skipped_nan).
//   2. Place: the force of a row at time t was measured where the tool was at t − delay_s (the
//      alignment's estimated force lag). The window's span s_start..s_end and the place of its peak are
//      the alignment's s at those shifted times, interpolated between rows. A window with any row
//      unaligned over its shifted span is skipped (skipped_not_aligned) — so is one shifted past the log.
//   3. Model inputs at the peak's place (the planned sample nearest to it): chip factor, XY speed ratio
//      (from the planned positions around it), contact length and axial depth. The feed is the one
//      actually run: the log's feed_mm_per_min at the shifted peak time when present and finite, else
//      ds/dt over the window. t_m = planner::chip_thickness_mm, L = planner::model_contact_length_mm
//      (evaluated as the planner evaluates the model), force = peak / planner::axial_depth_ratio (on the
//      model's axial depth) unless disabled — and / the sensor's peak gain there when given
//      (MeasuredRevolutionOptions::sensor_peak_gain; the revolutions' raw peaks stay as read).
//   4. A revolution becomes a LearningSample when the plan has it engaged at the peak's place with at
//      least min_engagement_rad and a chip (chip factor × XY ratio ≥ planner::kMinChipFactor) and a
//      positive feed; otherwise skipped_not_engaged. Every aligned revolution (engaged or not) is in
//      `revolutions` with its raw peak, for planner::compare_peaks.
//   5. Tooth periods: steps 1–4 on windows of 1/Z turn give `tooth_periods` — Z places per revolution
//      instead of one, for learning along the path where the force changes within a revolution
//      (entries). The windows start at the row that puts the force peaks in their middle (the peaks'
//      force-weighted circular mean phase), so that a window boundary never splits a tooth's peak;
//      window k belongs to flute window k mod Z and to turn k / Z. With runout one flute cuts more
//      than the others and the revolution's peak is that flute's, so each tooth period carries the
//      factor its peak is short of the turn's largest by: per flute window, the median of (largest /
//      own peak) over the 5 steady turns nearest to it (all Z windows engaged, the largest peak within
//      2 % of the turn before's) — 1 up to noise without runout. Local, not one per log, because the
//      runout's share changes with the feed per tooth, and because the flute whose peak a window holds
//      changes where the cutting direction turns the force (measured on a corner with 8 µm runout: one
//      factor per log was 5–8 % off on the second wall).
//   6. Noise: its spread out of the cut and how far it raises the tooth periods' peak readings
//      (peak_noise_bias.hpp); the peaks are given as read, the excess beside them.

#include <string>
#include <vector>

#include "feedplan/learning/learning_sample.hpp"
#include "feedplan/learning/log_alignment.hpp"
#include "feedplan/learning/peak_noise_bias.hpp"
#include "feedplan/model/response_surface_model.hpp"
#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/planner/peak_comparison.hpp"
#include "feedplan/force_log/force_log.hpp"

namespace feedplan::learning {

//! Which revolutions count and how forces are scaled.
struct MeasuredRevolutionOptions {
  double min_engagement_rad = 0.05;        //!< smaller planned engagement at the peak's place: not engaged, rad (≥ 0)
  //! Divide forces by the factor the planner puts on the straight-cut model there (planner::
  //! force_transfer_factor: the axial-depth scaling or the chip-load transfer, whichever binds)
  bool transfer_to_model = true;
  //! Per plan sample: the factor the force sensor's own dynamics put on a peak read there
  //! (sensor_dynamics.hpp); each window's peak is divided by the one at its peak's place. Empty: none.
  std::vector<double> sensor_peak_gain;
};

//! One tooth period's peak (step 5).
struct ToothPeriodPeak {
  long window = 0;          //!< tooth-period number counted from the log's first row (flute window: window mod Z)
  double s_start_mm = 0.0;  //!< path span of the period (after the delay shift), mm
  double s_end_mm = 0.0;    //!< see s_start_mm
  double s_peak_mm = 0.0;   //!< where its peak was measured, mm
  double t_peak_s = 0.0;    //!< when, on the log's clock (before the delay shift), s
  LearningSample sample;    //!< model inputs at the peak's place and the period's peak (scaled as the revolutions')
  double runout_factor = 1.0;  //!< the peak × this stands for the revolution's peak (step 5), ≥ 1
};

//! The revolutions of one log.
struct MeasuredRevolutions {
  std::vector<LearningSample> samples;                   //!< engaged, fully aligned revolutions, in time order
  std::vector<planner::MeasuredRevolution> revolutions;  //!< every aligned revolution: s span and raw peak, N
  //! For each entry of `samples`, the time its revolution starts on the log's clock, s.
  std::vector<double> sample_t_start_s;
  std::vector<ToothPeriodPeak> tooth_periods;  //!< engaged, fully aligned tooth periods, in time order
  PeakNoise noise;  //!< the sensor noise out of the cut and how far it raises the tooth periods' peaks (step 6)
  int flutes = 0;   //!< Z: tooth periods per turn
  int skipped_not_engaged = 0;  //!< aligned revolutions the plan has out of the material (or without a chip or feed)
  int skipped_nan = 0;          //!< revolutions with a NaN force or a gap in the rows
  int skipped_not_aligned = 0;  //!< revolutions with a row off the path, before or after it (after the delay shift)
  std::string message;          //!< counts and reasons, for people
};

//! Extracts the per-revolution samples of `log` (aligned by `alignment`, which must come from align_log
//! on the same log and `plan`, asserted by size) with the rule at the top of this file. `model` gives the
//! contact-length floor and the axial depth scale; `flutes` and `spindle_rpm` the tool and the speed the
//! log was cut at. Throws InputError when flutes < 1, the spindle speed is not finite and > 0, the log
//! has no forces, or the options are out of range. An alignment that is not usable (usable(status)
//! false) gives no samples and says so in the message.
MeasuredRevolutions measured_revolutions(const force_log::ForceLog& log, const Alignment& alignment,
                                         const planner::PlanResult& plan, const model::ResponseSurfaceModel& model,
                                         int flutes, double spindle_rpm, const MeasuredRevolutionOptions& options = {});

}  // namespace feedplan::learning
