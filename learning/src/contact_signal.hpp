#pragma once
// When the tool touches the stock by the measured force (log_alignment.hpp, "Why contact"): |F_xy| per
// row, its peak envelope over one spindle revolution, and 1 where that exceeds a tenth of its maximum.
// Internal to learning.

#include <vector>

#include "feedplan/force_log/force_log.hpp"
#include "feedplan/planner/feed_plan.hpp"

namespace feedplan::learning::detail {

//! |F_xy| = √(Fx² + Fy²) per row; NaN where a force is NaN.
std::vector<double> force_xy(const force_log::ForceLog& log);

//! Spindle speed for smoothing over one revolution: the log's column, its metadata, else the program's
//! largest S, rpm (0 when none is known).
double spindle_rpm_for(const force_log::ForceLog& log, const planner::PlanResult& plan);

//! Bins of `bin_s` in one revolution at `rpm`, made odd for a centred window; 1 without a speed.
int revolution_bins(double rpm, double bin_s);

//! 1 where the measured peak envelope (running maximum over `width` bins) exceeds 3 % of its maximum
//! (the 99.9th percentile, so single spikes do not set it) and `noise_level_n`, 0 elsewhere, NaN without data.
std::vector<double> in_contact(const std::vector<double>& force_bins, int width, double noise_level_n = 0.0);

//! in_contact for a peak envelope already taken (moving_max of the force bins over one revolution).
std::vector<double> contact_of_envelope(std::vector<double> envelope, double noise_level_n);

//! The level a peak `envelope` (running maximum over `width` bins) stays under where only noise is read:
//! kNoiseEnvelopeMargin × its 99.5th percentile over the bins where `in_air` is 1 — 0 when fewer than 4
//! revolutions' worth of such bins (no estimate: the contact threshold is its share of the maximum alone).
double noise_envelope_n(const std::vector<double>& envelope, int width, const std::vector<double>& in_air);

}  // namespace feedplan::learning::detail
