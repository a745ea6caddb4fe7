#pragma once
// Where on the planned path each row of a force log was measured (docs/method.md §2 learning, §4 force log):
// the arc length s of the plan for every log row, so measured forces can be paired with the model's
// inputs there (measured_revolutions.hpp).
//
// Two methods:
//   1. Positions (our CSV format, the virtual machine's logs): each row's logged tool position is matched
//      to the planned path (the polyline through PlannedSample::position, projected onto the segment
//      between neighbouring samples for a sub-sample s). Progress is monotonic: a row is matched to the
//      first stretch of the path, at or after the previous match (less a small tolerance for position
//      noise), that comes within AlignmentOptions::max_distance_mm, and there to the nearest point. So a
//      path that crosses itself (trochoid loops, a return over the cut at another height) is followed in
//      order. XY and Z are compared when the row has z_mm, XY only otherwise. Rows before the first match
//      are the machine before the program (not aligned, NaN, not off the path) when that match is at the
//      path's start — the machine arrives there; otherwise the log started after the path start and such
//      rows left the path. The same for rows after the last match and the path's end. Every other row
//      farther than max_distance_mm from the path is off the path; too many → kNotThisProgram.
//   2. Time profile (Kistler DynoWare exports: no positions): the log's contact signal (below) is
//      cross-correlated with the plan's engagement over the plan's predicted time (PlannedSample::time_s)
//      to find when the program started on the log's clock; then s(t) is the plan's time → s. Only as good
//      as the plan's timing prediction (the controller model against the real machine): typically a few mm.
//
// Force delay (positions only): the force signal may lag the positions (filters, a separate acquisition).
// The measured contact signal is cross-correlated with the plan's engagement at each row's place (through
// the alignment) over lags in [−max_delay_s, max_delay_s]; delay_s is the lag of the best correlation (the
// middle of a flat top). The alignment itself is not shifted: the force of row i belongs to the place of
// time t_i − delay_s (measured_revolutions applies this). A best correlation under 0.5 is said and not
// applied (delay_s stays 0): a lag the two contact signals hardly agree on moves every entry's force along
// the path by its size.
//
// Why contact and not the predicted force: the model is what learning corrects, so its force shape is
// the least trustworthy thing here (a plan holds it flat at the target while the real peak rises over the
// entry); where the tool touches the stock is geometry, which the plan and the machine share. Contact:
// the peak envelope of |F_xy| (running maximum over one spindle revolution, centred; the speed from the
// log's spindle_rpm column, else its metadata, else the program's S) above 3 % of its maximum;
// engagement: PlannedSample::engaged under the same running maximum, so both edges move alike.
// Accuracy on the virtual machine: the measured edge is where the force passes 3 % of its peak, the
// planned one where the tool first touches, so the estimate is late by about half the difference of the
// force's rise times at the entry and at the exit: under 2 ms over a corner cycle entered at 11 mm/s
// (at 10 % it was 6–10 ms there: the force passed 10 % 0.11 mm after the first touch); about 5 ms when
// only the entry is logged. Where the noise's envelope reaches 3 % of the peak (a 7.6 N dynamometer on peaks
// of 360 N, bins of 0.9 ms: the air before a corner's entry read as contact in places, and the delay came
// out −19.6 ms where the virtual machine has none), the threshold is the noise's instead: 1.25 × the 99.5th
// percentile of the envelope where the plan has the tool in the air for max_delay_s either side — there
// the corner's estimate is −3.3 ms. No such air (a log that starts in the cut, a trochoid whose loops are
// shorter than that): 3 % alone. A threshold above the noise is passed later at a gradual entry, so the
// estimate comes out late by a few milliseconds (20 N of noise per axis on the corner above: +3 to +6 ms);
// a fixed higher share instead (raised for every log) biased a spiral's delay by −13 ms. A log that reads
// as much force in the air as in the cut gets no delay, and says so.

#include <string>
#include <vector>

#include "feedplan/planner/feed_plan.hpp"
#include "feedplan/force_log/force_log.hpp"

namespace feedplan::learning {

//! How a log is aligned with a plan.
struct AlignmentOptions {
  double max_distance_mm = 0.5;  //!< a logged position farther than this from the path is off the path, mm (> 0)
  //! Larger share of off-path rows (of those that should follow the path) → not this program, in [0, 1].
  double max_off_path_fraction = 0.02;
  bool estimate_delay = true;  //!< estimate the force signal's lag behind the positions
  double max_delay_s = 0.5;    //!< largest |delay| searched, s (≥ 0)
};

//! How the rows were placed on the path.
enum class AlignmentMethod {
  kPositions,    //!< logged positions matched to the planned path
  kTimeProfile,  //!< no positions: the plan's predicted time profile, offset by cross-correlating forces
};

//! "positions", "time profile".
std::string to_string(AlignmentMethod method);

//! Outcome of an alignment.
enum class AlignmentStatus {
  kOk,              //!< the log covers the whole in-cut part of the path
  kNotThisProgram,  //!< the positions do not follow the path (s_mm all NaN)
  //! No aligned row lies in the in-cut part of the path (or the plan has none; or, by time profile, the
  //! force never changes between air and contact).
  kNoCut,
  kTruncated,       //!< the log covers only part of the in-cut path: usable for that part (covered_fraction)
  kUnitsLookWrong,  //!< the positions fit the path after ×25.4 (inches) or ÷25.4: convert the log (s_mm all NaN)
};

//! "ok", "not this program", "no cut", "truncated", "units look wrong".
std::string to_string(AlignmentStatus status);

//! True when `status` leaves aligned rows to learn from (kOk or kTruncated).
bool usable(AlignmentStatus status);

//! Each log row's place on the planned path.
struct Alignment {
  AlignmentStatus status = AlignmentStatus::kOk;  //!< outcome
  std::string message;  //!< what was done and found, for people (method, coverage, delay, problems)
  AlignmentMethod method = AlignmentMethod::kPositions;  //!< how
  std::vector<double> s_mm;        //!< per log row: arc length on the plan's path, mm; NaN where not aligned
  double delay_s = 0.0;            //!< estimated lag of the force signal behind the positions, s (0 when not estimated)
  double delay_correlation = 0.0;  //!< correlation coefficient at delay_s (0 when not estimated), in [−1, 1]
  int rows = 0;                    //!< rows in the log
  int rows_aligned = 0;            //!< rows with a finite s_mm
  //! Rows with a NaN position (when the log has positions) or force (when it has forces): skipped.
  int rows_with_nan = 0;
  int rows_off_path = 0;          //!< rows off the path (not counting those before or after the program)
  int gaps = 0;                   //!< time steps longer than 3 × the median step
  double covered_fraction = 0.0;  //!< share of the in-cut path length the aligned rows cover, in [0, 1]
};

//! Aligns `log` with `plan` (the method at the top of this file; positions when log.has_positions, else
//! the time profile). Needs a plan with samples and a log with rows in strictly increasing time (what
//! force_log::read_force_log guarantees; asserted). Throws InputError when the options are out of range, or the
//! log has neither positions nor forces (nothing to align by). Every other outcome — another program,
//! inches, no cut, a truncated log — is a status with a message naming rows, times and distances.
Alignment align_log(const force_log::ForceLog& log, const planner::PlanResult& plan, const AlignmentOptions& options = {});

}  // namespace feedplan::learning
